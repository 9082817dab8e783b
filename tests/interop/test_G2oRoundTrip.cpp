// `esif export g2o` and `esif import g2o` as a user runs them: the exported
// file holds every pose, landmark, odometry and measurement of the rawlog
// with positive definite information; a ceres_full run exported as initial
// values and imported back gives that run's trajectory and map to the
// precision written (shortest round-trip text, so exact but for the yaw's
// trip through trajectory.tum's quaternion); broken files are one line
// FILE:LINE: reason.

#include <EsifTestSupport.h>

#include <esif/formats/FullSlamProblem.h>
#include <esif/formats/RawlogReader.h>
#include <esif/formats/RunOutputReader.h>
#include <esif/models/Se2.h>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

namespace
{
using namespace esif;
using test::readText;
using test::runEsif;
using test::TempDir;

double parse(const std::string& t)
{
	double v = 0;
	std::from_chars(t.data(), t.data() + t.size(), v);
	return v;
}

/// The data lines of a g2o file, split into tokens, grouped by tag.
std::map<std::string, std::vector<std::vector<std::string>>> linesByTag(const std::string& path)
{
	std::map<std::string, std::vector<std::vector<std::string>>> out;
	std::istringstream in(readText(path));
	for (std::string line; std::getline(in, line);)
	{
		std::istringstream ss(line);
		std::vector<std::string> toks;
		for (std::string t; ss >> t;) toks.push_back(t);
		if (!toks.empty() && toks[0][0] != '#') out[toks[0]].push_back(toks);
	}
	return out;
}

/// The symmetric matrix whose upper triangle is toks[first..].
template <int N>
Eigen::Matrix<double, N, N> upperTriangle(const std::vector<std::string>& toks, std::size_t first)
{
	Eigen::Matrix<double, N, N> m;
	for (int r = 0; r < N; ++r)
		for (int c = r; c < N; ++c) m(r, c) = m(c, r) = parse(toks[first++]);
	return m;
}

class G2oRoundTrip : public ::testing::Test
{
   protected:
	static void SetUpTestSuite()
	{
		dir_ = std::make_unique<TempDir>();
		rawlog_ = dir_->file("small.rawlog");
		const auto sim = test::simulateSmall(rawlog_);
		ASSERT_EQ(sim.exit_code, 0) << sim.out;
		const auto run = runEsif("run -q --config '" + test::sourcePath("configs/ceres_full.ini") + "' --rawlog '" +
								 rawlog_ + "' --out '" + dir_->file("ceres") + "'");
		ASSERT_EQ(run.exit_code, 0) << run.out;
	}
	static void TearDownTestSuite() { dir_.reset(); }

