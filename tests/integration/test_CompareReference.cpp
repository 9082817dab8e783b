// `esif compare --reference LABEL` as a user runs it: EKF and D-SLAM on a
// small simulated rawlog, each run's difference from the reference in
// comparison.csv / .md and the printed table, and a one-line error for a
// label that is not one of the runs; a run that associates on its own
// paired with the reference through the true landmarks, as `esif run
// --reference-run` pairs it too.

#include <EsifTestSupport.h>

#include <esif/eval/RunDifference.h>
#include <esif/formats/RunOutputReader.h>

#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

namespace
{
using esif::test::runEsif;
using esif::test::sourcePath;
using esif::test::TempDir;

/// comparison.csv as label -> (column -> text).
std::map<std::string, std::map<std::string, std::string>> readCsv(const std::string& path)
{
	std::map<std::string, std::map<std::string, std::string>> rows;
	for (auto& row : esif::test::readCsvRows(path)) rows[row["label"]] = std::move(row);
	return rows;
}

double number(const std::map<std::string, std::string>& row, const std::string& key)
{
	const auto it = row.find(key);
	if (it == row.end() || it->second.empty()) return std::nan("");
	return std::stod(it->second);
}

/// One small rawlog (configs/sim/small.ini, 200 steps), the EKF and D-SLAM
/// (different filters, so different estimates), shared by the tests.
class CompareReference : public ::testing::Test
{
   protected:
	static void SetUpTestSuite()
	{
		dir_ = std::make_unique<TempDir>();
		const auto r = esif::test::simulateSmall(dir_->file("small.rawlog"));
		ASSERT_EQ(r.exit_code, 0) << r.out;
		std::ofstream(dir_->file("dslam.ini")) << "[esif]\nplugin = Dslam\nlabel = dslam\n[dslam]\nassociation = known_ids\n";
	}
	static void TearDownTestSuite() { dir_.reset(); }

	static std::string compareArgs(const std::string& out, const std::string& extra)
	{
		return "compare --configs '" + sourcePath("configs/ekf.ini") + "," + dir_->file("dslam.ini") +
			   "' --rawlog '" + dir_->file("small.rawlog") + "' --out '" + dir_->file(out) + "' " + extra;
	}

