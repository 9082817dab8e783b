// The book's Table 5.1 layout: book columns in the book's order filled by
// formulation (or "not available"), then the other runs by label.

#include <esif/compare/BookTable.h>

#include <gtest/gtest.h>
#include <sstream>

namespace
{
esif::Stats run(const std::string& label, const std::string& formulation, std::optional<long long> nnz,
				long long features, long long poses, long long dim)
{
	esif::Stats s;
	s.set("label", esif::StatValue(label));
	if (!formulation.empty()) s.set("formulation", esif::StatValue(formulation));
	s.set("landmarks", esif::StatValue(features));
	if (poses >= 0) s.set("poses_in_state", esif::StatValue(poses));
	s.set("state_dim", esif::StatValue(dim));
	s.set("info_nnz", nnz ? esif::StatValue(*nnz) : esif::StatValue(nullptr));
	return s;
}

std::vector<std::string> lines(const std::string& text)
{
	std::vector<std::string> out;
	std::istringstream in(text);
	for (std::string l; std::getline(in, l);) out.push_back(l);
	return out;
}

/// EKF first, then D-SLAM, full SLAM, a second D-SLAM and an old stats.json without formulation.
std::vector<esif::Stats> fiveRuns()
{
	return {
		run("ekf", "ekf_slam", std::nullopt, 196, 1, 395),
		run("dslam", "dslam", 12345, 196, 0, 392),
		run("ceres", "full_slam", 1234567, 196, 3000, 9392),
		run("dslam2", "dslam", 999, 190, 0, 380),
		run("old", "", std::nullopt, 10, -1, 23),
	};
}

TEST(BookTable, TextLayout)
{
	const auto text = esif::bookTable51Text(fiveRuns());
	const auto l = lines(text);
	ASSERT_EQ(l.size(), 6u) << text;
	EXPECT_EQ(l[0], "Table 5.1 layout: performance of exactly sparse information filters");
	// Book columns in the book's order, then the runs left over, in their order.
	const std::vector<std::string> headings = {
		"full SLAM", "D-SLAM", "D-SLAM local map joining filter", "SLSJF", "ekf", "dslam2", "old"};
	std::size_t at = 0;
	for (const auto& h : headings)
	{
		const auto found = l[1].find(h, at);
		ASSERT_NE(found, std::string::npos) << h << " in " << l[1];
		at = found + h.size();
	}
	EXPECT_EQ(l[2].rfind("Number of non-zeros", 0), 0u);
	EXPECT_EQ(l[3].rfind("Number of features", 0), 0u);
	EXPECT_EQ(l[4].rfind("Number of poses", 0), 0u);
	EXPECT_EQ(l[5].rfind("State dimension", 0), 0u);
	// Every line of the table as wide as the header: aligned columns.
	for (std::size_t i = 2; i < l.size(); ++i) EXPECT_EQ(l[i].size(), l[1].size()) << l[i];
	// Cells right-aligned under their headings: the first number ends where "full SLAM" ends.
	const auto full_end = l[1].find("full SLAM") + std::string("full SLAM").size();
	EXPECT_EQ(l[2].substr(full_end - 9, 9), "1,234,567") << text;
	EXPECT_EQ(l[4].substr(full_end - 5, 5), "3,000") << text;
	// Only the first D-SLAM run fills the book column; the second has its own.
	const auto dslam_end = l[1].find("D-SLAM ") + std::string("D-SLAM").size();
	EXPECT_EQ(l[2].substr(dslam_end - 6, 6), "12,345") << text;
	const auto dslam2_end = l[1].find("dslam2") + std::string("dslam2").size();
	EXPECT_EQ(l[2].substr(dslam2_end - 3, 3), "999") << text;
	EXPECT_EQ(l[3].substr(dslam2_end - 3, 3), "190") << text;
}

TEST(BookTable, MissingFiguresAndColumns)
{
	const auto l = lines(esif::bookTable51Text(fiveRuns()));
	// LMJF and SLSJF have no run: "not available" in every row, twice.
	for (std::size_t i = 2; i < l.size(); ++i)
	{
		const auto first = l[i].find("not available");
		ASSERT_NE(first, std::string::npos) << l[i];
		EXPECT_NE(l[i].find("not available", first + 1), std::string::npos) << l[i];
	}
	// Null info_nnz (covariance filters) and a missing key (old stats) are "-".
	const auto ekf_end = l[1].find(" ekf") + 4;
	EXPECT_EQ(l[2].substr(ekf_end - 1, 1), "-") << l[2];
	EXPECT_EQ(l[4].back(), '-') << "old stats.json without poses_in_state: " << l[4];
	EXPECT_EQ(l[2].back(), '-') << l[2];
}

TEST(BookTable, Markdown)
{
	const auto md = esif::bookTable51Markdown(fiveRuns());
	EXPECT_EQ(md.rfind("## Table 5.1 layout: performance of exactly sparse information filters\n\n", 0), 0u) << md;
	EXPECT_NE(md.find("| | full SLAM | D-SLAM | D-SLAM local map joining filter | SLSJF | ekf | dslam2 | old |\n"
					  "|---|---:|---:|---:|---:|---:|---:|---:|\n"),
			  std::string::npos)
		<< md;
	EXPECT_NE(md.find("| Number of poses | 3,000 | 0 | not available | not available | 1 | 0 | - |\n"), std::string::npos)
		<< md;
	EXPECT_NE(md.find("| Number of non-zeros | 1,234,567 | 12,345 | not available | not available | - | 999 | - |\n"),
			  std::string::npos)
		<< md;
}

TEST(BookTable, NoRunsLeavesOnlyBookColumns)
{
	const auto l = lines(esif::bookTable51Text({}));
	ASSERT_EQ(l.size(), 6u);
	EXPECT_EQ(l[5].find("State dimension"), 0u);
	std::size_t count = 0;
	for (auto at = l[5].find("not available"); at != std::string::npos; at = l[5].find("not available", at + 1))
		++count;
	EXPECT_EQ(count, 4u) << l[5];
}

}  // namespace
