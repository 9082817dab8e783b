#pragma once
/// \file LocalMapJoiner.h
/// The second, small interface of the map-joining plugins (book Ch. 4-5):
/// they fuse a sequence of local maps. A joining plugin derives from both
/// FilterPlugin (fed with steps, it builds its own local maps with the
/// framework's LocalMapBuilder) and LocalMapJoiner (fed with local maps read
/// from files by `esif run --local-maps DIR`). The host tells a joiner by
/// this interface (dynamic_cast), never by its name.
///
/// Notes to implementers:
/// - On local-map input the host calls configure(), then joinLocalMap() for
///   k = 1, 2, ... in order, then finish(); processStep() is not called.
///   robotPose() and estimate() then describe the last fused map's end pose
///   and the global map.
/// - Throw NumericalError naming the map for numerical failure.

#include <esif/core/Estimate.h>
#include <esif/localmap/LocalMap.h>
#include <esif/localmap/LocalMapBuilderParams.h>

#include <cstddef>
#include <vector>

namespace esif
{
/// The cost of fusing one local map (book Fig. 5.7-5.8, 4.14-4.15).
struct LocalMapFusionCost
{
	std::size_t map = 0;  ///< k
	double total_s = 0;	 ///< the whole fusion of the map [s]
	double association_s = 0;  ///< of which data association (with its covariance recovery) [s]
	std::size_t state_dim = 0;	///< global state dimension after the fusion
};

class LocalMapJoiner
{
   public:
	virtual ~LocalMapJoiner();

	/// How this plugin builds local maps from a rawlog (its configured
	/// builder parameters); `esif localmaps build --config` uses them.
	virtual LocalMapBuilderParams localMapBuilderParams() const = 0;

	/// Fuses local map `map` (k = map.index, in order from 1) into the global map.
	virtual void joinLocalMap(const LocalMap& map) = 0;

	/// Global estimate of the end pose of every fused map (index k-1), with
	/// its marginal covariance where known (after finish(): every one).
	virtual std::vector<PoseEstimate> endPoses() const = 0;

	/// What the fusion of map k did with each of its features, in the map's
	/// feature order: New (started global landmark `id`), Matched (fused
	/// into global landmark `id`) or Rejected (left out). Empty before map k
	/// is fused. The host writes these to associations.txt (as "step" k,
	/// "measurement" i) and scores them against the files' feature IDs.
	virtual StepReport mapReport(std::size_t k) const = 0;

	/// Cost of every fusion so far, in order.
	virtual std::vector<LocalMapFusionCost> fusionCosts() const = 0;
};

}  // namespace esif
