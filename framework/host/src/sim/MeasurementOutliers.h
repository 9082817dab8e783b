#pragma once
/// \file MeasurementOutliers.h
/// The simulator's outlier classes (Scenario::wrong_id_rate, spurious_rate),
/// applied to a scan of true measurements. They draw from a generator of
/// their own, so a scenario with outliers keeps the path, the noise and the
/// true measurements of the same scenario without them, and the defaults
/// (both rates 0) draw nothing at all.

#include <esif/core/StepInput.h>
#include <esif/sim/Scenario.h>

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <random>
#include <set>
#include <vector>

namespace esif
{
class MeasurementOutliers
{
   public:
	/// `landmarks` and `landmark_ids` (parallel): every landmark of the
	/// world, the positions and IDs a misread can give.
	MeasurementOutliers(
		const Scenario& scenario, std::vector<Eigen::Vector2d> landmarks, std::vector<LandmarkId> landmark_ids,
		std::uint32_t seed);

	/// A misread gives the ID of one of this many landmarks nearest to the
	/// true one (the ring of 8 around a grid feature).
	static constexpr std::size_t kMisreadNeighbours = 8;

	/// `scan` holds true measurements, each with its landmark's ID, and
	/// `true_ids` those IDs. Gives some measurements another landmark's ID
	/// (true_ids unchanged), then inserts spurious returns at random places
	/// (true ID none); true_ids stays parallel to scan.measurements.
	void apply(Scan& scan, std::vector<std::optional<LandmarkId>>& true_ids, const Eigen::Matrix2d& measurement_cov);

	std::size_t wrongIdCount() const { return wrong_ids_; }
	std::size_t spuriousCount() const { return spurious_; }

   private:
	void misreadIds(Scan& scan, const std::vector<std::optional<LandmarkId>>& true_ids);
	LandmarkId otherLandmark(LandmarkId true_id, const std::set<LandmarkId>& taken);
	void addClutter(Scan& scan, std::vector<std::optional<LandmarkId>>& true_ids, const Eigen::Matrix2d& cov);

	const Scenario& s_;
	std::vector<Eigen::Vector2d> landmarks_;
	std::vector<LandmarkId> landmark_ids_;
	/// std::mt19937 is specified bit for bit; the distributions are those of
	/// the project's one toolchain (libstdc++), which MRPT's generator lacks
	/// for Poisson counts.
	std::mt19937 rng_;
	LandmarkId next_clutter_id_;
	std::size_t wrong_ids_ = 0, spurious_ = 0;
};

}  // namespace esif
