// `esif bench sparse` as a user runs it: the CSV it promises, and one-line
// errors for a bad command line.

#include <EsifTestSupport.h>

#include <gtest/gtest.h>
#include <sstream>
#include <vector>

namespace
{
using esif::test::runEsif;

TEST(BenchCommand, PrintsOneCsvRowPerMethodAndSize)
{
	const auto r = runEsif("bench sparse --features 40,60 --steps 5");
	ASSERT_EQ(r.exit_code, 0) << r.out;
	std::istringstream in(r.out);
	std::string line;
	std::vector<std::string> csv;
	while (std::getline(in, line))  // stderr is merged in: its lines are indented or prefixed
		if (line.rfind("  ", 0) != 0 && line.rfind("esif bench sparse:", 0) != 0) csv.push_back(line);
	ASSERT_FALSE(csv.empty()) << r.out;
	EXPECT_EQ(csv[0], "method,features,steps,us_per_step,factor_nnz,reorders");
	int rows = 0, dense = 0;
	for (std::size_t k = 1; k < csv.size(); ++k)
	{
		line = csv[k];
		++rows;
		EXPECT_EQ(std::count(line.begin(), line.end(), ','), 5) << line;
		if (line.rfind("dense_inverse,40,5,", 0) == 0) ++dense;
	}
	EXPECT_EQ(rows, 5 + 6);  // dense_inverse at the smallest size only
	EXPECT_EQ(dense, 1);
}

TEST(BenchCommand, BadArgumentsAreOneLineErrors)
{
	for (const std::string args :
		 {"bench nonsense", "bench sparse --methods cholesky", "bench sparse --features 12x", "bench sparse --steps 0"})
	{
		const auto r = runEsif(args);
		EXPECT_EQ(r.exit_code, 1) << args << ": " << r.out;
		EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << args << ": " << r.out;
		EXPECT_NE(r.out.find("esif: error: "), std::string::npos) << r.out;
	}
}

}  // namespace
