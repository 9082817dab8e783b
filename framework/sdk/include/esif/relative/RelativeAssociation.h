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
/// With anchors (measurements already tied to mapped features, e.g. by
/// D-SLAM's tracking of the features its local SLAM holds) the hypotheses
/// of step 1 are chosen by the relative test with the anchors instead of
/// JCBB, and a measurement that fits no candidate relative to them is new:
/// after a long stretch of dead reckoning the absolute gate passes every
/// feature within metres, and a grid row shifted by one spacing keeps all
/// relative distances and angles among the measured features themselves.
/// Candidates are the features predicted within the sensor's range and field
/// of view plus margins that grow with the robot's uncertainty.
/// Only the candidate features' covariance blocks are recovered from the map.
/// Serves D-SLAM (Ch. 3) and D-SLAM map joining (Ch. 4), whose map is the
/// same feature-only EIF.

#include <esif/association/DataAssociation.h>
#include <esif/core/Estimate.h>
#include <esif/core/StepInput.h>
#include <esif/relative/FeatureMap.h>
#include <esif/relative/ReferencePair.h>
#include <esif/relative/RelativeAssociationParams.h>

#include <cstddef>
#include <unordered_set>

namespace esif::relative
{
class RelativeAssociation
{
   public:
	/// `reference_rules` choose the pair the relative test measures angles
	/// from (the map update's rules: the same linearisation on both sides).
	RelativeAssociation(const RelativeAssociationParams& params, const ReferenceRules& reference_rules);

	/// One decision per measurement of `scan`: Matched (with the map ID),
	/// New (id -1: the caller names it) or Rejected. Features in `excluded`
	/// are no candidates: D-SLAM tests the features its local SLAM holds
	/// first, with their correlation to the robot, and a measurement that
	/// test did not match is none of them.
	///
	/// `anchors`: measurements of this scan already associated with mapped
	/// features (D-SLAM's tracking). They join every relative test, so a
	/// hypothesis must also fit them, and a measurement near a candidate in
	/// absolute terms is still new when no such candidate fits them.
	struct Anchor
	{
		RangeBearing measurement;
		LandmarkId feature = -1;
	};
	StepReport associate(const Scan& scan, const Pose2& robot, const Eigen::Matrix3d& robot_cov, FeatureMap& map,
						 const std::unordered_set<LandmarkId>& excluded = {}, const std::vector<Anchor>& anchors = {});

	std::size_t jcbbNodes() const { return jcbb_nodes_; }
	/// Scans too ambiguous for JCBB (SearchBounds): their hypotheses came from
	/// nearest neighbour with the joint compatibility test, then eq. (3.45).
	std::size_t jcbbFallbacks() const { return jcbb_fallbacks_; }
	/// Matches dropped because the relative test, eq. (3.45), failed.
	std::size_t droppedByRelativeTest() const { return dropped_; }
	/// Scans whose anchors failed the relative test among themselves: their
	/// other measurements were left unassociated.
	std::size_t anchorConflicts() const { return anchor_conflicts_; }
	/// Scans whose one match, unchecked by the relative test, was dropped as
	/// ambiguous (RelativeAssociationParams::ambiguity_margin_chi2_quantile).
	std::size_t ambiguousWaits() const { return ambiguous_waits_; }

   private:
	struct Match
	{
		int measurement = 0;
		int candidate = 0;
		bool anchor = false;  ///< tracked before: never dropped
	};
	/// What the relative tests read: measurements, their features and the
	/// features' joint covariance (Match indexes the first two).
	struct Tested
	{
		const Scan& scan;
		const Eigen::MatrixXd& cov;
		const std::vector<LandmarkId>& features;
		const FeatureMap& map;
	};
	std::vector<LandmarkId> candidatesFor(const Scan& scan, const Pose2& robot, const Eigen::Matrix3d& robot_cov,
										  const FeatureMap& map, const std::unordered_set<LandmarkId>& excluded) const;
	/// Eq. (3.45) statistic D^2 / chi2(d, alpha) of a matched set (< 1 passes).
	/// `quantile`: the test's confidence, relative_gate_chi2_quantile if 0.
	double relativeTest(const std::vector<Match>& matches, const Tested& t, double quantile = 0) const;
	/// relativeTest of the anchors plus the pair (measurement, candidate).
	double relativeTestWithAnchors(const std::vector<Match>& anchored, int measurement, int candidate,
								   const Tested& t) const;
	/// Drops matches until the relative test passes.
	void verify(std::vector<Match>& matches, const Tested& t);
	/// Drops the scan's one match when the relative test had nothing to check
	/// it against and another candidate is nearly as likely (Ambiguity.h).
	void dropUncheckedAmbiguousMatch(std::vector<Match>& matches, const AssociationInput& in, const Eigen::MatrixXd& d2,
									 const Scan& scan);
	static AssociationInput absoluteInput(const Scan& scan, const Pose2& robot, const Eigen::Matrix3d& robot_cov,
										  const FeatureMap& map, const std::vector<LandmarkId>& candidates,
										  const Eigen::MatrixXd& candidate_cov);
	/// Hypotheses when anchors exist: per measurement the candidate that best
	/// passes the relative test with them (-1: none); `d2`: individual
	/// distances, measurements x candidates (individualDistances2).
	std::vector<int> bestFitsToAnchors(const Eigen::MatrixXd& d2, const std::vector<Match>& anchored,
									   const Tested& t) const;
	/// An unmatched measurement within the new-feature gate of candidates:
	/// true when none of them passes the relative test with the anchors.
	bool noCandidateFitsAnchors(int measurement, const Eigen::MatrixXd& d2, const std::vector<Match>& anchored,
								const std::vector<Match>& accepted, const Tested& t) const;

	RelativeAssociationParams params_;
	ReferenceRules reference_rules_;
	double new_gate_ = 0;
	double ambiguity_margin_d2_ = 0;
	std::size_t jcbb_nodes_ = 0;
	std::size_t jcbb_fallbacks_ = 0;
	std::size_t dropped_ = 0;
	std::size_t anchor_conflicts_ = 0;
	std::size_t ambiguous_waits_ = 0;
};

}  // namespace esif::relative
