/// \file test_LocalMapBuilder.cpp
/// The local-map builder of the map-joining filters (book Sec. 4.2.1, 4.4.4,
/// 5.1.1): its parameters, noise-free simulations where every local map must
/// equal the truth in its start frame, the close policy (step limit, the
/// Ch. 4 rule of two features common with the previous map, finish()), the
/// odometry link (eq. 5.4), step reports, the information form, and local
/// maps of the committed grid196 rawlog checked for consistency and for the
/// previous-map matching made without landmark IDs.

#include <EsifTestSupport.h>
#include <LocalMapBuilderTestSupport.h>
#include <ParamsTestSupport.h>

#include <esif/association/Chi2.h>
#include <esif/core/Errors.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/RawlogReader.h>
#include <esif/localmap/LocalMapBuilder.h>
#include <esif/localmap/LocalMapBuilderParams.h>

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <set>
#include <vector>

namespace
{
using namespace esif;
namespace tb = esif::test::builder;

constexpr double kDeg = M_PI / 180.0;

// ---------------------------------------------------------------- parameters

TEST(LocalMapBuilderParams, PrefixedAssociationKeysLoad)
{
	const auto p = test::loadParamsText<LocalMapBuilderParams>(
		"joiner", "local_association = nn\nlocal_gate_chi2_quantile = 0.95\nlocal_map_steps = 30\n"
				  "local_map_link = odometry\n");
	EXPECT_EQ(p.association.association, EkfAssociation::NearestNeighbor);
	EXPECT_EQ(p.association.gate_chi2_quantile, 0.95);
	EXPECT_EQ(p.local_map_steps, 30);
	EXPECT_EQ(p.local_map_link, LocalMapLink::Odometry);
	// Untouched keys keep their defaults.
	EXPECT_EQ(p.association.new_landmark_chi2_quantile, EkfAssociationParams{}.new_landmark_chi2_quantile);

	// Every association key is listed with its prefix, none without.
	std::set<std::string> keys;
	for (const auto& info : describeParams(LocalMapBuilderParams{})) keys.insert(info.key);
	for (const auto& info : describeParams(EkfAssociationParams{}))
	{
		EXPECT_EQ(keys.count("local_" + info.key), 1u) << info.key;
		EXPECT_EQ(keys.count(info.key), 0u) << info.key;
	}
}

TEST(LocalMapBuilderParams, ErrorsNameTheKey)
{
	using test::paramsErrorOf;
	EXPECT_EQ(paramsErrorOf<LocalMapBuilderParams>("joiner", "local_map_steps = -1\n"),
			  "joiner.ini: [joiner] local_map_steps = -1: must be >= 0");
	EXPECT_EQ(paramsErrorOf<LocalMapBuilderParams>("joiner", "local_association = psychic\n"),
			  "joiner.ini: [joiner] local_association = psychic: must be one of auto|known_ids|nn|jcbb");
	EXPECT_EQ(paramsErrorOf<LocalMapBuilderParams>("joiner", "local_gate_chi2_quantile = 1\n"),
			  "joiner.ini: [joiner] local_gate_chi2_quantile = 1: must be in (0, 1)");
	// The unprefixed key is not a key of this section.
	EXPECT_NE(paramsErrorOf<LocalMapBuilderParams>("joiner", "association = nn\n").find("association"),
			  std::string::npos);
	EXPECT_EQ(paramsErrorOf<LocalMapBuilderParams>("joiner", "association = nn\n").find("local_association"),
			  std::string::npos);
}

// ---------------------------------------------------------- shared checks

/// Maps tile the log: contiguous first/last steps, counts that add up.
void expectTiling(const std::vector<LocalMap>& maps, std::size_t log_steps)
{
	ASSERT_FALSE(maps.empty());
	std::size_t total = 0;
	for (std::size_t k = 0; k < maps.size(); ++k)
	{
		SCOPED_TRACE(::testing::Message() << "map " << k + 1);
		EXPECT_EQ(maps[k].index, k + 1);
		EXPECT_EQ(maps[k].first_step, k == 0 ? 0 : maps[k - 1].last_step + 1);
		EXPECT_EQ(maps[k].last_step - maps[k].first_step + 1, maps[k].steps);
		total += maps[k].steps;
	}
	EXPECT_EQ(maps.back().last_step + 1, log_steps);
	EXPECT_EQ(total, log_steps);
}

/// One report per step with one association per measurement; the IDs of
/// the New and Matched ones are exactly the map's features, each started
/// once (so a feature renamed by previous-map matching is renamed in every
/// report), and the provisional reports processStep() returned differ from
/// them only by such renamings: one-to-one, and only for features flagged
/// in_earlier_maps.
void expectStepReports(const tb::BuiltMaps& built, const std::vector<StepInput>& steps)
{
	for (const LocalMap& map : built.maps)
	{
		SCOPED_TRACE(::testing::Message() << "map " << map.index);
		ASSERT_EQ(map.step_reports.size(), map.steps);
		std::map<LandmarkId, bool> earlier;
		for (const auto& f : map.features) earlier[f.id] = f.in_earlier_maps;
		std::map<LandmarkId, int> started;
		std::set<LandmarkId> used;
		std::map<LandmarkId, LandmarkId> provisional_to_final;
		std::size_t measurements = 0;
		for (std::size_t s = 0; s < map.steps; ++s)
		{
			const auto& step = steps.at(map.first_step + s);
			const std::size_t m = step.scan ? step.scan->measurements.size() : 0;
			measurements += m;
			const auto& final_assoc = map.step_reports[s].associations;
			const auto& prov_assoc = built.provisional_reports.at(map.first_step + s).associations;
			ASSERT_EQ(final_assoc.size(), m) << "step " << map.first_step + s;
			ASSERT_EQ(prov_assoc.size(), m);
			for (std::size_t i = 0; i < m; ++i)
			{
				const auto& a = final_assoc[i];
				EXPECT_EQ(a.kind, prov_assoc[i].kind);
				if (a.kind == Association::Kind::Rejected) continue;
				EXPECT_TRUE(earlier.count(a.id)) << "report id " << a.id << " is no feature of the map";
				if (a.kind == Association::Kind::New) ++started[a.id];
				used.insert(a.id);
				const auto [it, inserted] = provisional_to_final.emplace(prov_assoc[i].id, a.id);
				EXPECT_EQ(it->second, a.id) << "provisional id " << prov_assoc[i].id << " renamed two ways";
				if (prov_assoc[i].id != a.id)
				{
					EXPECT_TRUE(earlier[a.id]) << "renamed " << prov_assoc[i].id;
				}
			}
		}
		EXPECT_EQ(map.measurements, measurements);
		EXPECT_EQ(used.size(), map.features.size());
		for (const auto& f : map.features) EXPECT_EQ(started[f.id], 1) << "feature " << f.id;
		std::set<LandmarkId> finals;
		for (const auto& [prov, fin] : provisional_to_final) EXPECT_TRUE(finals.insert(fin).second) << fin;
	}
}

/// Information is the inverse of the covariance (which holds the documented
/// stabilisation: no robot variance below kMinRobotVariance), and validate()
/// passes. Residual ||I P - Id||: a Cholesky solve is backward stable, so it
/// is ~ n eps cond(P); the bound takes 100 n eps cond(P), and at least 1e-12.
void expectInformationIsInverse(const LocalMap& map, double* worst_residual = nullptr)
{
	SCOPED_TRACE(::testing::Message() << "map " << map.index);
	ASSERT_TRUE(map.covariance);
	EXPECT_NO_THROW(map.validate("test"));
	const Eigen::MatrixXd& P = *map.covariance;
	for (int r = 0; r < 3; ++r) EXPECT_GE(P(r, r), LocalMapBuilder::kMinRobotVariance);
	const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(P, Eigen::EigenvaluesOnly);
	const double cond = eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff();
	const double n = static_cast<double>(P.rows());
	const double residual = (map.information * P - Eigen::MatrixXd::Identity(P.rows(), P.cols())).cwiseAbs().maxCoeff();
	EXPECT_LT(residual, std::max(1e-12, 100 * n * 2.2e-16 * cond)) << "cond " << cond;
	EXPECT_EQ((map.information - map.information.transpose()).cwiseAbs().maxCoeff(), 0.0);  // symmetrised
	if (worst_residual) *worst_residual = std::max(*worst_residual, residual);
}

// ------------------------------------------------ noise-free simulations

/// Filter noise of the noise-free runs: any small positive value serves, the
/// innovations being zero but for round-off.
constexpr double kFilterStdRange = 1e-3, kFilterStdBearing = 0.01 * kDeg;

/// Round-off bound of a noise-free map against the truth: the estimate
/// differs from the truth only by the round-off of hundreds of compositions
/// and EKF updates on coordinates of ~30 m (eps * 30 m ~ 7e-15 per
/// operation); 1e-9 m (rad) leaves five orders of magnitude while a single
/// wrongly composed step is off by centimetres.
constexpr double kNoiseFreeTol = 1e-9;

struct TruthDeviation
{
	double pose = 0, feature = 0;
};

/// Every map against the truth in its start frame.
TruthDeviation expectMapsEqualTruth(const std::vector<LocalMap>& maps, const tb::SimulatedRun& run)
{
	TruthDeviation worst;
	const auto starts = tb::trueStartPoses(maps, run.true_poses);
	for (std::size_t k = 0; k < maps.size(); ++k)
	{
		SCOPED_TRACE(::testing::Message() << "map " << k + 1);
		const Pose2 end = inverseCompose(starts[k], run.true_poses[maps[k].last_step]);
		const double dp = std::max((maps[k].end_pose.head<2>() - end.head<2>()).norm(),
								   std::abs(wrapAngle(maps[k].end_pose.z() - end.z())));
		EXPECT_LT(dp, kNoiseFreeTol);
		worst.pose = std::max(worst.pose, dp);
		for (const auto& f : maps[k].features)
		{
			if (!run.features.count(f.id))
			{
				ADD_FAILURE() << "feature " << f.id << " is no true feature";
				continue;
			}
			const double df = (f.position - tb::inFrame(starts[k], run.features.at(f.id))).norm();
			EXPECT_LT(df, kNoiseFreeTol) << "feature " << f.id;
			worst.feature = std::max(worst.feature, df);
		}
	}
	return worst;
}

/// The exact close rule, for maps built with landmark IDs: map k (k >= 2)
/// closes at the first step at which it has taken `steps_limit` steps and
/// holds `min_common` features of map k-1 (map 1: the step limit alone);
/// the last map is the one that never got there and finish() emitted.
/// With `in_earlier_maps`, the common features are counted in maps 1..k-1.
void expectExactClosePolicy(const tb::BuiltMaps& built, int steps_limit, int min_common, bool in_earlier_maps = false)
{
	const auto& maps = built.maps;
	for (std::size_t k = 0; k < maps.size(); ++k)
	{
		SCOPED_TRACE(::testing::Message() << "map " << k + 1);
		std::set<LandmarkId> previous;
		for (std::size_t j = in_earlier_maps ? 0 : k - std::min<std::size_t>(k, 1); j < k; ++j)
			for (const auto& f : maps[j].features) previous.insert(f.id);
		std::set<LandmarkId> held;
		std::optional<std::size_t> close_after;	 // steps after which the rule fires
		for (std::size_t s = 0; s < maps[k].steps && !close_after; ++s)
		{
			for (const auto& a : maps[k].step_reports[s].associations)
				if (a.kind == Association::Kind::New) held.insert(a.id);
			std::size_t common = 0;
			for (const LandmarkId id : held) common += previous.count(id);
			if (s + 1 >= static_cast<std::size_t>(steps_limit) && (k == 0 || common >= static_cast<std::size_t>(min_common)))
				close_after = s + 1;
		}
		if (k + 1 < maps.size())
		{
			ASSERT_TRUE(close_after) << "closed although the rule never fired";
			EXPECT_EQ(maps[k].steps, *close_after);
		}
		else
		{
			// The last map: closed by the rule at the log's last step, or by finish().
			EXPECT_EQ(built.last_from_finish, !close_after || *close_after != maps[k].steps);
			if (close_after)
			{
				EXPECT_EQ(*close_after, maps[k].steps);
			}
		}
	}
}

/// Features of map k that are features of map k-1 (by ID).
std::size_t commonWithPrevious(const std::vector<LocalMap>& maps, std::size_t k)
{
	std::set<LandmarkId> previous;
	for (const auto& f : maps[k - 1].features) previous.insert(f.id);
	std::size_t n = 0;
	for (const auto& f : maps[k].features) n += previous.count(f.id);
	return n;
}

/// The featureless scenario without noise (simulated once for the tests
/// that share it): the robot crosses a 10 m band without features eight
/// times, so a common-features rule has to extend maps.
const auto& noiseFreeFeatureless()
{
	static const auto run = tb::simulateInMemory(
		tb::withoutNoise(tb::scenarioFromConfig("featureless")), kFilterStdRange, kFilterStdBearing);
	return run;
}

/// Maps of 30 steps that close only with 2 common features.
LocalMapBuilderParams thirtyStepsTwoCommon()
{
	LocalMapBuilderParams params;
	params.local_map_steps = 30;
	params.local_map_min_common_features = 2;
	return params;
}

TEST(LocalMapBuilderNoiseFree, MapsEqualTheTruthInTheirStartFrames)
{
	const auto& run = noiseFreeFeatureless();
	const LocalMapBuilderParams params = thirtyStepsTwoCommon();
	const auto built = tb::buildLocalMaps(params, run.steps);
	const auto& maps = built.maps;
	ASSERT_GT(maps.size(), 10u);

	const auto worst = expectMapsEqualTruth(maps, run);
	expectTiling(maps, run.steps.size());
	expectExactClosePolicy(built, 30, 2);
	expectStepReports(built, run.steps);
	std::size_t extended = 0, longest = 0;
	for (std::size_t k = 1; k + 1 < maps.size(); ++k)
	{
		EXPECT_GE(commonWithPrevious(maps, k), 2u) << "map " << k + 1;
		extended += maps[k].steps > 30;
		longest = std::max(longest, maps[k].steps);
	}
	for (const auto& m : maps) expectInformationIsInverse(m);
	std::cout << "noise-free featureless: " << maps.size() << " maps, " << extended
			  << " extended by the common-feature rule (longest " << longest << " steps), last "
			  << maps.back().steps << " steps (from finish(): " << built.last_from_finish
			  << "); largest deviation from the truth: pose " << worst.pose << ", feature " << worst.feature << "\n";
	// The band forces extensions: the rule is exercised, not vacuous.
	EXPECT_GT(extended, 0u);
	EXPECT_TRUE(built.last_from_finish);
}

TEST(LocalMapBuilderNoiseFree, CommonFeaturesCountedInEveryEarlierMapCloseMapsSooner)
{
	// Where the robot comes back to features mapped long before, the
	// previous map shares none with the new one but the earlier maps do, so
	// fewer maps are extended and none for longer.
	const auto& run = noiseFreeFeatureless();
	LocalMapBuilderParams params = thirtyStepsTwoCommon();
	const auto previous = tb::buildLocalMaps(params, run.steps);
	params.local_map_common_features_in = CommonFeaturesIn::EarlierMaps;
	const auto earlier = tb::buildLocalMaps(params, run.steps);
	expectTiling(earlier.maps, run.steps.size());
	expectExactClosePolicy(earlier, 30, 2, true);
	expectMapsEqualTruth(earlier.maps, run);
	const auto extendedSteps = [](const tb::BuiltMaps& b) {
		std::size_t n = 0;
		for (std::size_t k = 0; k + 1 < b.maps.size(); ++k) n += b.maps[k].steps - std::min<std::size_t>(b.maps[k].steps, 30);
		return n;
	};
	std::cout << "featureless, 30 steps + 2 common: " << previous.maps.size() << " maps (previous map), "
			  << earlier.maps.size() << " (earlier maps); steps beyond the limit " << extendedSteps(previous) << " / "
			  << extendedSteps(earlier) << "\n";
	EXPECT_GE(earlier.maps.size(), previous.maps.size());
	EXPECT_LE(extendedSteps(earlier), extendedSteps(previous));
}

TEST(LocalMapBuilderNoiseFree, StepLimitAloneGivesMapsOfExactlyNSteps)
{
	const auto run = tb::simulateInMemory(
		tb::withoutNoise(tb::scenarioFromConfig("small")), kFilterStdRange, kFilterStdBearing);
	for (const int N : {1, 7, 30, 200, 250})
	{
		SCOPED_TRACE(::testing::Message() << "N = " << N);
		LocalMapBuilderParams params;
		params.local_map_steps = N;
		const auto built = tb::buildLocalMaps(params, run.steps);
		const std::size_t T = run.steps.size();	 // 200
		ASSERT_EQ(built.maps.size(), (T + N - 1) / N);
		for (std::size_t k = 0; k + 1 < built.maps.size(); ++k) EXPECT_EQ(built.maps[k].steps, static_cast<std::size_t>(N));
		EXPECT_EQ(built.maps.back().steps, T - (built.maps.size() - 1) * N);
		// finish() emits the last map only when the rule did not close it.
		EXPECT_EQ(built.last_from_finish, T % N != 0);
		expectTiling(built.maps, T);
		expectMapsEqualTruth(built.maps, run);
		expectStepReports(built, run.steps);
	}
}

TEST(LocalMapBuilderNoiseFree, AllLimitsZeroIsOneMapOfTheWholeLog)
{
	const auto run = tb::simulateInMemory(
		tb::withoutNoise(tb::scenarioFromConfig("small")), kFilterStdRange, kFilterStdBearing);
	LocalMapBuilderParams params;
	params.local_map_steps = 0;
	const auto built = tb::buildLocalMaps(params, run.steps);
	ASSERT_EQ(built.maps.size(), 1u);
	EXPECT_TRUE(built.last_from_finish);
	EXPECT_EQ(built.maps[0].steps, run.steps.size());
	expectMapsEqualTruth(built.maps, run);
}

TEST(LocalMapBuilderNoiseFree, FeatureAndDistanceLimits)
{
	const auto run = tb::simulateInMemory(
		tb::withoutNoise(tb::scenarioFromConfig("small")), kFilterStdRange, kFilterStdBearing);
	{
		LocalMapBuilderParams params;
		params.local_map_steps = 0;
		params.local_map_max_features = 5;
		const auto built = tb::buildLocalMaps(params, run.steps);
		ASSERT_GT(built.maps.size(), 1u);
		for (std::size_t k = 0; k + 1 < built.maps.size(); ++k)
		{
			// Closed at the first step that brought it to >= 5 features.
			EXPECT_GE(built.maps[k].features.size(), 5u) << "map " << k + 1;
			std::size_t before_last = 0;
			for (std::size_t s = 0; s + 1 < built.maps[k].steps; ++s)
				for (const auto& a : built.maps[k].step_reports[s].associations) before_last += a.kind == Association::Kind::New;
			EXPECT_LT(before_last, 5u) << "map " << k + 1;
		}
		expectMapsEqualTruth(built.maps, run);
	}
	{
		// The noise-free odometry travels speed * dt = 0.1 m per step, so a
		// 1.95 m limit closes after 20 moving steps (19 make 1.9 m; the first
		// step's zero move counts none; 1.95 keeps clear of the round-off of
		// summing 0.1 twenty times).
		LocalMapBuilderParams params;
		params.local_map_steps = 0;
		params.local_map_max_distance_m = 1.95;
		const auto built = tb::buildLocalMaps(params, run.steps);
		ASSERT_GT(built.maps.size(), 2u);
		EXPECT_EQ(built.maps[0].steps, 21u);
		for (std::size_t k = 1; k + 1 < built.maps.size(); ++k) EXPECT_EQ(built.maps[k].steps, 20u) << "map " << k + 1;
		expectMapsEqualTruth(built.maps, run);
	}
}

TEST(LocalMapBuilderNoiseFree, OdometryLinkComposesToTheTruePoses)
{
	const auto run = tb::simulateInMemory(
		tb::withoutNoise(tb::scenarioFromConfig("small")), kFilterStdRange, kFilterStdBearing);
	LocalMapBuilderParams params;
	params.local_map_steps = 15;
	params.local_map_link = LocalMapLink::Odometry;
	const auto built = tb::buildLocalMaps(params, run.steps);
	const auto& maps = built.maps;
	ASSERT_GT(maps.size(), 5u);
	expectTiling(maps, run.steps.size());
	expectMapsEqualTruth(maps, run);  // start of map k >= 2 = true pose at its first step
	expectStepReports(built, run.steps);
	EXPECT_FALSE(maps[0].link);
	// Chain of the maps' own estimates from the global origin (the true start):
	// G_k = G_{k-1} (+) link_k (+) end_k gives the true pose at the map's last
	// step, and (G_{k-1} (+) link_k) (+) feature the true feature.
	Pose2 G = run.true_poses[0];
	double worst = 0;
	for (std::size_t k = 0; k < maps.size(); ++k)
	{
		SCOPED_TRACE(::testing::Message() << "map " << k + 1);
		Pose2 start = G;
		if (k > 0)
		{
			ASSERT_TRUE(maps[k].link);
			const auto& odo = *run.steps[maps[k].first_step].odometry;
			EXPECT_EQ(maps[k].link->delta, odo.delta);
			EXPECT_EQ(maps[k].link->cov, odo.cov);
			start = compose(G, maps[k].link->delta);
		}
		G = compose(start, maps[k].end_pose);
		const Pose2& truth = run.true_poses[maps[k].last_step];
		const double d = std::max((G.head<2>() - truth.head<2>()).norm(), std::abs(wrapAngle(G.z() - truth.z())));
		EXPECT_LT(d, kNoiseFreeTol);
		worst = std::max(worst, d);
		for (const auto& f : maps[k].features)
			EXPECT_LT((transformPoint(start, f.position) - run.features.at(f.id)).norm(), kNoiseFreeTol) << f.id;
		expectInformationIsInverse(maps[k]);
	}
	std::cout << "odometry link: " << maps.size() << " maps, composed end poses within " << worst << " of the truth\n";
}

TEST(LocalMapBuilderNoiseFree, OdometryLinkWithCommonFeatureRuleAndHiddenIds)
{
	// Without IDs the previous map's features must be carried through the
	// link into the open map's frame to be recognised; the rule then holds.
	auto run = tb::simulateInMemory(
		tb::withoutNoise(tb::scenarioFromConfig("small")), kFilterStdRange, kFilterStdBearing);
	std::vector<std::vector<std::optional<LandmarkId>>> true_ids;
	for (auto& step : run.steps)
	{
		true_ids.emplace_back();
		for (auto& m : step.scan->measurements) true_ids.back().push_back(m.id), m.id.reset();
	}
	LocalMapBuilderParams params;
	params.local_map_steps = 15;
	params.local_map_min_common_features = 2;
	params.local_map_link = LocalMapLink::Odometry;
	const auto built = tb::buildLocalMaps(params, run.steps);
	const auto& maps = built.maps;
	ASSERT_GT(maps.size(), 5u);
	std::size_t matched = 0;
	for (std::size_t k = 1; k < maps.size(); ++k)
	{
		const auto truth_k = tb::trueIdsOfFeatures(maps[k], true_ids);
		const auto truth_prev = tb::trueIdsOfFeatures(maps[k - 1], true_ids);
		if (k + 1 < maps.size())
		{
			EXPECT_GE(commonWithPrevious(maps, k), 2u) << "map " << k + 1;
		}
		for (const auto& f : maps[k].features)
			if (f.in_earlier_maps)
			{
				++matched;
				EXPECT_EQ(truth_k.at(f.id), truth_prev.at(f.id)) << "map " << k + 1 << " feature " << f.id;
			}
	}
	EXPECT_GE(matched, 2 * (maps.size() - 2));  // two per map but the last, at least
	expectStepReports(built, run.steps);
}

namespace
{
/// The steps of every map built from `steps` with hidden IDs, the close
/// rule needing two common features counted in earlier maps, and the
/// joining filter's count of own features in its global map given by `counter`.
std::vector<std::size_t> mapLengthsWithCounter(const std::vector<StepInput>& steps,
											   LocalMapBuilder::OwnFeaturesInGlobalMap counter)
{
	LocalMapBuilderParams params;
	params.local_map_steps = 15;
	params.local_map_min_common_features = 2;
	params.local_map_common_features_in = CommonFeaturesIn::EarlierMaps;
	LocalMapBuilder builder(params);
	if (counter) builder.countOwnFeaturesWith(std::move(counter));
	std::vector<std::size_t> lengths;
	for (const auto& step : steps)
	{
		builder.processStep(step);
		if (const auto map = builder.takeClosedMap()) lengths.push_back(map->steps);
	}
	if (const auto last = builder.finish()) lengths.push_back(last->steps);
	return lengths;
}
}  // namespace

TEST(LocalMapBuilderNoiseFree, HiddenIdsCountOwnFeaturesWithTheJoiningFiltersCounter)
{
	auto run = tb::simulateInMemory(
		tb::withoutNoise(tb::scenarioFromConfig("small")), kFilterStdRange, kFilterStdBearing);
	for (auto& step : run.steps)
		for (auto& m : step.scan->measurements) m.id.reset();
	const std::size_t n = run.steps.size();
	ASSERT_GT(n, 60u);

	// The filter's count decides: two known features close every map at 15
	// steps; none never lets map 2 close.
	const auto counted = mapLengthsWithCounter(run.steps, [](const LandmarkEkf&, const std::set<LandmarkId>& own) {
		return std::optional<std::size_t>(std::min<std::size_t>(2, own.size()));
	});
	ASSERT_GE(counted.size(), n / 15);
	for (std::size_t k = 0; k + 1 < counted.size(); ++k) EXPECT_EQ(counted[k], 15u) << "map " << k + 1;
	const auto never = mapLengthsWithCounter(run.steps, [](const LandmarkEkf&, const std::set<LandmarkId>&) {
		return std::optional<std::size_t>(0);
	});
	EXPECT_EQ(never, (std::vector<std::size_t>{15, n - 15}));

	// A filter that cannot tell leaves the rule to the previous-map match.
	const auto undecided = mapLengthsWithCounter(
		run.steps, [](const LandmarkEkf&, const std::set<LandmarkId>&) { return std::optional<std::size_t>(); });
	EXPECT_EQ(undecided, mapLengthsWithCounter(run.steps, nullptr));
}

TEST(LocalMapBuilderNoiseFree, ScansWithAndWithoutIdsKeepTheirFeaturesApart)
{
	// A recorded association (`--associations-from`) takes the ID off every
	// measurement its run rejected, so a log can hold scans with IDs and
	// scans without; here the first five steps of every 30 lose theirs. The
	// builder numbers the features of the scans without IDs above the log's
	// IDs (reserveIdsUpTo, as the host asks every plugin), so no number names
	// a feature a later ID names; and a numbered feature matched to the
	// previous map keeps its number when a feature of its map holds that
	// map's ID already (the same landmark seen without and with its ID).
	// Before, the first map's features 1, 2 and 4, numbered by the builder,
	// took the log's IDs 1, 2 and 4, whose measurements the ID gate then
	// rejected, and map 2 held feature 6 twice.
	auto run = tb::simulateInMemory(
		tb::withoutNoise(tb::scenarioFromConfig("small")), kFilterStdRange, kFilterStdBearing);
	LandmarkId largest = 0;
	for (auto& step : run.steps)
		for (auto& m : step.scan->measurements)
		{
			largest = std::max(largest, *m.id);
			if (step.index % 30 < 5) m.id.reset();
		}
	LocalMapBuilderParams params;
	params.local_map_steps = 30;
	LocalMapBuilder builder(params);
	builder.reserveIdsUpTo(largest);
	tb::BuiltMaps built;
	for (const auto& step : run.steps)
	{
		ASSERT_NO_THROW(built.provisional_reports.push_back(builder.processStep(step))) << "step " << step.index;
		if (auto m = builder.takeClosedMap()) built.maps.push_back(std::move(*m));
	}
	if (auto m = builder.finish()) built.maps.push_back(std::move(*m)), built.last_from_finish = true;
	ASSERT_GE(built.maps.size(), 3u);
	expectStepReports(built, run.steps);
	// Noise-free: every measurement that carries an ID is used on the feature of that ID.
	for (std::size_t k = 0; k < run.steps.size(); ++k)
		for (std::size_t i = 0; i < run.steps[k].scan->measurements.size(); ++i)
			if (const auto id = run.steps[k].scan->measurements[i].id)
			{
				EXPECT_NE(built.provisional_reports[k].associations[i].kind, Association::Kind::Rejected)
					<< "step " << k << ", ID " << *id;
				EXPECT_EQ(built.provisional_reports[k].associations[i].id, *id) << "step " << k;
			}
}

// -------------------------------------------------------- information form

TEST(LocalMapBuilder, StationaryRobotGetsTheDocumentedStabilisation)
{
	// Three scans from the origin, no odometry: the robot pose is exactly
	// known, so the filter's covariance has a zero 3x3 robot block.
	LocalMapBuilderParams params;
	params.local_map_steps = 0;
	LocalMapBuilder builder(params);
	for (std::size_t k = 0; k < 3; ++k)
	{
		StepInput s;
		s.index = k;
		s.scan = Scan{};
		for (LandmarkId id = 0; id < 3; ++id)
		{
			RangeBearing m;
			m.range_m = 2.0 + static_cast<double>(id);
			m.bearing_rad = -0.5 + 0.5 * static_cast<double>(id);
			m.cov = Eigen::Vector2d(0.01, 1e-4).asDiagonal();
			m.id = id;
			s.scan->measurements.push_back(m);
		}
		builder.processStep(s);
	}
	const Eigen::MatrixXd filter_cov = builder.openMap().core().covariance();
	ASSERT_EQ(filter_cov.rows(), 9);
	EXPECT_EQ((filter_cov.topLeftCorner<3, 3>().cwiseAbs().maxCoeff()), 0.0);
	EXPECT_EQ(filter_cov.topRightCorner(3, 6).cwiseAbs().maxCoeff(), 0.0);
	EXPECT_NE(Eigen::LLT<Eigen::MatrixXd>(filter_cov).info(), Eigen::Success);	// singular as it is

	std::optional<LocalMap> closed;
	ASSERT_NO_THROW(closed = builder.finish());
	ASSERT_TRUE(closed && closed->covariance);
	const LocalMap& map = *closed;
	const double k = LocalMapBuilder::kMinRobotVariance;
	// Covariance: the filter's, with kMinRobotVariance on the robot diagonal.
	Eigen::MatrixXd expected = filter_cov;
	expected.topLeftCorner<3, 3>() = k * Eigen::Matrix3d::Identity();
	EXPECT_EQ((*map.covariance - expected).cwiseAbs().maxCoeff(), 0.0);
	EXPECT_NO_THROW(map.validate("test"));
	// Information = blockdiag(I3 / kMinRobotVariance, features' inverse): the
	// inverse of a block-diagonal matrix; relative round-off of one LLT of a
	// well-conditioned matrix (cond 1e6 / 1e-3 ~ 1e9 only through the
	// decoupled robot block), bound 1e-12 relative.
	const double robot_info_dev =
		(map.information.topLeftCorner<3, 3>() - Eigen::Matrix3d::Identity() / k).cwiseAbs().maxCoeff();
	EXPECT_LT(robot_info_dev, 1e-12 / k);
	EXPECT_LT(map.information.topRightCorner(3, 6).cwiseAbs().maxCoeff(), 1e-12);
	const Eigen::MatrixXd Pf = filter_cov.bottomRightCorner(6, 6);
	EXPECT_LT((map.information.bottomRightCorner(6, 6) * Pf - Eigen::MatrixXd::Identity(6, 6)).cwiseAbs().maxCoeff(), 1e-12);
	expectInformationIsInverse(map);
}

TEST(LocalMapBuilder, FinishWithoutStepsGivesNothing)
{
	LocalMapBuilder builder(LocalMapBuilderParams{});
	EXPECT_FALSE(builder.finish());
	EXPECT_FALSE(builder.takeClosedMap());
	EXPECT_EQ(builder.openMapIndex(), 1u);
}

// ------------------------------------------------------------- grid196

const std::string kGrid196 = test::sourcePath("rawlogs/grid196.rawlog");

struct Grid196
{
	Rawlog log;
	GroundTruth truth;	// world frame
};

const Grid196& grid196(bool hide_ids)
{
	static std::map<bool, Grid196> cache;
	auto it = cache.find(hide_ids);
	if (it == cache.end())
	{
		RawlogReadOptions opts;
		opts.hide_landmark_ids = hide_ids;
		Grid196 g{readRawlog(kGrid196, opts), *loadGroundTruth(groundTruthPrefixFor(kGrid196))};
		it = cache.emplace(hide_ids, std::move(g)).first;
	}
	return it->second;
}

TEST(LocalMapBuilderGrid196, ThirtyStepMapsAreConsistent)
{
	const auto& g = grid196(false);
	ASSERT_EQ(g.truth.path.size(), g.log.steps.size());
	LocalMapBuilderParams params;
	params.local_map_steps = 30;
	const auto built = tb::buildLocalMaps(params, g.log.steps);
	const auto& maps = built.maps;
	ASSERT_EQ(maps.size(), 100u);  // 3000 / 30
	expectTiling(maps, g.log.steps.size());
	expectStepReports(built, g.log.steps);

	// NEES of every feature against the truth in its map's true start frame,
	// with the map's marginal covariance. A consistent filter is below the
	// 95% chi-square bound (2 dof) for 95% of the entries, but the features
	// of one map share its heading error, so the 996 entries are worth about
	// 100 independent ones: the fraction scatters by ~2% around its mean. EKF
	// SLAM is also slightly over-confident (book Sec. 1.3.3; here, heading
	// errors of ~3 sigma in 4 of the 100 maps): over seeds 1-6 of this
	// scenario the fraction is 93.0-95.6% (mean 93.9%; seed 1, the committed
	// rawlog: 93.1%). As for the EKF plugin on the whole log, 90% is required:
	// a wrong frame or a wrong covariance block gives a few percent or less.
	const auto starts = tb::trueStartPoses(maps, g.truth.path);
	const double bound = chi2Quantile(0.95, 2);
	std::size_t entries = 0, below = 0, pose_entries = 0, pose_below = 0;
	double worst_residual = 0;
	for (std::size_t k = 0; k < maps.size(); ++k)
	{
		const auto& map = maps[k];
		ASSERT_TRUE(map.covariance);
		for (std::size_t i = 0; i < map.features.size(); ++i)
		{
			const auto& f = map.features[i];
			const Eigen::Vector2d e = f.position - tb::inFrame(starts[k], g.truth.landmarks.at(f.id));
			const Eigen::Matrix2d Pi = map.covariance->block<2, 2>(3 + 2 * i, 3 + 2 * i);
			const double nees = e.dot(Pi.ldlt().solve(e));
			++entries;
			below += nees < bound;
		}
		Eigen::Vector3d e = map.end_pose - inverseCompose(starts[k], g.truth.path[map.last_step]);
		e.z() = wrapAngle(e.z());
		++pose_entries;
		pose_below += e.dot(map.covariance->topLeftCorner<3, 3>().ldlt().solve(e)) < chi2Quantile(0.95, 3);
		expectInformationIsInverse(map, &worst_residual);
	}
	const double fraction = static_cast<double>(below) / static_cast<double>(entries);
	std::cout << "grid196, 30-step maps: feature NEES below the 95% bound for " << below << " of " << entries << " ("
			  << fraction << "); end poses " << pose_below << " of " << pose_entries
			  << "; largest |I P - Id| " << worst_residual << "\n";
	EXPECT_GE(fraction, 0.90);
	// End poses: 100 entries only, so the same 95% less two binomial sigmas (4.4%).
	EXPECT_GE(static_cast<double>(pose_below) / static_cast<double>(pose_entries), 0.9);
}

/// The two-common-features rule on grid196: map by map, and exactly as stated.
TEST(LocalMapBuilderGrid196, CommonFeatureRuleWithIds)
{
	const auto& g = grid196(false);
	LocalMapBuilderParams params;
	params.local_map_steps = 30;
	params.local_map_min_common_features = 2;
	const auto built = tb::buildLocalMaps(params, g.log.steps);
	const auto& maps = built.maps;
	expectTiling(maps, g.log.steps.size());
	expectExactClosePolicy(built, 30, 2);
	expectStepReports(built, g.log.steps);
	std::size_t min_common = 1000, extended = 0;
	for (std::size_t k = 1; k + 1 < maps.size(); ++k)
	{
		EXPECT_GE(commonWithPrevious(maps, k), 2u) << "map " << k + 1;
		min_common = std::min(min_common, commonWithPrevious(maps, k));
		extended += maps[k].steps > 30;
	}
	std::cout << "grid196 with IDs, rule 30 steps + 2 common: " << maps.size() << " maps, " << extended
			  << " extended, fewest common " << min_common << ", last " << maps.back().steps << " steps\n";
}

/// Without IDs (hidden, JCBB inside the maps, PreviousMapMatcher across
/// them): the rule holds by the builder's IDs, and every previous-map match
/// is checked against the true IDs behind the measurements.
struct MatchRun
{
	EkfAssociation association = EkfAssociation::Jcbb;
	int min_common = 2;
	LocalMapLink link = LocalMapLink::SharedPose;
	const char* label = "";
};

void expectGeometricMatchesRight(const Grid196& g, const MatchRun& run)
{
	LocalMapBuilderParams params;
	params.local_map_steps = 30;
	params.local_map_min_common_features = run.min_common;
	params.local_map_link = run.link;
	params.association.association = run.association;
	const auto built = tb::buildLocalMaps(params, g.log.steps);
	const auto& maps = built.maps;
	expectTiling(maps, g.log.steps.size());
	expectStepReports(built, g.log.steps);
	if (run.min_common > 0)
	{
		// With IDs the same rule gives 22 maps: maps 1-21 of 30 steps, then
		// map 22 takes the remaining 2370 steps because map 21 holds only
		// features 1-4 of the bottom row, three of which are never seen
		// again. Matching that missed common features would close maps
		// later, hence fewer of them.
		ASSERT_GE(maps.size(), 20u);
	}
	else
	{
		ASSERT_EQ(maps.size(), 100u);
	}

	std::size_t matched = 0, wrong = 0, missed = 0, mixed = 0;
	auto truth_prev = tb::trueIdsOfFeatures(maps[0], g.log.true_ids);
	for (std::size_t k = 1; k < maps.size(); ++k)
	{
		SCOPED_TRACE(::testing::Message() << "map " << k + 1);
		const auto truth_k = tb::trueIdsOfFeatures(maps[k], g.log.true_ids);
		if (k + 1 < maps.size())
		{
			EXPECT_GE(commonWithPrevious(maps, k), static_cast<std::size_t>(run.min_common));
		}
		// Common IDs are exactly the features matched to the previous map.
		EXPECT_EQ(commonWithPrevious(maps, k), maps[k].featuresInEarlierMaps());
		std::set<LandmarkId> true_prev;
		for (const auto& [id, t] : truth_prev) true_prev.insert(t);
		for (const auto& f : maps[k].features)
		{
			const LandmarkId t = truth_k.at(f.id);
			mixed += t == -2;
			if (f.in_earlier_maps)
			{
				++matched;
				wrong += !truth_prev.count(f.id) || truth_prev.at(f.id) != t;
			}
			else
				missed += true_prev.count(t);
		}
		truth_prev = truth_k;
	}
	std::cout << "grid196 without IDs (" << run.label << "): " << maps.size() << " maps, " << matched
			  << " previous-map matches, " << wrong << " wrong, " << missed << " missed; " << mixed
			  << " features with measurements of two true landmarks\n";
	EXPECT_EQ(wrong, 0u);
	// A match is missed only when the gate cannot decide it; most are found.
	EXPECT_LT(missed, matched / 10);
}

TEST(LocalMapBuilderGrid196, CommonFeatureRuleWithHiddenIdsMatchesRight)
{
	expectGeometricMatchesRight(grid196(true), {EkfAssociation::Jcbb, 2, LocalMapLink::SharedPose, "jcbb, rule"});
}

TEST(LocalMapBuilderGrid196, CommonFeatureRuleWithHiddenIdsNearestNeighbour)
{
	expectGeometricMatchesRight(
		grid196(true), {EkfAssociation::NearestNeighbor, 2, LocalMapLink::SharedPose, "nn, rule"});
}

TEST(LocalMapBuilderGrid196, PreviousMapMatchingOnEveryClose)
{
	// Without the rule: 100 maps of 30 steps, each matched to the one before
	// (99 closes), with a shared pose and through an odometry link.
	expectGeometricMatchesRight(grid196(true), {EkfAssociation::Jcbb, 0, LocalMapLink::SharedPose, "jcbb, 30 steps"});
	expectGeometricMatchesRight(
		grid196(true), {EkfAssociation::Jcbb, 0, LocalMapLink::Odometry, "jcbb, 30 steps, odometry link"});
}

TEST(LocalMapBuilderGrid196, DistanceAssociationIgnoresIdsPresentInTheLog)
{
	// IDs in the log but local_association = jcbb: the filter numbers every
	// feature itself, so the builder must match them to the previous map
	// geometrically, exactly as when the IDs are hidden.
	expectGeometricMatchesRight(
		grid196(false), {EkfAssociation::Jcbb, 2, LocalMapLink::SharedPose, "jcbb, rule, IDs in the log"});
}

}  // namespace
