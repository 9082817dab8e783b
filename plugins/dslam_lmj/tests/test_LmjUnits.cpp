// The D-SLAM local map joining filter (book Ch. 4) on inputs whose answer is
// known: one local map is the global map with the robot marginalised; the
// pair-frame transforms and the global robot pose (Sec. 4.4.1) have the
// Jacobians finite differences give; local maps of a single scan reproduce
// D-SLAM's mapping update (Sec. 4.9); the information matrix is exactly
// sparse (eq. 4.18-4.19): every off-diagonal block links two features of one
// local map; a map whose reference pair places its end where its start cannot
// reach is not fused.

#include <EsifTestSupport.h>
#include <LocalMapTestSupport.h>
#include <NumericJacobian.h>

#include "JoinedMaps.h"
#include "PairFrame.h"
#include "ReferenceChoice.h"
#include "UpperLevelAssociation.h"

#include <esif/association/Chi2.h>
#include <esif/formats/RawlogReader.h>
#include <esif/localmap/LocalMapBuilder.h>
#include <esif/models/LocalMapObservation.h>
#include <esif/plugin/LocalMapJoiner.h>
#include <esif/relative/FeatureMap.h>
#include <esif/relative/RelativeGeometry.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <limits>
#include <map>
#include <random>
#include <set>

