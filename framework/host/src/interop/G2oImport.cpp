/// \file G2oImport.cpp
/// A g2o solution written back as run outputs, with the writers `esif run` uses.

#include <esif/core/Errors.h>
#include <esif/formats/MapWriter.h>
#include <esif/interop/G2oImport.h>
#include <esif/safeio/OutputApart.h>
#include <esif/safeio/RunFolder.h>

#include <filesystem>
#include <limits>

namespace esif
{
namespace
{
std::vector<Pose2> posesOf(const G2oGraph& graph, std::size_t count, const std::string& path)
{
	std::vector<Pose2> poses;
	for (std::size_t i = 0; i < count; ++i)
	{
		const auto it = graph.poses.find(static_cast<long long>(i));
		if (it == graph.poses.end())
			throw InputError(
				path + ": no VERTEX_SE2 " + std::to_string(i) + " (the rawlog's problem has poses 0.." +
				std::to_string(count - 1) + ")");
		poses.push_back(it->second);
	}
	if (!graph.poses.empty() && graph.poses.rbegin()->first >= static_cast<long long>(count))
		throw InputError(
			path + ": VERTEX_SE2 " + std::to_string(graph.poses.rbegin()->first) + ", but the rawlog's problem has " +
			std::to_string(count) + " poses (a file of another rawlog?)");
	return poses;
}

/// The landmark vertices, which must be exactly the problem's landmarks
/// (vertex P + ID, P poses): a file of another rawlog, or with the IDs
/// shifted, would otherwise be scored against unrelated landmarks.
std::vector<LandmarkEstimate> landmarksOf(const G2oGraph& graph, const FullSlamProblem& problem, const std::string& path)
{
	const double nan = std::numeric_limits<double>::quiet_NaN();
	const auto pose_count = static_cast<long long>(problem.poses.size());
	std::vector<LandmarkEstimate> out;
	for (const auto& [vertex, position] : graph.points)
	{
		if (vertex < pose_count)
			throw InputError(
				path + ": VERTEX_XY " + std::to_string(vertex) + " has a pose's ID (landmark vertices are " +
				std::to_string(pose_count) + " + landmark ID)");
		if (!problem.landmarks.count(vertex - pose_count))
			throw InputError(
				path + ": VERTEX_XY " + std::to_string(vertex) + " is landmark " + std::to_string(vertex - pose_count) +
				", which the rawlog's problem does not have (a file of another rawlog?)");
		LandmarkEstimate l;
		l.id = vertex - pose_count;
		l.mean = position;
		l.cov << nan, nan, nan, nan;
		out.push_back(l);
	}
	for (const auto& [id, initial] : problem.landmarks)
		if (!graph.points.count(pose_count + id))
			throw InputError(
				path + ": no VERTEX_XY " + std::to_string(pose_count + id) + " for landmark " + std::to_string(id) +
				" of the rawlog's problem (" + std::to_string(problem.landmarks.size()) + " landmarks, vertices " +
				std::to_string(pose_count) + " + ID)");
	return out;
}
}  // namespace

G2oSolution solutionFromG2o(const G2oGraph& graph, const FullSlamProblem& problem, const std::string& path)
{
	const std::vector<Pose2> poses = posesOf(graph, problem.poses.size(), path);
	G2oSolution s;
	for (std::size_t k = 0; k < problem.step_pose.size(); ++k)
	{
		TrajectoryPoint p;
		p.step = k;
		p.time_s = problem.step_time_s[k];
		p.pose.mean = poses[problem.step_pose[k]];
		s.trajectory.push_back(p);
	}
	s.estimate.landmarks = landmarksOf(graph, problem, path);
	if (!s.trajectory.empty()) s.estimate.robot = s.trajectory.back().pose;
	return s;
}

G2oImportSummary importG2oSolution(
	const std::string& g2o_path, const std::string& rawlog_path, const std::string& out_dir)
{
	requireOutputApart(out_dir, {{"the g2o file", g2o_path}, {"the rawlog", rawlog_path}});
	const G2oGraph graph = readG2oFile(g2o_path);
	const FullSlamProblem problem = buildFullSlamProblem(readRawlog(rawlog_path));
	const G2oSolution solution = solutionFromG2o(graph, problem, g2o_path);
	writeRunFolder(out_dir, {"trajectory.tum", "landmarks.txt"}, [&](const std::string& staging) {
		writeTrajectoryTum(solution.trajectory, (std::filesystem::path(staging) / "trajectory.tum").string());
		writeLandmarksTxt(solution.estimate, (std::filesystem::path(staging) / "landmarks.txt").string());
		return 0;
	});
	return {problem.poses.size(), solution.trajectory.size(), solution.estimate.landmarks.size()};
}

}  // namespace esif
