#pragma once
/// \file DivergenceGuard.h
/// Detects a diverging D-SLAM estimate and stops the run at the step it
/// happens, with one NumericalError line (exit 3), instead of carrying on
/// and writing an absurd map. Every feature the robot has seen lies within
/// the path travelled plus one sensor range of the map origin (the initial
/// pose); an estimate `factor` times farther than that, a non-finite value
/// in the map or the robot pose, is no estimate any more. (A singular
/// information matrix is reported by the sparse core itself.) And the map
/// and the local SLAM must not disagree on the robot pose (the covariance
/// intersection gate, Dslam::robotEstimatesAgree) at many admissible scans
/// in a row: one disagreement is a bad match, a run of them is a map that
/// no longer fits the measurements (configs/dslam_jcbb.ini on
/// configs/sim/long_gap.ini: 724 disagreements, landmarks 72 m RMS off).

#include <esif/core/StepInput.h>
#include <esif/models/Se2.h>

#include <Eigen/Core>
#include <vector>

namespace esif::dslam
{
class DivergenceGuard
{
   public:
	/// `factor` <= 0 switches the distance check off (non-finite values are
	/// always errors).
	/// `max_disagreeing_scans` = 0 switches the second check off.
	explicit DivergenceGuard(double factor = 0, int max_disagreeing_scans = 0)
		: factor_(factor), max_disagreeing_scans_(max_disagreeing_scans)
	{
	}

	/// Path length from the odometry increment's translation.
	void travel(const OdometryIncrement& u);
	/// The largest range measured so far bounds how far a feature is seen.
	void sense(const Scan& scan);

	/// Distance bound from the origin [m].
	double bound() const { return factor_ * (path_m_ + max_range_m_); }

	/// Throws NumericalError naming the feature if one of `positions`
	/// ([x1, y1, x2, y2, ...], features `ids`) is non-finite or beyond
	/// bound(), or the robot pose is non-finite.
	void check(const std::vector<LandmarkId>& ids, const Eigen::VectorXd& positions, const Pose2& robot) const;

	/// Whether the map and the local SLAM agreed at this admissible scan;
	/// throws NumericalError at the max_disagreeing_scans-th disagreement
	/// in a row.
	void fusion(bool agreed);
	/// Disagreements in a row so far.
	int disagreeingInARow() const { return disagreeing_in_a_row_; }

   private:
	double factor_;
	int max_disagreeing_scans_;
	int disagreeing_in_a_row_ = 0;
	double path_m_ = 0;
	double max_range_m_ = 0;
};

}  // namespace esif::dslam