namespace
{
using namespace esif;
using test::pluginCounter;

const std::string kGrid196 = test::sourcePath("rawlogs/grid196.rawlog");

LocalMapJoiner& joinerOf(FilterPlugin& plugin) { return dynamic_cast<LocalMapJoiner&>(plugin); }

TEST(LmjUnits, OneLocalMapIsTheGlobalMapWithTheRobotMarginalised)
{
	// Sec. 4.3: "the global map is just the same as the first local map
	// without the robot pose": I(1) = P_ff^-1.
	auto plugin = test::makePlugin("DslamLocalMapJoining", "");
	const LocalMap map = test::randomLocalMap(1, 4, 5);
	joinerOf(*plugin).joinLocalMap(map);
	plugin->finish();
	const Eigen::MatrixXd P = map.information.inverse();  // 11 x 11 reference
	const Estimate e = plugin->estimate();
	ASSERT_EQ(e.landmarks.size(), 4u);
	for (std::size_t i = 0; i < 4; ++i)
	{
		EXPECT_EQ(e.landmarks[i].id, map.features[i].id);
		EXPECT_LT((e.landmarks[i].mean - map.features[i].position).norm(), 1e-10);
		EXPECT_LT((e.landmarks[i].cov - P.block<2, 2>(3 + 2 * i, 3 + 2 * i)).norm(), 1e-10 * P.norm());
	}
	const CostFigures cost = plugin->costFigures();
	EXPECT_EQ(cost.state_dim, 8u);
	EXPECT_EQ(cost.poses_in_state, 0u);
	EXPECT_EQ(cost.info_nnz, 64u);	// one dense 8 x 8 block
	// Map 1's frame is the global frame: its end pose is the local one.
	const auto ends = joinerOf(*plugin).endPoses();
	ASSERT_EQ(ends.size(), 1u);
	EXPECT_LT((ends[0].mean - map.end_pose).norm(), 1e-9);
}

TEST(LmjUnits, PairFrameAndRobotPoseJacobiansMatchFiniteDifferences)
{
	std::mt19937 rng(3);
	std::uniform_real_distribution<double> u(-5, 5);
	for (int trial = 0; trial < 20; ++trial)
	{
		Eigen::VectorXd x(4);
		x << u(rng), u(rng), u(rng), u(rng);
		const auto f = [](const Eigen::VectorXd& p) -> Eigen::VectorXd {
			return lmj::pairFrame(p.head<2>(), p.tail<2>()).pose;
		};
		const Eigen::MatrixXd numeric = test::numericJacobian(f, x, 1e-6, {2});
		EXPECT_LT((numeric - lmj::pairFrame(x.head<2>(), x.tail<2>()).d_pair).cwiseAbs().maxCoeff(), 1e-6) << trial;

		// The global robot pose from (robot, f1, f2) local and (f1, f2) global:
		// its covariance is J P J^T with the finite-difference J.
		Eigen::VectorXd all(11);
		all << u(rng), u(rng), 0.5 * u(rng), x, u(rng), u(rng), u(rng), u(rng);
		const auto g = [](const Eigen::VectorXd& v) -> Eigen::VectorXd {
			return lmj::robotFromPairs(v.head<3>(), v.segment<2>(3), v.segment<2>(5), Eigen::MatrixXd::Zero(7, 7),
											   v.segment<2>(7), v.segment<2>(9), Eigen::Matrix4d::Zero())
							   .mean;
		};
		const Eigen::MatrixXd J = test::numericJacobian(g, all, 1e-6, {2});
		Eigen::MatrixXd A(11, 11);
		for (int r = 0; r < 11; ++r)
			for (int c = 0; c < 11; ++c) A(r, c) = u(rng);
		const Eigen::MatrixXd Pall = A * A.transpose() * 1e-3;
		const auto pose = lmj::robotFromPairs(all.head<3>(), all.segment<2>(3), all.segment<2>(5),
											  Pall.topLeftCorner(7, 7), all.segment<2>(7), all.segment<2>(9),
											  Pall.bottomRightCorner<4, 4>());
		// The two estimates are independent: the reference drops the cross terms.
		Eigen::MatrixXd P = Pall;
		P.topRightCorner(7, 4).setZero();
		P.bottomLeftCorner(4, 7).setZero();
		const Eigen::Matrix3d expected = J * P * J.transpose();
		EXPECT_LT((pose.cov - expected).cwiseAbs().maxCoeff(), 1e-6 * expected.cwiseAbs().maxCoeff()) << trial;
	}
}

TEST(LmjUnits, TwoLocalFeaturesGivenOneGlobalFeatureAreNeitherKnown)
{
	// When an earlier association merged two local features into one global
	// feature, a later map holding both cannot use either as a known
	// correspondence (the update would list the global feature twice).
	relative::FeatureMap global(SparseRecoveryParams{});
	Eigen::VectorXd xy(4);
	xy << 0, 0, 3, 0;
	global.updateAnchor({100, 101}, {xy, 0.01 * Eigen::MatrixXd::Identity(4, 4)});
	LocalMap map;
	map.index = 2;
	for (const LandmarkId id : {7, 8, 9}) map.features.push_back({id, Eigen::Vector2d::Zero(), false});
	const std::map<LandmarkId, LandmarkId> global_of_local = {{7, 100}, {8, 100}, {9, 101}};
	const auto known = lmj::knownGlobalIds(map, false, global_of_local, global);
	ASSERT_EQ(known.size(), 3u);
	EXPECT_FALSE(known[0]);
	EXPECT_FALSE(known[1]);
	ASSERT_TRUE(known[2]);
	EXPECT_EQ(*known[2], 101);
}

/// A global map of six features 3 m apart (ids 1-6) and a local map of the
/// same six seen from another frame with 2 cm of noise, except that the
/// local feature of id `misread` lies where no mapped feature is (a misread
/// ID: its position belongs to an unmapped beacon at (6, 6)).
struct MisreadCase
{
	relative::FeatureMap global{SparseRecoveryParams{}};
	LocalMap map;
	Eigen::MatrixXd local_cov;
};

void buildMisreadCase(MisreadCase& c, LandmarkId misread)
{
	const std::vector<Eigen::Vector2d> truth = {{0, 0}, {3, 0}, {6, 0}, {0, 3}, {3, 3}, {6, 3}};
	Eigen::VectorXd xy(12);
	for (int i = 0; i < 6; ++i) xy.segment<2>(2 * i) = truth[i];
	c.global.updateAnchor({1, 2, 3, 4, 5, 6}, {xy, 0.02 * 0.02 * Eigen::MatrixXd::Identity(12, 12)});
	const Pose2 frame(1, 2, 0.3);
	std::mt19937 rng(11);
	std::normal_distribution<double> noise(0, 0.02);
	c.map.index = 2;
	for (int i = 0; i < 6; ++i)
	{
		const Eigen::Vector2d p = (i + 1 == misread) ? Eigen::Vector2d(6, 6) : truth[i];
		const Eigen::Vector2d local = pointInFrame(frame, p).value + Eigen::Vector2d(noise(rng), noise(rng));
		c.map.features.push_back({i + 1, local, false});
	}
	c.local_cov = 0.02 * 0.02 * Eigen::MatrixXd::Identity(12, 12);
}

/// Local map `index` ending at `end` with the features 1, 2, ... at
/// `points`, every variable independent with 5 cm sigma per axis (0.01 rad
/// in heading): test::makeLocalMap with a heading known better.
LocalMap independentMap(std::size_t index, const Pose2& end, const std::vector<Eigen::Vector2d>& points)
{
	std::vector<test::TestFeature> features;
	for (std::size_t i = 0; i < points.size(); ++i)
		features.push_back({static_cast<LandmarkId>(i + 1), points[i].x(), points[i].y()});
	LocalMap m = test::makeLocalMap(index, end, features, 0.05);
	m.information(2, 2) = 1 / (0.01 * 0.01);
	return m;
}

/// Two consecutive local maps with the features 1 and 2: `earlier` ends at
/// (2, 0, 0) with feature 1 at (4, 0) and 2 at (4, 2); `later` starts there
/// and holds feature 1 where earlier has it and feature 2 at (4, 4), 2 m from
/// earlier's (the ID a scan gave a neighbouring cluster). Every variable has
/// 5 cm sigma per axis, 0.01 rad in heading; later has one sighting of each
/// feature in its reports.
std::pair<LocalMap, LocalMap> mapsDisagreeingOnFeature2()
{
	const auto make = [](std::size_t index, const Pose2& end, const std::vector<Eigen::Vector2d>& features) {
		LocalMap m = independentMap(index, end, features);
		m.ids_identify_features = false;
		return m;
	};
	const Pose2 end(2, 0, 0);
	LocalMap earlier = make(5, end, {{4, 0}, {4, 2}});
	LocalMap later = make(6, Pose2(1, 0, 0), {pointInFrame(end, {4, 0}).value, pointInFrame(end, {4, 4}).value});
	StepReport report;
	report.associations = {{Association::Kind::Matched, 1}, {Association::Kind::Matched, 2}};
	later.step_reports = {report};
	return {earlier, later};
}

TEST(LmjUnits, AJoinLeavesOutAFeatureIdTheTwoMapsPlaceApart)
{
	const auto [earlier, later] = mapsDisagreeingOnFeature2();
	const double gate = chi2Quantile(0.9999, 2);
	// Feature 2: 2 m against a 0.07 m sigma of the difference; feature 1 agrees.
	EXPECT_EQ(lmj::disagreeingFeatures(earlier, later, gate), std::vector<LandmarkId>{2});
	EXPECT_TRUE(lmj::disagreeingFeatures(earlier, later, std::numeric_limits<double>::infinity()).empty());

	const lmj::JoinedMaps joined =
		lmj::joinConsecutive(lmj::single(earlier), lmj::single(later), lmj::disagreeingFeatures(earlier, later, gate));
	ASSERT_EQ(joined.map.features.size(), 2u);
	for (const auto& f : joined.map.features)
	{
		if (f.id == 2)	// earlier's alone: not pulled towards (4, 4)
		{
			EXPECT_LT((f.position - Eigen::Vector2d(4, 2)).norm(), 1e-6);
		}
	}
	// Later's sighting of feature 2 is reported rejected, that of 1 kept.
	ASSERT_EQ(joined.map.step_reports.size(), 1u);
	EXPECT_EQ(joined.map.step_reports[0].associations[0].kind, Association::Kind::Matched);
	EXPECT_EQ(joined.map.step_reports[0].associations[1].kind, Association::Kind::Rejected);

	// Joined through both, feature 2 lands between the two, 1 m from either.
	const lmj::JoinedMaps blind = lmj::joinConsecutive(lmj::single(earlier), lmj::single(later));
	for (const auto& f : blind.map.features)
	{
		if (f.id == 2)
		{
			EXPECT_GT((f.position - Eigen::Vector2d(4, 2)).norm(), 0.5);
		}
	}
}

TEST(LmjUnits, AMapWhosePairPlacesItsEndOutOfItsStartsReachIsNotFused)
{
	// Map 1 ends at (2, 0, 0) with the features 1-3; map 2 starts there and
	// ends 1 m on. Shifted, it sees the three 3 m further along x than map 1
	// does: rigidly, so the pair gate of the ID association passes, but
	// every pair places its end at (0, 0), where its start reaches (3, 0)
	// within 7 cm.
	const std::vector<Eigen::Vector2d> world = {{4, 0}, {4, 3}, {7, 1}};
	const Pose2 end1(2, 0, 0);
	const LocalMap map1 = independentMap(1, end1, world);
	std::vector<Eigen::Vector2d> seen_right, seen_shifted;
	for (const auto& p : world)
	{
		seen_right.push_back(pointInFrame(end1, p).value);
		seen_shifted.push_back(pointInFrame(end1, p).value + Eigen::Vector2d(3, 0));
	}
	struct Case
	{
		const char* name;
		bool shifted;
		const char* section;  ///< the plugin's INI section text
		bool refused;
		Pose2 end2;	 ///< where map 2's end pose must land
	};
	for (const Case& c : {Case{"consistent", false, "", false, Pose2(3, 0, 0)},
						  Case{"shifted", true, "", true, Pose2(3, 0, 0)},
						  Case{"shifted, test off (the book)", true, "reference_pair_chi2_quantile = 1\n", false,
							   Pose2(0, 0, 0)}})
	{
		SCOPED_TRACE(c.name);
		auto plugin = test::makePlugin("DslamLocalMapJoining", c.section);
		joinerOf(*plugin).joinLocalMap(map1);
		joinerOf(*plugin).joinLocalMap(independentMap(2, Pose2(1, 0, 0), c.shifted ? seen_shifted : seen_right));
		plugin->finish();
		EXPECT_EQ(pluginCounter(*plugin, "fusions_refused"), c.refused ? 1 : 0);
		// Its pair fails and both its matches are left out; the one feature
		// left makes no pair.
		EXPECT_EQ(pluginCounter(*plugin, "reference_pairs_refused"), c.refused ? 1 : 0);
		// Refused, the map cannot be joined with map 1 either (all three
		// features disagree): it is reported unjoinable, its end pose
		// carried from map 1's by its own. Fused without the test, the pair
		// throws it 3 m back. The features stay either way: a rigid shift
		// leaves the relative geometry the fusion takes from the map
		// unchanged (eq. 4.10).
		EXPECT_EQ(pluginCounter(*plugin, "local_maps_fused"), c.refused ? 1 : 2);
		EXPECT_EQ(pluginCounter(*plugin, "local_maps_unjoinable"), c.refused ? 1 : 0);
		const auto ends = joinerOf(*plugin).endPoses();
		ASSERT_EQ(ends.size(), 2u);
		EXPECT_LT((ends[1].mean - c.end2).norm(), 0.1) << ends[1].mean.transpose();
		for (const auto& l : plugin->estimate().landmarks)
			EXPECT_LT((l.mean - world[static_cast<std::size_t>(l.id - 1)]).norm(), 0.1) << "feature " << l.id;
	}
}

TEST(LmjUnits, IdMatchedFeatureFailingTheGateIsLeftOut)
{
	// Feature 5 (inside the grid) misread, and feature 3, whose misplaced
	// position makes the widest baseline: the reference pair is then the
	// misread one, most others fail, and the pair is chosen again without it.
	for (const LandmarkId misread : {5, 3})
	{
		MisreadCase c;
		buildMisreadCase(c, misread);
		lmj::DslamLmjParams params;
		const auto out = lmj::associateByIds(c.map, c.local_cov, c.global, params);
		ASSERT_EQ(out.decisions.associations.size(), 6u);
		EXPECT_EQ(out.tally.id_gate_rejected, 1u) << misread;
		for (int i = 0; i < 6; ++i)
			EXPECT_EQ(out.decisions.associations[i].kind,
					  i + 1 == misread ? Association::Kind::Rejected : Association::Kind::Matched)
				<< "misread " << misread << ", feature " << i + 1;
		// Disabled gate: IDs trusted, everything matched.
		params.id_gate_chi2_quantile = 1;
		const auto trusted = lmj::associateByIds(c.map, c.local_cov, c.global, params);
		EXPECT_EQ(trusted.tally.id_gate_rejected, 0u);
	}
}

TEST(LmjUnits, StartPoseAssociationNeedsNoKnownFeature)
{
	// The same six features with their IDs hidden (local 11-16) and none
	// known: placed by a start pose 0.36 m and 1.1 deg off, whose covariance
	// says so, five find their global feature; the misread one, 3 m from
	// every mapped feature, is new.
	MisreadCase c;
	buildMisreadCase(c, 5);
	for (auto& f : c.map.features) f.id += 10;
	const std::vector<std::optional<LandmarkId>> known(6);
	PoseEstimate start;
	start.mean = Pose2(1.3, 1.8, 0.32);
	start.cov = Eigen::Vector3d(0.3 * 0.3, 0.3 * 0.3, 0.03 * 0.03).asDiagonal();
	lmj::DslamLmjParams params;
	const auto out = lmj::associateInStartFrame(c.map, c.local_cov, known, start, c.global, params);
	ASSERT_EQ(out.decisions.associations.size(), 6u);
	for (int i = 0; i < 6; ++i)
	{
		const Association& a = out.decisions.associations[i];
		if (i + 1 == 5)
		{
			EXPECT_EQ(a.kind, Association::Kind::New);
			continue;
		}
		EXPECT_EQ(a.kind, Association::Kind::Matched) << "feature " << i + 1;
		EXPECT_EQ(a.id, i + 1);
	}
}

TEST(LmjUnits, WrongMatchFailsThePairGate)
{
	// Feature 2 (at (3, 0)) given to global feature 3 (at (6, 0)): in the
	// frame of a pair of the others it lies 3 m from it, and is left out.
	MisreadCase c;
	buildMisreadCase(c, -1);
	lmj::UpperLevelOutcome outcome;
	for (int i = 0; i < 6; ++i) outcome.decisions.associations.push_back({Association::Kind::Matched, i + 1});
	outcome.decisions.associations[1].id = 3;
	outcome.decisions.associations[2] = {Association::Kind::New, 3};
	lmj::rejectMatchesFailingPairGate(c.map, c.local_cov, c.global, lmj::DslamLmjParams{}, outcome);
	EXPECT_EQ(outcome.decisions.associations[1].kind, Association::Kind::Rejected);
	EXPECT_EQ(outcome.tally.pairs_dropped, 1u);
	for (const int i : {0, 3, 4, 5}) EXPECT_EQ(outcome.decisions.associations[i].kind, Association::Kind::Matched) << i;
}

/// grid196's local maps of `steps` steps (IDs known, features closer than
/// 0.3 m unused, as the configs).
std::vector<LocalMap> grid196Maps(int steps, std::size_t step_count)
{
	LocalMapBuilderParams p;
	p.local_map_steps = steps;
	p.local_map_min_common_features = 2;
	p.association.association = EkfAssociation::KnownIds;
	p.association.min_range_m = 0.3;
	LocalMapBuilder builder(p);
	std::vector<LocalMap> maps;
	const Rawlog log = readRawlog(kGrid196);
	for (std::size_t k = 0; k < std::min(step_count, log.steps.size()); ++k)
	{
		builder.processStep(log.steps[k]);
		if (auto m = builder.takeClosedMap()) maps.push_back(*m);
	}
	if (auto m = builder.finish()) maps.push_back(*m);
	return maps;
}

TEST(LmjUnits, InformationMatrixIsExactlySparse)
{
	// Eq. 4.18-4.19: each map's update is a dense block over its own features
	// and zero elsewhere, and there is no prediction step, so an off-diagonal
	// block of I is non-zero only for two features of one local map.
	auto plugin = test::makePlugin("DslamLocalMapJoining", "association = known_ids\n");
	const auto maps = grid196Maps(45, 3000);
	std::set<std::pair<LandmarkId, LandmarkId>> together;
	for (const auto& map : maps)
	{
		joinerOf(*plugin).joinLocalMap(map);
		for (const auto& a : map.features)
			for (const auto& b : map.features) together.insert({a.id, b.id});
	}
	plugin->finish();
	const auto pattern = plugin->informationPattern();
	ASSERT_TRUE(pattern);
	const auto landmarks = plugin->estimate().landmarks;  // variable order
	ASSERT_EQ(pattern->information.rows(), static_cast<Eigen::Index>(2 * landmarks.size()));
	std::set<std::pair<LandmarkId, LandmarkId>> linked;
	for (int col = 0; col < pattern->information.outerSize(); ++col)
		for (Eigen::SparseMatrix<double>::InnerIterator it(pattern->information, col); it; ++it)
		{
			const LandmarkId i = landmarks[it.row() / 2].id, j = landmarks[col / 2].id;
			if (i == j || it.value() == 0.0) continue;
			linked.insert({i, j});
			EXPECT_TRUE(together.count({i, j})) << "features " << i << " and " << j << " linked, in no map together";
		}
	// Conversely every two features of one map are linked: the blocks are
	// dense (eq. 4.18), and the links are those of the maps, no more.
	std::size_t pairs = 0;
	for (const auto& [i, j] : together) pairs += i != j;
	EXPECT_EQ(linked.size(), pairs);
}

TEST(LmjUnits, SingleScanMapsReproduceDslamMapping)
{
	// Sec. 4.9: with local maps of one scan each, the filter is D-SLAM's
	// mapping. The local map's features carry the robot pose's uncertainty
	// too, but distances and angles among them do not depend on the pose, so
	// z_map and R_map are D-SLAM's (eq. 3.8-3.9) with the pair chosen alike.
	const auto maps = grid196Maps(1, 120);
	auto plugin = test::makePlugin("DslamLocalMapJoining", "association = known_ids\n");
	for (const auto& map : maps) joinerOf(*plugin).joinLocalMap(map);
	plugin->finish();
	for (const auto& [name, value] : plugin->costFigures().counters)
	{
		if (name == "local_maps_merged")
		{
			ASSERT_EQ(value, 0) << "a merged map has no D-SLAM counterpart";
		}
	}

	// D-SLAM's mapping on the same scans: the first anchors the map, each
	// later one is a relative update about the same pair.
	relative::FeatureMap dslam(SparseRecoveryParams{});
	for (const auto& map : maps)
	{
		std::vector<LandmarkId> ids;
		std::vector<Eigen::Vector2d> points;
		for (const auto& f : map.features)
		{
			ids.push_back(f.id);
			points.push_back(f.position);
		}
		const Eigen::MatrixXd P = map.covarianceMatrix().bottomRightCorner(2 * ids.size(), 2 * ids.size());
		relative::PointSet all{map.state().tail(2 * ids.size()), P};
		if (dslam.featureCount() == 0)
		{
			dslam.updateAnchor(ids, all);
			dslam.recover(points.front());
			continue;
		}
		std::vector<int> mapped;
		for (int i = 0; i < static_cast<int>(ids.size()); ++i)
			if (dslam.supported(ids[i])) mapped.push_back(i);
		const auto pair = lmj::chooseReferenceFeatures(points, mapped, 1.0, 0.2);
		ASSERT_TRUE(pair) << "map " << map.index;
		const auto order = relative::pairFirst(static_cast<int>(ids.size()), pair->first, pair->second);
		std::vector<LandmarkId> ordered;
		for (const int i : order) ordered.push_back(ids[i]);
		dslam.updateRelative(ordered, relative::selectPoints(all, order));
		dslam.recover(dslam.position(ordered.front()));
	}
	const auto lmj = plugin->estimate().landmarks;
	const auto reference = dslam.landmarks();
	ASSERT_EQ(lmj.size(), reference.size());
	for (std::size_t i = 0; i < lmj.size(); ++i)
	{
		EXPECT_EQ(lmj[i].id, reference[i].id);
		EXPECT_LT((lmj[i].mean - reference[i].mean).norm(), 1e-9) << lmj[i].id;
		EXPECT_LT((lmj[i].cov - reference[i].cov).norm(), 1e-9 * reference[i].cov.norm()) << lmj[i].id;
	}
}

}  // namespace
