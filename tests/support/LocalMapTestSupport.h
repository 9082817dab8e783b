#pragma once
/// \file LocalMapTestSupport.h
/// Helpers of the local-map host tests: hand-made local maps, a reference
/// result written in the authors' layout, the test-only joining plugin's
/// folder and configs, and stats.json read back.

#include <esif/formats/StatsJson.h>
#include <esif/localmap/LocalMap.h>

#include <Eigen/Core>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace esif::test
{
/// A feature of a hand-made map: file ID and position in the map's frame.
struct TestFeature
{
	LandmarkId id;
	double x, y;
};

/// Local map k with the given end pose and features, every variable
/// independent with standard deviation `sigma` (information 1/sigma^2 I).
inline LocalMap makeLocalMap(
	std::size_t k, const Pose2& end_pose, const std::vector<TestFeature>& features, double sigma = 0.1)
{
	LocalMap map;
	map.index = k;
	map.end_pose = end_pose;
	for (const auto& f : features) map.features.push_back({f.id, Eigen::Vector2d(f.x, f.y), false});
	const auto n = static_cast<Eigen::Index>(map.stateDim());
	map.information = Eigen::MatrixXd::Identity(n, n) / (sigma * sigma);
	return map;
}

/// Local map `index` with `features` random features spread along x (3 m
/// apart, 1 m noise) and a random, well-conditioned SPD information matrix:
/// for tests of algebra that must hold for any map.
inline LocalMap randomLocalMap(std::size_t index, int features, unsigned seed)
{
	std::mt19937 rng(seed);
	std::normal_distribution<double> n(0, 1);
	LocalMap map;
	map.index = index;
	map.end_pose = Pose2(2 + n(rng), n(rng), 0.3 * n(rng));
	for (int i = 0; i < features; ++i)
		map.features.push_back({10 + i, Eigen::Vector2d(3 * i + n(rng), 3 * n(rng)), false});
	const int d = 3 + 2 * features;
	Eigen::MatrixXd A(d, d);
	for (int r = 0; r < d; ++r)
		for (int c = 0; c < d; ++c) A(r, c) = n(rng);
	map.information = A * A.transpose() + d * Eigen::MatrixXd::Identity(d, d);
	return map;
}

/// Writes DIR/feature.txt (`id x y`) and DIR/pose.txt (`k x y phi`) with
/// full precision, the layout of the authors' Linear SLAM result.
inline void writeReferenceResult(
	const std::string& dir, const std::map<LandmarkId, Eigen::Vector2d>& features,
	const std::map<std::size_t, Pose2>& poses)
{
	std::ofstream f(dir + "/feature.txt"), p(dir + "/pose.txt");
	char buf[128];
	for (const auto& [id, xy] : features)
	{
		std::snprintf(buf, sizeof(buf), "%lld %.17g %.17g\n", static_cast<long long>(id), xy.x(), xy.y());
		f << buf;
	}
	for (const auto& [k, pose] : poses)
	{
		std::snprintf(buf, sizeof(buf), "%zu %.17g %.17g %.17g\n", k, pose.x(), pose.y(), pose.z());
		p << buf;
	}
}

/// stats.json of a run folder.
inline Stats readStatsJson(const std::string& run_dir)
{
	std::ifstream in(run_dir + "/stats.json");
	std::stringstream ss;
	ss << in.rdbuf();
	return Stats::fromJson(ss.str(), run_dir + "/stats.json");
}

#ifdef ESIF_TEST_PLUGIN_DIR
/// `--plugin-dir` of the test-only plugins (DeadReckoningJoiner), which are
/// not in the host's plugin folder.
inline std::string testPluginDirOption() { return std::string("--plugin-dir '") + ESIF_TEST_PLUGIN_DIR + "'"; }
#endif

/// INI text for the test joiner: `[esif]` with `esif_extra` lines, then its section with `section_extra`.
inline std::string joinerConfig(const std::string& esif_extra = "", const std::string& section_extra = "")
{
	return "[esif]\nplugin = test::DeadReckoningJoiner\n" + esif_extra + "\n[dead_reckoning_joiner]\n" + section_extra;
}

}  // namespace esif::test
