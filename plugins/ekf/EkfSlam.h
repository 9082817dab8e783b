#pragma once
/// \file EkfSlam.h
/// Classical full-covariance EKF SLAM (book Sec. 1.2.1): the reference every
/// sparse filter is compared with. The filter itself, association included,
/// is the framework's LandmarkEkf (shared with the local-map builder of the
/// map-joining filters); this plugin exposes it to the host, section [ekf].

#include "EkfSlamParams.h"

#include <esif/ekf/LandmarkEkf.h>
#include <esif/plugin/PluginWithParams.h>

namespace esif
{
class EkfSlam : public PluginWithParams<EkfSlamParams>
{
	DEFINE_MRPT_OBJECT(EkfSlam, esif)

   public:
	std::string sectionName() const override { return "ekf"; }
	StepReport processStep(const StepInput& step) override;
	void reserveLandmarkIds(LandmarkId largest_input_id) override { filter_.reserveIdsUpTo(largest_input_id); }
	PoseEstimate robotPose() const override { return filter_.robotPose(); }
	Estimate estimate() const override { return filter_.estimate(); }
	CostFigures costFigures() const override;
	Formulation formulation() const override { return Formulation::EkfSlam; }
	/// When landmarks were merged (merge_landmarks_after_matches), every
	/// step's report with the IDs of the landmarks their measurements ended in.
	std::optional<std::vector<StepReport>> finalReports() const override;
	/// The covariance P of the robot and `landmarks` landmarks (Sec. 1.2.1),
	/// (3 + 2N)^2 doubles: the one part of the filter that grows as N^2, so
	/// for a large map the rest is small beside it (the update works on P in
	/// place, as a rank update).
	std::optional<double> bytesForLandmarks(std::size_t landmarks) const override
	{
		const double n = 3.0 + 2.0 * static_cast<double>(landmarks);
		return n * n * sizeof(double);
	}

   private:
	void start() override;
	LandmarkEkf filter_;
	std::vector<StepReport> reports_;  // kept only when landmarks may be merged
};

}  // namespace esif