	static std::unique_ptr<TempDir> dir_;
	static std::string rawlog_;
};
std::unique_ptr<TempDir> G2oRoundTrip::dir_;
std::string G2oRoundTrip::rawlog_;

TEST_F(G2oRoundTrip, ExportHoldsEveryPoseLandmarkAndFactorWithPositiveDefiniteInformation)
{
	const std::string g2o = dir_->file("dead_reckoning.g2o");
	const auto r = runEsif("export g2o --rawlog '" + rawlog_ + "' --out '" + g2o + "'");
	ASSERT_EQ(r.exit_code, 0) << r.out;

	// What the file must hold, counted from the rawlog itself: every step of
	// small.ini moves (step 0 by a zero increment whose covariance, 1e-10 as
	// MRPT stores it, is not the zero of a stand-still), so 200 steps make
	// 201 poses as in ceres_full; every measurement carries its landmark's ID.
	const Rawlog log = readRawlog(rawlog_);
	std::size_t moves = 0, measurements = 0;
	std::set<LandmarkId> ids;
	for (const auto& s : log.steps)
	{
		if (s.odometry && !isStandStill(*s.odometry)) ++moves;
		if (s.scan)
			for (const auto& m : s.scan->measurements)
			{
				++measurements;
				ids.insert(*m.id);
			}
	}
	ASSERT_EQ(moves, 200u);
	const std::size_t P = moves + 1;
	auto lines = linesByTag(g2o);
	EXPECT_EQ(lines.size(), 5u) << "tags: VERTEX_SE2 VERTEX_XY FIX EDGE_SE2 EDGE_SE2_XY";
	ASSERT_EQ(lines["VERTEX_SE2"].size(), P);
	ASSERT_EQ(lines["VERTEX_XY"].size(), ids.size());
	ASSERT_EQ(lines["EDGE_SE2"].size(), moves);
	ASSERT_EQ(lines["EDGE_SE2_XY"].size(), measurements);
	ASSERT_EQ(lines["FIX"].size(), 1u);
	EXPECT_EQ(lines["FIX"][0], (std::vector<std::string>{"FIX", "0"}));

	// Vertex IDs: poses 0..P-1 in order, landmarks P + ID.
	for (std::size_t i = 0; i < P; ++i) EXPECT_EQ(lines["VERTEX_SE2"][i][1], std::to_string(i));
	std::set<LandmarkId> exported;
	for (const auto& v : lines["VERTEX_XY"]) exported.insert(std::stoll(v[1]) - static_cast<LandmarkId>(P));
	EXPECT_EQ(exported, ids);

	// Dead reckoning: each pose vertex is the previous one composed with the
	// edge's increment, and the edge's information is the inverse of the
	// rawlog's odometry covariance seen from the increment's end (g2o's
	// EdgeSE2 error, G2oFormat.h): I J Q J^T = 1 to rounding times the
	// condition number of Q (x, y and heading variances span a few decades),
	// ~1e-12 measured, so 1e-9.
	std::size_t k = 0;
	for (const auto& s : log.steps)
	{
		if (!s.odometry || isStandStill(*s.odometry)) continue;
		const auto& e = lines["EDGE_SE2"][k];
		ASSERT_EQ(e.size(), 12u);
		EXPECT_EQ(e[1], std::to_string(k));
		EXPECT_EQ(e[2], std::to_string(k + 1));
		const Pose2 delta(parse(e[3]), parse(e[4]), parse(e[5]));
		EXPECT_EQ(delta, s.odometry->delta);
		const Eigen::Matrix3d info = upperTriangle<3>(e, 6);
		EXPECT_EQ(Eigen::LLT<Eigen::Matrix3d>(info).info(), Eigen::Success);
		Eigen::Matrix3d J = Eigen::Matrix3d::Identity();
		J.topLeftCorner<2, 2>() << std::cos(delta.z()), std::sin(delta.z()), -std::sin(delta.z()), std::cos(delta.z());
		EXPECT_LT((info * J * s.odometry->cov * J.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-9);
		const auto& from = lines["VERTEX_SE2"][k];
		const auto& to = lines["VERTEX_SE2"][k + 1];
		const Pose2 composed = compose(Pose2(parse(from[2]), parse(from[3]), parse(from[4])), delta);
		EXPECT_NEAR(parse(to[2]), composed.x(), 1e-12);
		EXPECT_NEAR(parse(to[3]), composed.y(), 1e-12);
		EXPECT_NEAR(std::remainder(parse(to[4]) - composed.z(), 2 * M_PI), 0.0, 1e-12);
		++k;
	}
	std::set<std::string> poses_seen;
	for (const auto& e : lines["EDGE_SE2_XY"])
	{
		ASSERT_EQ(e.size(), 8u);
		EXPECT_LT(std::stoul(e[1]), P);
		EXPECT_TRUE(exported.count(std::stoll(e[2]) - static_cast<LandmarkId>(P)));
		EXPECT_EQ(Eigen::LLT<Eigen::Matrix2d>(upperTriangle<2>(e, 5)).info(), Eigen::Success);
	}
}

TEST_F(G2oRoundTrip, CeresRunExportedAndImportedBackIsThatRun)
{
	const std::string g2o = dir_->file("ceres.g2o");
	const auto ex = runEsif(
		"export g2o --rawlog '" + rawlog_ + "' --associations-from '" + dir_->file("ceres") + "' --out '" + g2o + "'");
	ASSERT_EQ(ex.exit_code, 0) << ex.out;
	const auto im =
		runEsif("import g2o --g2o '" + g2o + "' --rawlog '" + rawlog_ + "' --out '" + dir_->file("imported") + "'");
	ASSERT_EQ(im.exit_code, 0) << im.out;
	EXPECT_NE(im.out.find("200 steps (201 poses)"), std::string::npos) << im.out;

	const RunOutputs run = readRunOutputs(dir_->file("ceres"));
	const RunOutputs back = readRunOutputs(dir_->file("imported"));
	ASSERT_EQ(back.trajectory.size(), run.trajectory.size());
	for (std::size_t k = 0; k < run.trajectory.size(); ++k)
	{
		EXPECT_EQ(back.trajectory[k].time_s, run.trajectory[k].time_s);
		EXPECT_EQ(back.trajectory[k].pose.x, run.trajectory[k].pose.x) << k;
		EXPECT_EQ(back.trajectory[k].pose.y, run.trajectory[k].pose.y) << k;
		// The yaw goes through a quaternion twice (trajectory.tum): a few ulps.
		EXPECT_NEAR(back.trajectory[k].pose.phi, run.trajectory[k].pose.phi, 1e-14) << k;
	}
	ASSERT_EQ(back.landmarks.size(), run.landmarks.size());
	std::map<LandmarkId, Eigen::Vector2d> by_id;
	for (const auto& l : run.landmarks) by_id[l.id] = l.mean;
	for (const auto& l : back.landmarks)
	{
		ASSERT_TRUE(by_id.count(l.id)) << l.id;
		EXPECT_EQ(l.mean, by_id[l.id]) << l.id;	 // x and y written as shortest round-trip text
		EXPECT_TRUE(std::isnan(l.cov(0, 0))) << "a g2o file has no marginals";
	}
}

TEST_F(G2oRoundTrip, BearingRangeFormForGtsamCarriesTheMeasurementsAndTheirSigmas)
{
	const std::string g2o = dir_->file("br.g2o");
	const auto r = runEsif("export g2o --landmark-edge br --rawlog '" + rawlog_ + "' --out '" + g2o + "'");
	ASSERT_EQ(r.exit_code, 0) << r.out;
	auto lines = linesByTag(g2o);
	EXPECT_EQ(lines.count("EDGE_SE2_XY"), 0u);
	const Rawlog log = readRawlog(rawlog_);
	std::size_t n = 0;
	for (const auto& s : log.steps)
		if (s.scan)
			for (const auto& m : s.scan->measurements)
			{
				ASSERT_LT(n, lines["BR"].size());
				const auto& e = lines["BR"][n++];
				ASSERT_EQ(e.size(), 7u);
				EXPECT_EQ(parse(e[3]), m.bearing_rad);
				EXPECT_EQ(parse(e[4]), m.range_m);
				EXPECT_EQ(parse(e[5]), std::sqrt(m.cov(1, 1)));
				EXPECT_EQ(parse(e[6]), std::sqrt(m.cov(0, 0)));
			}
	EXPECT_EQ(n, lines["BR"].size());
	// esif reads its own BR files back too.
	const auto im =
		runEsif("import g2o --g2o '" + g2o + "' --rawlog '" + rawlog_ + "' --out '" + dir_->file("br_imported") + "'");
	EXPECT_EQ(im.exit_code, 0) << im.out;
}

/// The cell of `column` in the row of `label` of a comparison.csv ("" if absent).
std::string csvCell(const std::string& path, const std::string& label, const std::string& column)
{
	std::istringstream in(readText(path));
	std::string line;
	std::getline(in, line);
	std::vector<std::string> header;
	std::stringstream hs(line);
	for (std::string c; std::getline(hs, c, ',');) header.push_back(c);
	const auto col = std::find(header.begin(), header.end(), column) - header.begin();
	const auto label_col = std::find(header.begin(), header.end(), "label") - header.begin();
	while (std::getline(in, line))
	{
		std::vector<std::string> cells;
		std::stringstream ss(line);
		for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
		if (label_col < static_cast<long>(cells.size()) && cells[label_col] == label && col < static_cast<long>(cells.size()))
			return cells[col];
	}
	return "";
}

TEST_F(G2oRoundTrip, ImportedSolutionIsACompareReference)
{
	// Another solver's solution stands in as the imported ceres run: the same
	// config compared against it differs by nothing.
	const std::string g2o = dir_->file("ref.g2o");
	ASSERT_EQ(runEsif("export g2o --rawlog '" + rawlog_ + "' --associations-from '" + dir_->file("ceres") +
					  "' --out '" + g2o + "'")
				  .exit_code,
			  0);
	ASSERT_EQ(
		runEsif("import g2o --g2o '" + g2o + "' --rawlog '" + rawlog_ + "' --out '" + dir_->file("solver") + "'")
			.exit_code,
		0);
	const auto r = runEsif(
		"compare --configs '" + test::sourcePath("configs/ceres_full.ini") + "," + test::sourcePath("configs/ekf.ini") +
		"' --rawlog '" + rawlog_ + "' --reference '" + dir_->file("solver") + "' --out '" + dir_->file("cmp") + "'");
	ASSERT_EQ(r.exit_code, 0) << r.out;
	const std::string csv = dir_->file("cmp/comparison.csv");
	EXPECT_NE(r.out.find("ref_*: difference from the run folder " + dir_->file("solver")), std::string::npos) << r.out;
	// ceres_full is deterministic: its run here is the one imported,
	// positions exactly, headings to the few ulps of their trip through
	// trajectory.tum's quaternions.
	EXPECT_EQ(csvCell(csv, "ceres_full", "ref_traj_rms_m"), "0") << readText(csv);
	EXPECT_LT(std::stod(csvCell(csv, "ceres_full", "ref_heading_rms_deg")), 1e-12) << readText(csv);
	EXPECT_EQ(csvCell(csv, "ceres_full", "ref_landmark_rms_m"), "0") << readText(csv);
	EXPECT_EQ(csvCell(csv, "ceres_full", "ref_landmarks_matched"), "16") << readText(csv);
	// The EKF differs from the optimum by its estimation error: centimetres.
	const std::string ekf_cell = csvCell(csv, "ekf", "ref_landmark_rms_m");
	ASSERT_FALSE(ekf_cell.empty()) << readText(csv);
	const double ekf = std::stod(ekf_cell);
	EXPECT_GT(ekf, 0.0);
	EXPECT_LT(ekf, 0.2);
}

/// Writes `text` as a g2o file and imports it: the exit code and output.
test::CommandResult importText(const TempDir& dir, const std::string& rawlog, const std::string& text)
{
	const std::string path = dir.file("bad.g2o");
	std::ofstream(path) << text;
	return runEsif("import g2o --g2o '" + path + "' --rawlog '" + rawlog + "' --out '" + dir.file("bad_out") + "'");
}

TEST_F(G2oRoundTrip, BadFilesAreOneLineNamingFileAndLine)
{
	const std::string head = "# comment\nVERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\nVERTEX_XY 205 2 1\n";
	const std::string edge = "EDGE_SE2 0 1 1 0 0 100 0 0 100 0 400\n";
	const struct
	{
		std::string text;
		std::string where;
		std::string reason;
	} cases[] = {
		{head + "EDGE_SE3:QUAT 0 1 0 0 0 0 0 0 1\n", ":5: ", "unknown tag 'EDGE_SE3:QUAT'"},
		{head + "EDGE_SE2 0 7 1 0 0 100 0 0 100 0 400\n", ":5: ", "no VERTEX_SE2 7"},
		{head + "EDGE_SE2_XY 1 9 1 0 100 0 100\n", ":5: ", "no VERTEX_XY 9"},
		{head + "EDGE_SE2 0 1 1 0 0 100 0 0 -100 0 400\n", ":5: ", "not positive definite"},
		{head + "EDGE_SE2_XY 1 205 1 0 1 2 1\n", ":5: ", "not positive definite"},
		{head + "BR 1 205 0.1 2 0 0.1\n", ":5: ", "sigmas must be positive"},
		{head + "VERTEX_XY 205 3 3\n", ":5: ", "defined twice (first on line 4)"},
		{head + "VERTEX_SE2 2 1 x 0\n", ":5: ", "'x' is not a number"},
		{head + "VERTEX_SE2 -2 1 0 0\n", ":5: ", "not a non-negative integer"},
		{head + edge + "EDGE_SE2 0 1 1 0 100 0 0 100 0 400\n", ":6: ", "needs 11 values"},
		{head + "VERTEX_SE2 2 1 nan 0\n", ":5: ", "not finite"},
	};
	for (const auto& c : cases)
	{
		const auto r = importText(*dir_, rawlog_, c.text);
		EXPECT_EQ(r.exit_code, 1) << c.text;
		EXPECT_NE(r.out.find(dir_->file("bad.g2o") + c.where), std::string::npos) << r.out;
		EXPECT_NE(r.out.find(c.reason), std::string::npos) << r.out;
		EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
		EXPECT_FALSE(std::filesystem::exists(dir_->file("bad_out")));
	}
	// A well-formed file of another problem: the rawlog's 200 poses are not all there.
	const auto r = importText(*dir_, rawlog_, head + edge);
	EXPECT_EQ(r.exit_code, 1);
	EXPECT_NE(r.out.find("no VERTEX_SE2 2 (the rawlog's problem has poses 0..200)"), std::string::npos) << r.out;
}

TEST_F(G2oRoundTrip, ExportWithoutLandmarkIdsNeedsARunFolder)
{
	const auto r = runEsif("export g2o --rawlog '" + rawlog_ + "' --associations-from '" + dir_->file("nowhere") +
						   "' --out '" + dir_->file("x.g2o") + "'");
	EXPECT_EQ(r.exit_code, 1);
	EXPECT_NE(r.out.find("nowhere: run folder not found"), std::string::npos) << r.out;
	EXPECT_FALSE(std::filesystem::exists(dir_->file("x.g2o")));
}

}  // namespace
