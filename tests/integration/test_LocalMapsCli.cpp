// Local maps as a first-class input, through the `esif` binary as a user
// runs it, with the test-only joining plugin (DeadReckoningJoiner, loaded
// with --plugin-dir): `localmaps build` and `info`, `run --local-maps` with
// its evaluation, reference result and hidden IDs, `compare --local-maps`,
// the one-line errors, and a joiner's rawlog run (final reports, figure).

#include <EsifTestSupport.h>
#include <LocalMapTestSupport.h>

#include <esif/formats/AssociationFile.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/LocalMapFiles.h>
#include <esif/formats/RunOutputReader.h>
#include <esif/models/Se2.h>
#include <esif/localmaps/LocalMapBuild.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>

namespace fs = std::filesystem;

namespace
{
using esif::test::readStatsJson;
using esif::test::expectOneErrorLine;
using esif::test::quoted;
using esif::test::runEsif;
using esif::test::sourcePath;
using esif::test::TempDir;

const std::string kGrid196 = sourcePath("rawlogs/grid196.rawlog");
const std::string kSim5 = sourcePath("../shared/data/localmaps/sim5_with_truth");
const std::string kVicpark200 = sourcePath("../shared/data/localmaps/vicpark_200");

/// Configs shared by the tests, written once.
class LocalMapsCli : public ::testing::Test
{
   protected:
	static void SetUpTestSuite()
	{
		dir_ = std::make_unique<TempDir>();
		std::ofstream(dir_->file("joiner.ini")) << esif::test::joinerConfig("label = joiner\n");
		std::ofstream(dir_->file("hidden.ini"))
			<< esif::test::joinerConfig("label = hidden\nhide_landmark_ids = true\n");
		std::ofstream(dir_->file("ekf.ini")) << "[esif]\nplugin = EkfSlam\n";
		esif::LocalMapFolder tiny;
		tiny.maps.push_back(esif::test::makeLocalMap(1, esif::Pose2(2, 0, 0.1), {{1, 1, 1}, {2, 3, -1}}));
		tiny.maps.push_back(esif::test::makeLocalMap(2, esif::Pose2(2, 0.5, 0), {{2, 1, -1}, {3, 2, 2}}));
		esif::writeLocalMapFolder(tiny, tinyMaps());
	}
	static void TearDownTestSuite() { dir_.reset(); }

	static std::string config(const std::string& name) { return quoted(dir_->file(name)); }

	/// `esif run -q` of `config` on local maps `maps` into `out` (a folder name under the suite's dir).
	static esif::test::CommandResult runOnMaps(
		const std::string& cfg, const std::string& maps, const std::string& out, const std::string& extra = "")
	{
		return runEsif("run -q --config " + config(cfg) + " --local-maps " + quoted(maps) + " --out " +
					   quoted(dir_->file(out)) + " " + esif::test::testPluginDirOption() + " " + extra);
	}

	/// GTEST_SKIP() only leaves the function it is called in, so each test
	/// that needs the third-party set checks this itself.
	static bool sim5Present() { return fs::exists(kSim5 + "/localmap_1.txt"); }

	/// A folder of two hand-made maps, for the tests that do not depend on
	/// the maps' content (they run without ../shared/data).
	static std::string tinyMaps() { return dir_->file("tiny_maps"); }

