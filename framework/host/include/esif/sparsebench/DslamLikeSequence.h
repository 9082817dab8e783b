#pragma once
/// \file DslamLikeSequence.h
/// A D-SLAM-like mapping sequence for benchmarks and tests of the sparse
/// core: a robot sweeps a square grid of point features, lane by lane along
/// the rows, then along the columns (revisiting everything and closing
/// loops), then rows again, and so on. At each step it sees the 5 to 15
/// nearest features in its field of view and measures their positions
/// relative to one of them already mapped (the reference), as D-SLAM's map
/// measurements are relative to previously seen features (book Sec. 3.1.1).
///
/// Measurement of feature i: z_i = (p_i - r) - (p_ref - r) + n_i - n_ref with
/// robot-relative noises n ~ N(0, sigma^2 I): the z_i of one step share
/// n_ref, so R = sigma^2 (I + 1 1^T (x) I_2) is dense, and the update couples
/// every feature in view, as in D-SLAM. The model is linear: h(x) = J x.

#include <Eigen/Core>
#include <random>
#include <vector>

namespace esif
{
struct DslamSequenceOptions
{
	int features = 300;      ///< features on the grid (about sqrt(features) per row)
	double spacing_m = 2.0;  ///< grid spacing [m]
	double range_m = 4.5;    ///< sensor range [m]
	double fov_deg = 180.0;  ///< sensor field of view [deg]
	double step_m = 0.5;     ///< robot travel per step [m]
	int min_in_view = 5;     ///< fewer visible: the nearest features are added
	int max_in_view = 15;    ///< more visible: only the nearest are measured
	double sigma_m = 0.05;   ///< robot-relative position noise per axis [m]
	unsigned seed = 1;
};

/// One step: who is seen, what is measured.
struct DslamStep
{
	Eigen::Vector3d robot = Eigen::Vector3d::Zero();  ///< true pose (x, y, heading)
	int reference = -1;             ///< feature the others are measured from (already mapped, or the anchor)
	std::vector<int> others;        ///< the other features seen
	std::vector<int> new_features;  ///< features first seen at this step (subset of others, or the anchor)
	bool anchor = false;            ///< first step: the reference gets a prior at its true position
	Eigen::VectorXd z;              ///< 2 x others.size(): p_other - p_reference + noise
};

class DslamLikeSequence
{
   public:
	explicit DslamLikeSequence(const DslamSequenceOptions& options);

	const DslamSequenceOptions& options() const { return options_; }
	/// True feature positions.
	const std::vector<Eigen::Vector2d>& features() const { return features_; }
	/// Steps of the first sweep (along the rows), which maps every feature.
	int mappingSteps() const { return mapping_steps_; }

	/// The next step (deterministic for a given seed).
	DslamStep next();

	/// Covariance of a step's z (2m x 2m for m = others.size()).
	Eigen::MatrixXd covariance(const DslamStep& step) const;

   private:
	Eigen::Vector3d pose(long k) const;
	/// Features within `radius` of p, nearest first.
	std::vector<int> near(const Eigen::Vector2d& p, double radius) const;
	std::vector<int> visible(const Eigen::Vector3d& pose) const;
	int nearestMapped(const Eigen::Vector2d& p) const;

	DslamSequenceOptions options_;
	int columns_ = 0;  ///< features per grid row
	std::vector<Eigen::Vector2d> features_;
	std::vector<Eigen::Vector2d> path_;  ///< one cycle: rows sweep, columns sweep, back to the start
	std::vector<double> arc_;            ///< arc length at each waypoint
	std::vector<bool> mapped_;
	int mapped_count_ = 0;
	int mapping_steps_ = 0;
	long step_ = 0;
	std::mt19937 rng_;
};

}  // namespace esif