	static std::unique_ptr<TempDir> dir_;
};
std::unique_ptr<TempDir> CompareReference::dir_;

TEST_F(CompareReference, AddsDifferenceColumns)
{
	const auto r = runEsif(compareArgs("cmp", "--reference ekf"));
	ASSERT_EQ(r.exit_code, 0) << r.out;
	for (const auto& k : esif::runDifferenceKeys()) EXPECT_NE(r.out.find(k), std::string::npos) << k << "\n" << r.out;

	const auto rows = readCsv(dir_->file("cmp/comparison.csv"));
	ASSERT_EQ(rows.size(), 2u);
	ASSERT_TRUE(rows.count("ekf") && rows.count("dslam"));
	const auto& ref = rows.at("ekf");
	const auto& other = rows.at("dslam");
	for (const char* k :
		 {"ref_traj_rms_m", "ref_traj_max_m", "ref_heading_rms_deg", "ref_landmark_rms_m", "ref_landmark_max_m"})
	{
		EXPECT_EQ(number(ref, k), 0.0) << k;
		EXPECT_TRUE(std::isfinite(number(other, k))) << k;
		EXPECT_GT(number(other, k), 0.0) << k;  // another noise model gives another estimate
	}
	EXPECT_LE(number(other, "ref_traj_rms_m"), number(other, "ref_traj_max_m"));
	EXPECT_LE(number(other, "ref_landmark_rms_m"), number(other, "ref_landmark_max_m"));
	EXPECT_LT(number(other, "ref_traj_max_m"), 2.0);  // same data, same IDs: close, not diverged
	// The reference's row shows its own landmark count; both runs map the same landmarks (known IDs).
	EXPECT_EQ(number(ref, "ref_landmarks_matched"), number(ref, "landmarks"));
	EXPECT_GT(number(ref, "landmarks"), 0.0);
	EXPECT_EQ(number(other, "ref_landmarks_matched"), number(ref, "landmarks"));

	std::ifstream md(dir_->file("cmp/comparison.md"));
	std::stringstream text;
	text << md.rdbuf();
	for (const auto& k : esif::runDifferenceKeys())
		EXPECT_NE(text.str().find("| " + k + " |"), std::string::npos) << k;
	EXPECT_NE(text.str().find("difference from run 'ekf'"), std::string::npos) << text.str();
	// Same data, same IDs: no rotation to speak of between the two maps.
	EXPECT_LT(std::abs(number(other, "ref_rotation_deg")), 1.0);
	EXPECT_LE(number(other, "ref_landmark_rms_aligned_m"), number(other, "ref_landmark_rms_m") + 1e-9);
	EXPECT_TRUE(std::filesystem::exists(dir_->file("cmp/maps_overlay.png")));

	// D-SLAM holds an information matrix: its whole-state test is computed
	// against the reference run, as `esif run --reference-run` computes it,
	// which is named by the folder it has once the comparison is in place.
	const auto dslam = esif::Stats::load(dir_->file("cmp/dslam/stats.json"));
	EXPECT_EQ(dslam.text("state_nees_reference").value_or(""), dir_->file("cmp/ekf"));
	EXPECT_GT(esif::test::statNumber(dslam, "state_nees_dof"), 0);
	EXPECT_TRUE(std::isfinite(esif::test::statNumber(dslam, "state_nees")));
	EXPECT_TRUE(std::isfinite(number(other, "state_nees")));
}

TEST_F(CompareReference, WithoutReferenceNoColumns)
{
	const auto r = runEsif(compareArgs("plain", ""));
	ASSERT_EQ(r.exit_code, 0) << r.out;
	EXPECT_FALSE(std::filesystem::exists(dir_->file("plain/maps_overlay.png")));
	EXPECT_EQ(r.out.find("ref_"), std::string::npos) << r.out;
	std::ifstream csv(dir_->file("plain/comparison.csv"));
	std::string header;
	std::getline(csv, header);
	EXPECT_EQ(header.find("ref_"), std::string::npos) << header;
}

TEST_F(CompareReference, UnknownLabelIsOneLineErrorBeforeAnyRun)
{
	const auto r = runEsif(compareArgs("bad", "--reference nope"));
	EXPECT_EQ(r.exit_code, 1) << r.out;
	EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
	EXPECT_NE(r.out.find("esif: error: esif compare: --reference 'nope': not the label of a compared run "
						 "(labels: ekf, dslam)"),
			  std::string::npos)
		<< r.out;
	EXPECT_FALSE(std::filesystem::exists(dir_->file("bad")));

	// Two configs of one label: ambiguous unless a run folder is named.
	for (const char* name : {"s1.ini", "s2.ini"})
		std::ofstream(dir_->file(name)) << "[esif]\nplugin = EkfSlam\nlabel = same\n";
	const auto twice = runEsif(
		"compare --configs '" + dir_->file("s1.ini") + "," + dir_->file("s2.ini") + "' --rawlog '" +
		dir_->file("small.rawlog") + "' --out '" + dir_->file("bad") + "' --reference same");
	EXPECT_EQ(twice.exit_code, 1) << twice.out;
	EXPECT_EQ(std::count(twice.out.begin(), twice.out.end(), '\n'), 1) << twice.out;
	EXPECT_NE(twice.out.find("several runs have this label"), std::string::npos) << twice.out;
	EXPECT_NE(twice.out.find("run folders (s1, s2)"), std::string::npos) << twice.out;
	EXPECT_FALSE(std::filesystem::exists(dir_->file("bad")));
}

TEST_F(CompareReference, RunFolderNameAlsoNamesTheReference)
{
	// configs/ekf.ini under another label: its run folder is "renamed", its label "other_name".
	std::ifstream ekf(sourcePath("configs/ekf.ini"));
	std::stringstream text;
	text << ekf.rdbuf();
	std::string ini = text.str();
	const auto at = ini.find("label  = ekf\n");
	ASSERT_NE(at, std::string::npos) << ini;
	ini.replace(at, std::string("label  = ekf\n").size(), "label = other_name\n");
	std::ofstream(dir_->file("renamed.ini")) << ini;
	const auto r = runEsif(
		"compare --configs '" + sourcePath("configs/ekf.ini") + "," + dir_->file("renamed.ini") + "' --rawlog '" +
		dir_->file("small.rawlog") + "' --out '" + dir_->file("byfolder") + "' --reference renamed");
	ASSERT_EQ(r.exit_code, 0) << r.out;
	const auto rows = readCsv(dir_->file("byfolder/comparison.csv"));
	ASSERT_TRUE(rows.count("other_name")) << r.out;
	EXPECT_EQ(number(rows.at("other_name"), "ref_traj_max_m"), 0.0);
	// Same filter, same data: the same estimate.
	EXPECT_NEAR(number(rows.at("ekf"), "ref_traj_max_m"), 0.0, 1e-9);
}

/// The EKF with the IDs as the reference, the EKF with JCBB (IDs hidden,
/// its landmarks numbered by itself in the order it made them) as the run:
/// their landmarks are paired through the true landmark each stands for.
TEST_F(CompareReference, PairsThroughTrueLandmarksNotNumbers)
{
	const auto r = runEsif(
		"compare --configs '" + sourcePath("configs/ekf.ini") + "," + sourcePath("configs/ekf_jcbb.ini") +
		"' --rawlog '" + dir_->file("small.rawlog") + "' --out '" + dir_->file("jcbb") + "' --reference ekf");
	ASSERT_EQ(r.exit_code, 0) << r.out;
	const auto rows = readCsv(dir_->file("jcbb/comparison.csv"));
	ASSERT_TRUE(rows.count("ekf_jcbb")) << r.out;
	const auto& jcbb = rows.at("ekf_jcbb");
	EXPECT_EQ(jcbb.at("ref_landmarks_paired_by"), "true landmark");
	EXPECT_EQ(rows.at("ekf").at("ref_landmarks_paired_by"), "itself");
	EXPECT_EQ(number(jcbb, "ref_landmarks_matched"), number(jcbb, "landmarks_found"));
	EXPECT_EQ(number(jcbb, "landmarks_found"), number(jcbb, "landmarks_true"));
	// Two EKFs on the same data differ by centimetres (each is within about
	// 0.1 m of the truth here: landmark_ospa_m).
	EXPECT_LT(number(jcbb, "ref_landmark_rms_m"), 0.1);
	EXPECT_LT(number(jcbb, "ref_ospa_m"), number(jcbb, "ospa_c_m"));

	// The numbers alone would have paired other landmarks: the run numbers
	// some landmark differently from the true landmark it stands for, and
	// pairing by number puts landmarks metres apart.
	const auto run = esif::readRunOutputs(dir_->file("jcbb/ekf_jcbb"));
	const auto ref = esif::readRunOutputs(dir_->file("jcbb/ekf"));
	ASSERT_TRUE(run.identities && run.identities->truth);
	EXPECT_TRUE(std::any_of(run.identities->landmarks.begin(), run.identities->landmarks.end(),
							[](const esif::LandmarkIdentity& l) { return l.true_id != l.landmark; }));
	double by_number_sq = 0;
	std::size_t by_number = 0;
	for (const auto& a : run.landmarks)
		for (const auto& b : ref.landmarks)
			if (a.id == b.id) by_number_sq += (a.mean - b.mean).squaredNorm(), ++by_number;
	ASSERT_GT(by_number, 0u);
	EXPECT_GT(std::sqrt(by_number_sq / by_number), 1.0);

	// esif run --reference-run measures the same run the same way.
	const auto again = runEsif(
		"run -q --config '" + sourcePath("configs/ekf_jcbb.ini") + "' --rawlog '" + dir_->file("small.rawlog") +
		"' --reference-run '" + dir_->file("jcbb/ekf") + "' --out '" + dir_->file("jcbb_run") + "'");
	ASSERT_EQ(again.exit_code, 0) << again.out;
	const auto stats = esif::Stats::load(dir_->file("jcbb_run/stats.json"));
	EXPECT_EQ(stats.text("ref_landmarks_paired_by"), std::string("true landmark"));
	EXPECT_NEAR(*stats.number("ref_landmark_rms_m"), number(jcbb, "ref_landmark_rms_m"), 1e-12);
	EXPECT_NEAR(*stats.number("ref_ospa_m"), number(jcbb, "ref_ospa_m"), 1e-12);
}

}  // namespace