	static std::unique_ptr<TempDir> dir_;
};
std::unique_ptr<TempDir> LocalMapsCli::dir_;

TEST_F(LocalMapsCli, BuildOnGrid196WritesMapsWithGroundTruthThatInfoAndTheReaderAccept)
{
	const std::string out = dir_->file("grid196_maps");
	const auto r = runEsif("localmaps build --config " + config("joiner.ini") + " --rawlog " + quoted(kGrid196) +
						   " --out " + quoted(out) + " " + esif::test::testPluginDirOption());
	ASSERT_EQ(r.exit_code, 0) << r.out;
	EXPECT_NE(r.out.find("local maps from 3000 steps of"), std::string::npos) << r.out;
	// grid196's landmarks are numbered from 0, and the format needs positive IDs.
	EXPECT_NE(r.out.find("feature ID = rawlog ID + 1 (the format needs positive IDs)"), std::string::npos) << r.out;

	const auto folder = esif::readLocalMapFolder(out);
	ASSERT_GT(folder.maps.size(), 10u);
	std::size_t steps = 0;
	std::set<esif::LandmarkId> ids;
	for (const auto& m : folder.maps)
	{
		steps += m.steps;  // 0 when read back: the files hold no steps
		for (const auto& f : m.features) ids.insert(f.id);
	}
	EXPECT_EQ(steps, 0u);
	ASSERT_TRUE(folder.truth_landmarks.has_value());
	ASSERT_TRUE(folder.truth_end_poses.has_value());
	EXPECT_EQ(folder.truth_landmarks->size(), ids.size());	// one per feature ID, the rawlog's
	EXPECT_EQ(folder.truth_end_poses->size(), folder.maps.size());
	// The last map ends at the last step: its true end pose is the path's last pose.
	const auto truth = esif::loadGroundTruth(esif::groundTruthPrefixFor(kGrid196))->inInitialPoseFrame();
	EXPECT_LT((folder.truth_end_poses->at(folder.maps.size()) - truth.path.back()).norm(), 1e-9);
	// Map 1 is in the frame of pose 0: its features lie near their true landmarks.
	for (const auto& f : folder.maps.front().features)
		EXPECT_LT((f.position - folder.truth_landmarks->at(f.id)).norm(), 0.3) << "feature " << f.id;

	const auto info = runEsif("localmaps info " + quoted(out));
	ASSERT_EQ(info.exit_code, 0) << info.out;
	EXPECT_NE(info.out.find(std::to_string(folder.maps.size()) + " local maps\n"), std::string::npos) << info.out;
	EXPECT_NE(info.out.find("distinct feature IDs: " + std::to_string(ids.size())), std::string::npos) << info.out;
	EXPECT_NE(info.out.find("ground truth: " + std::to_string(ids.size()) + " landmarks, " +
							std::to_string(folder.maps.size()) + " end poses"),
			  std::string::npos)
		<< info.out;

	// The joiner fuses them back, scored against both truth files.
	const auto run = runOnMaps("joiner.ini", out, "grid196_run");
	ASSERT_EQ(run.exit_code, 0) << run.out;
	const auto stats = readStatsJson(dir_->file("grid196_run"));
	EXPECT_EQ(*stats.number("local_maps"), static_cast<double>(folder.maps.size()));
	EXPECT_EQ(*stats.number("da_wrong"), 0.0);
	ASSERT_TRUE(stats.number("landmark_rmse_m").has_value());
	EXPECT_LT(*stats.number("landmark_rmse_m"), 5.0);
	ASSERT_TRUE(stats.number("ate_rmse_m").has_value());
	EXPECT_TRUE(std::isfinite(*stats.number("pose_nees_mean")));
}

TEST_F(LocalMapsCli, BuildWithHiddenIdsKeysTheTruthByTheBuildersIds)
{
	const std::string out = dir_->file("grid196_hidden_maps");
	const auto r = runEsif("localmaps build -q --config " + config("hidden.ini") + " --rawlog " + quoted(kGrid196) +
						   " --out " + quoted(out) + " " + esif::test::testPluginDirOption());
	ASSERT_EQ(r.exit_code, 0) << r.out;
	EXPECT_TRUE(r.out.empty()) << r.out;  // --quiet
	const auto folder = esif::readLocalMapFolder(out);
	ASSERT_TRUE(folder.truth_landmarks.has_value());
	// The builder numbered the features itself; each is keyed to the true
	// landmark its measurements came from, so map 1 (frame of pose 0) lies
	// near the truth under its own IDs.
	ASSERT_FALSE(folder.maps.front().features.empty());
	for (const auto& f : folder.maps.front().features)
	{
		ASSERT_TRUE(folder.truth_landmarks->count(f.id)) << "feature " << f.id;
		EXPECT_LT((f.position - folder.truth_landmarks->at(f.id)).norm(), 0.3) << "feature " << f.id;
	}
}

TEST_F(LocalMapsCli, InfoOnVictoriaParkReportsTheMapSharingOneFeature)
{
	if (!fs::exists(kVicpark200 + "/localmap_1.txt")) GTEST_SKIP() << kVicpark200 << " not present";
	const auto r = runEsif("localmaps info " + quoted(kVicpark200));
	ASSERT_EQ(r.exit_code, 0) << r.out;
	EXPECT_NE(r.out.find(": 200 local maps\n"), std::string::npos) << r.out;
	EXPECT_NE(r.out.find("distinct feature IDs: 299\n"), std::string::npos) << r.out;
	EXPECT_NE(r.out.find("state dimension min/mean/max: 13 / 41.9 / 75\n"), std::string::npos) << r.out;
	EXPECT_NE(r.out.find("ground truth: none\n"), std::string::npos) << r.out;
	EXPECT_NE(r.out.find("(D-SLAM map joining needs 2, Sec. 4.4.4): 1\n"), std::string::npos) << r.out;
	EXPECT_NE(r.out.find("    map 132 shares 1 feature with maps 1-131\n"), std::string::npos) << r.out;
}

TEST_F(LocalMapsCli, RunOnSim5GivesFiniteRmseAndEveryOutput)
{
	if (!sim5Present()) GTEST_SKIP() << kSim5 << " not present";
	const auto r = runOnMaps("joiner.ini", kSim5, "sim5_run");
	ASSERT_EQ(r.exit_code, 0) << r.out;
	const std::string out = dir_->file("sim5_run");
	for (const char* f : {"landmarks.gz", "landmarks.txt", "trajectory.tum", "map.simplemap", "map.png",
						  "map.svg", "scene.3Dscene", "stats.json", "params.ini", "associations.txt",
						  "landmark_identities.txt", "localmap_times.png", "localmap_times.svg"})
		EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
	EXPECT_FALSE(fs::exists(out + "/step_times.png"));	// no steps to time

	const auto folder = esif::readLocalMapFolder(kSim5);
	std::size_t entries = 0;
	for (const auto& m : folder.maps) entries += m.features.size();
	const auto stats = readStatsJson(out);
	EXPECT_EQ(*stats.number("local_maps"), 5.0);
	EXPECT_EQ(*stats.number("steps"), 0.0);
	EXPECT_EQ(*stats.number("measurements"), static_cast<double>(entries));
	EXPECT_EQ(*stats.number("landmarks"), 37.0);
	EXPECT_EQ(*stats.number("da_wrong"), 0.0);
	ASSERT_TRUE(stats.number("landmark_rmse_m").has_value());
	EXPECT_TRUE(std::isfinite(*stats.number("landmark_rmse_m")));
	EXPECT_GT(*stats.number("landmarks_evaluated"), 0.0);
	EXPECT_FALSE(stats.number("ate_rmse_m").has_value());  // no end-pose truth in this set
	EXPECT_TRUE(stats.number("join_us_mean").has_value());
	EXPECT_EQ(*stats.number("poses_in_state"), 5.0);

	// trajectory.tum: end pose k at time k; associations.txt: one "step" per map.
	const auto trajectory = esif::readTrajectoryTum(out + "/trajectory.tum");
	ASSERT_EQ(trajectory.size(), 5u);
	EXPECT_DOUBLE_EQ(trajectory.front().time_s, 1.0);
	EXPECT_DOUBLE_EQ(trajectory.back().time_s, 5.0);
	const auto associations = esif::readAssociationFile(out + "/associations.txt", 5);
	ASSERT_EQ(associations.steps.size(), 5u);
	EXPECT_EQ(associations.steps[0].associations.size(), folder.maps[0].features.size());
}

TEST_F(LocalMapsCli, ReferenceResultOfItsOwnOutputGivesZeroAndAShiftGivesTheShift)
{
	if (!sim5Present()) GTEST_SKIP() << kSim5 << " not present";
	ASSERT_EQ(runOnMaps("joiner.ini", kSim5, "sim5_own").exit_code, 0);
	const auto own = esif::readRunOutputs(dir_->file("sim5_own"));
	// The run's own result as a reference, and the same moved by (0.6, -0.8)
	// with every heading + 2 pi (the authors' headings are unwrapped).
	for (const double shift : {0.0, 1.0})
	{
		const std::string ref = dir_->file("ref_" + std::to_string(static_cast<int>(shift)));
		fs::create_directories(ref);
		const Eigen::Vector2d d = shift * Eigen::Vector2d(0.6, -0.8);
		std::map<esif::LandmarkId, Eigen::Vector2d> features;
		for (const auto& lm : own.landmarks) features[lm.id] = lm.mean + d;
		std::map<std::size_t, esif::Pose2> poses;
		for (const auto& p : own.trajectory)
			poses[static_cast<std::size_t>(p.time_s)] = esif::Pose2(p.pose.x + d.x(), p.pose.y + d.y(), p.pose.phi + 2 * M_PI);
		esif::test::writeReferenceResult(ref, features, poses);

		const std::string out = "sim5_ref_" + std::to_string(static_cast<int>(shift));
		const auto r = runOnMaps("joiner.ini", kSim5, out, "--reference-result " + quoted(ref));
		ASSERT_EQ(r.exit_code, 0) << r.out;
		const auto stats = readStatsJson(dir_->file(out));
		EXPECT_EQ(*stats.number("refres_landmarks_matched"), 37.0);
		EXPECT_EQ(*stats.number("refres_poses_matched"), 5.0);
		EXPECT_NEAR(*stats.number("refres_landmark_rms_m"), shift, 1e-9);
		EXPECT_NEAR(*stats.number("refres_landmark_max_m"), shift, 1e-9);
		EXPECT_NEAR(*stats.number("refres_pose_rms_m"), shift, 1e-9);
		EXPECT_NEAR(*stats.number("refres_pose_max_m"), shift, 1e-9);
		EXPECT_NEAR(*stats.number("refres_heading_rms_deg"), 0.0, 1e-6);
	}
}

TEST_F(LocalMapsCli, HiddenIdsAreRenumberedForThePluginYetScoredAgainstTheFilesIds)
{
	if (!sim5Present()) GTEST_SKIP() << kSim5 << " not present";
	const auto r = runOnMaps("hidden.ini", kSim5, "sim5_hidden");
	ASSERT_EQ(r.exit_code, 0) << r.out;
	const auto folder = esif::readLocalMapFolder(kSim5);
	std::size_t entries = 0;
	for (const auto& m : folder.maps) entries += m.features.size();
	// The joiner associates by the IDs it is shown: unique per entry, so
	// every entry is a landmark of its own, numbered 1..entries ...
	const auto stats = readStatsJson(dir_->file("sim5_hidden"));
	EXPECT_EQ(*stats.number("landmarks"), static_cast<double>(entries));
	EXPECT_EQ(*stats.number("da_new"), static_cast<double>(entries));
	const auto landmarks = esif::readLandmarksTxt(dir_->file("sim5_hidden") + "/landmarks.txt");
	EXPECT_EQ(landmarks.back().id, static_cast<esif::LandmarkId>(entries));
	// ... and the files' IDs score it: each of the 37 landmarks seen more
	// than once is split, and every copy is matched to its true landmark.
	EXPECT_EQ(*stats.number("da_wrong"), static_cast<double>(entries - 37));
	EXPECT_EQ(*stats.number("landmarks_evaluated"), static_cast<double>(entries));
	EXPECT_TRUE(std::isfinite(*stats.number("landmark_rmse_m")));
}

TEST_F(LocalMapsCli, PluginThatCannotJoinIsOneLineAndWritesNothing)
{
	const std::string out = dir_->file("ekf_out");
	expectOneErrorLine(runOnMaps("ekf.ini", tinyMaps(), "ekf_out"),
					   "ekf.ini: plugin EkfSlam cannot join local maps (--local-maps needs a local-map joining plugin)");
	EXPECT_FALSE(fs::exists(out));
	expectOneErrorLine(runEsif("compare --configs " + config("joiner.ini") + "," + config("ekf.ini") +
							   " --local-maps " + quoted(tinyMaps()) + " --out " + quoted(out) + " " +
							   esif::test::testPluginDirOption()),
					   "ekf.ini: plugin EkfSlam cannot join local maps");
	EXPECT_FALSE(fs::exists(out));
	expectOneErrorLine(runEsif("localmaps build --config " + config("ekf.ini") + " --rawlog " + quoted(kGrid196) +
							   " --out " + quoted(out)),
					   "ekf.ini: plugin EkfSlam is not a local-map joining plugin");
	EXPECT_FALSE(fs::exists(out));
}

TEST_F(LocalMapsCli, BuildRefusesAssociationWithAGlobalMapItDoesNotHave)
{
	// The maps SLSJF builds with local_map_global_features_radius_m are
	// associated with its global map as they are built: esif localmaps build
	// has none, so it refuses rather than write maps SLSJF would not fuse.
	std::ofstream(dir_->file("scan_global.ini"))
		<< "[esif]\nplugin = Slsjf\nhide_landmark_ids = true\n[slsjf]\nlocal_map_global_features_radius_m = 12\n";
	const std::string out = dir_->file("scan_global_out");
	expectOneErrorLine(runEsif("localmaps build --config " + config("scan_global.ini") + " --rawlog " +
							   quoted(kGrid196) + " --out " + quoted(out)),
					   "scan_global.ini: local_map_global_features_radius_m needs the joining filter's global map");
	EXPECT_FALSE(fs::exists(out));
}

TEST_F(LocalMapsCli, RawlogAndLocalMapsTogetherOrNeitherIsAnError)
{
	const std::string out = dir_->file("both_out");
	const std::string base = "run -q --config " + config("joiner.ini") + " --out " + quoted(out) + " ";
	expectOneErrorLine(runEsif(base + "--rawlog " + quoted(kGrid196) + " --local-maps " + quoted(tinyMaps())),
					   "give exactly one of --rawlog FILE and --local-maps DIR");
	expectOneErrorLine(runEsif(base), "give exactly one of --rawlog FILE and --local-maps DIR");
	expectOneErrorLine(runEsif(base + "--rawlog " + quoted(kGrid196) + " --reference-result " + quoted(tinyMaps())),
					   "--reference-result applies to --local-maps input");
	expectOneErrorLine(runEsif(base + "--local-maps " + quoted(tinyMaps()) + " --ground-truth x"),
					   "--ground-truth applies to --rawlog input");
	expectOneErrorLine(runEsif("compare --configs " + config("joiner.ini") + " --out " + quoted(out) + " --rawlog " +
							   quoted(kGrid196) + " --local-maps " + quoted(tinyMaps())),
					   "give exactly one of --rawlog FILE and --local-maps DIR");
	EXPECT_FALSE(fs::exists(out));
	expectOneErrorLine(runEsif("localmaps frobnicate"), "unknown action 'frobnicate'");
	EXPECT_EQ(runEsif("localmaps build --help").exit_code, 0);
	EXPECT_EQ(runEsif("localmaps info --help").exit_code, 0);
}

TEST_F(LocalMapsCli, CompareOnLocalMapsShowsTheReferenceResultColumns)
{
	if (!sim5Present()) GTEST_SKIP() << kSim5 << " not present";
	// sim5's own truth as a reference result: feature.txt only.
	const std::string ref = dir_->file("sim5_truth_ref");
	fs::create_directories(ref);
	esif::test::writeReferenceResult(ref, *esif::readLocalMapFolder(kSim5).truth_landmarks, {});
	const std::string out = dir_->file("sim5_compare");
	const auto r = runEsif("compare --configs " + config("joiner.ini") + "," + config("hidden.ini") +
						   " --local-maps " + quoted(kSim5) + " --reference-result " + quoted(ref) + " --out " +
						   quoted(out) + " " + esif::test::testPluginDirOption());
	ASSERT_EQ(r.exit_code, 0) << r.out;
	EXPECT_NE(r.out.find("\nlocal_maps "), std::string::npos) << r.out;
	EXPECT_NE(r.out.find("\nrefres_landmark_rms_m "), std::string::npos) << r.out;
	EXPECT_NE(r.out.find("refres_*: difference from the reference result"), std::string::npos) << r.out;
	// Against the truth, the reference-result difference is the landmark RMSE.
	const auto stats = readStatsJson(out + "/joiner");
	EXPECT_NEAR(*stats.number("refres_landmark_rms_m"), *stats.number("landmark_rmse_m"), 1e-9);
	EXPECT_TRUE(fs::exists(out + "/comparison.md"));
}

TEST_F(LocalMapsCli, RawlogRunOfAJoinerDrawsLocalMapTimesAndScoresTheFinalReports)
{
	const std::string rawlog = dir_->file("small.rawlog");
	ASSERT_EQ(esif::test::simulateSmall(rawlog).exit_code, 0);
	const std::string out = dir_->file("small_joiner");
	const auto r = runEsif("run -q --config " + config("joiner.ini") + " --rawlog " + quoted(rawlog) + " --out " +
						   quoted(out) + " " + esif::test::testPluginDirOption());
	ASSERT_EQ(r.exit_code, 0) << r.out;
	EXPECT_TRUE(fs::exists(out + "/localmap_times.png"));
	EXPECT_TRUE(fs::exists(out + "/step_times.png"));
	const auto stats = readStatsJson(out);
	EXPECT_EQ(*stats.number("local_maps"), 5.0);  // 200 steps, 45 a map
	EXPECT_TRUE(stats.number("join_us_mean").has_value());
	EXPECT_EQ(*stats.number("da_wrong"), 0.0);
	// The final reports name the global landmarks (here the rawlog's IDs).
	const auto associations = esif::readAssociationFile(out + "/associations.txt", 200);
	ASSERT_EQ(associations.steps.size(), 200u);
	const auto landmarks = esif::readLandmarksTxt(out + "/landmarks.txt");
	std::set<esif::LandmarkId> mapped;
	for (const auto& lm : landmarks) mapped.insert(lm.id);
	for (const auto& step : associations.steps)
		for (const auto& a : step.associations)
		{
			if (a.kind != esif::Association::Kind::Rejected)
			{
				EXPECT_TRUE(mapped.count(a.id)) << a.id;
			}
		}
}

/// A reference result is held to its documented layout and bounds: without
/// pose.txt, with a pose of a map the folder does not have, or a feature ID
/// no rawlog carries, it is refused naming the file, never measured against
/// in part with refres_pose_* left null.
TEST_F(LocalMapsCli, AReferenceResultMissingPosesOrOutOfBoundsIsRefusedNamingTheFile)
{
	const std::string ref = dir_->file("ref_bounds");
	fs::create_directories(ref);
	const std::map<esif::LandmarkId, Eigen::Vector2d> features = {{1, {1, 1}}, {2, {3, -1}}, {3, {2, 2}}};
	esif::test::writeReferenceResult(ref, features, {{1, esif::Pose2(2, 0, 0.1)}, {2, esif::Pose2(4, 0.5, 0.1)}});
	const auto ok = runOnMaps("joiner.ini", tinyMaps(), "ref_ok", "--reference-result " + quoted(ref));
	ASSERT_EQ(ok.exit_code, 0) << ok.out;

	fs::remove(ref + "/pose.txt");
	expectOneErrorLine(runOnMaps("joiner.ini", tinyMaps(), "ref_no_poses", "--reference-result " + quoted(ref)),
					   ref + "/pose.txt: reference end poses not found");
	esif::test::writeReferenceResult(ref, features, {{1, esif::Pose2(2, 0, 0.1)}, {999, esif::Pose2(1, 1, 0)}});
	expectOneErrorLine(runOnMaps("joiner.ini", tinyMaps(), "ref_map_999", "--reference-result " + quoted(ref)),
					   ref + "/pose.txt:2: map index 999 but the folder has maps 1..2");
	esif::test::writeReferenceResult(ref, {{1, {1, 1}}, {99999999999, {3, -1}}}, {{1, esif::Pose2(2, 0, 0.1)}});
	expectOneErrorLine(runOnMaps("joiner.ini", tinyMaps(), "ref_big_id", "--reference-result " + quoted(ref)),
					   ref + "/feature.txt:2: id 99999999999 is beyond 2147483647");
	EXPECT_FALSE(fs::exists(dir_->file("ref_no_poses")));
}

}  // namespace
