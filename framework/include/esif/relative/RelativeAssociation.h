#pragma once
/// \file RelativeAssociation.h
/// D-SLAM data association without landmark IDs (book Sec. 3.4.2):
/// 1. hypotheses by maximum likelihood (MRPT nearest neighbour or JCBB)
///    from the current pose estimate, with the correlations between the
///    robot pose and the map taken as zero (the map is not correlated with
///    the pose in D-SLAM);
/// 2. verification of the matched set by the chi-square test on relative
///    distances and angles among the features, eq. (3.40)-(3.45), which a
///    pose error cannot pass or fail. When the test fails, the match whose
///    removal best restores consistency is dropped, and the test repeated.
/// Only the candidate features' covariance blocks are recovered from the map.
/// Serves D-SLAM (Ch. 3) and D-SLAM map joining (Ch. 4), whose map is the
/// same feature-only EIF.

#include <esif/core/Estimate.h>
#include <esif/core/StepInput.h>
#include <esif/relative/FeatureMap.h>
#include <esif/relative/ReferencePair.h>
#include <esif/relative/RelativeAssociationParams.h>

#include <cstddef>

namespace esif::relative
{
class RelativeAssociation
{
   public:
	/// `reference_rules` choose the pair the relative test measures angles
	/// from (the map update's rules: the same linearisation on both sides).
	RelativeAssociation(const RelativeAssociationParams& params, const ReferenceRules& reference_rules);

	/// One decision per measurement of `scan`: Matched (with the map ID),
	/// New (id -1: the caller names it) or Rejected.
	StepReport associate(const Scan& scan, const Pose2& robot, const Eigen::Matrix3d& robot_cov, FeatureMap& map);

	std::size_t jcbbNodes() const { return jcbb_nodes_; }
	/// Scans too ambiguous for JCBB (SearchBounds): their hypotheses came from
	/// nearest neighbour with the joint compatibility test, then eq. (3.45).
	std::size_t jcbbFallbacks() const { return jcbb_fallbacks_; }
	/// Matches dropped because the relative test, eq. (3.45), failed.
	std::size_t droppedByRelativeTest() const { return dropped_; }

   private:
	struct Match
	{
		int measurement = 0;
		int candidate = 0;
	};
	std::vector<LandmarkId> candidatesFor(const Scan& scan, const Pose2& robot, const FeatureMap& map) const;
	/// Eq. (3.45) statistic D^2 / chi2(d, alpha) of a matched set (< 1 passes).
	double relativeTest(const std::vector<Match>& matches, const Scan& scan, const Eigen::MatrixXd& candidate_cov,
						const std::vector<LandmarkId>& candidates, const FeatureMap& map) const;
	/// Drops matches until the relative test passes.
	void verify(std::vector<Match>& matches, const Scan& scan, const Eigen::MatrixXd& candidate_cov,
				const std::vector<LandmarkId>& candidates, const FeatureMap& map);

	RelativeAssociationParams params_;
	ReferenceRules reference_rules_;
	double new_gate_ = 0;
	std::size_t jcbb_nodes_ = 0;
	std::size_t jcbb_fallbacks_ = 0;
	std::size_t dropped_ = 0;
};

}  // namespace esif::relative
