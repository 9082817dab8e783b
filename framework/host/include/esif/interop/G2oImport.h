#pragma once
/// \file G2oImport.h
/// A solution in g2o form (the file `esif export g2o` wrote, or a solver's
/// optimised output with the same vertices) made into a run folder's
/// trajectory.tum and landmarks.txt, which `esif compare --reference` and
/// the other readers of run outputs (RunOutputReader.h) take. A g2o file has
/// no timestamps, so the rawlog it was exported from gives each step's time
/// and the pose current after it (FullSlamProblem.h); it has no marginal
/// covariances either: landmarks.txt holds `nan` for them.

#include <esif/core/Estimate.h>
#include <esif/formats/FullSlamProblem.h>
#include <esif/formats/G2oFormat.h>
#include <esif/formats/RunRecord.h>

#include <string>
#include <vector>

namespace esif
{
struct G2oSolution
{
	std::vector<TrajectoryPoint> trajectory;  ///< one pose per rawlog step
	Estimate estimate;	///< robot = the last pose; landmarks by ID, covariance NaN
};

/// Maps `graph`'s vertices onto `problem`'s steps (vertex IDs: G2oFormat.h).
/// Throws InputError naming `path` when a pose vertex 0..P-1 is missing, a
/// pose vertex lies beyond P-1, or a point vertex below P.
G2oSolution solutionFromG2o(const G2oGraph& graph, const FullSlamProblem& problem, const std::string& path);

struct G2oImportSummary
{
	std::size_t poses = 0;
	std::size_t steps = 0;
	std::size_t landmarks = 0;
};

/// Reads `g2o_path` and `rawlog_path` and writes OUT/trajectory.tum and
/// OUT/landmarks.txt as one all-or-nothing run folder (RunFolder.h).
G2oImportSummary importG2oSolution(
	const std::string& g2o_path, const std::string& rawlog_path, const std::string& out_dir);

}  // namespace esif
