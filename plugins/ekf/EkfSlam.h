#pragma once
/// \file EkfSlam.h
/// Classical full-covariance EKF SLAM (book Sec. 1.2.1): the reference every
/// sparse filter is compared with. The filter itself, association included,
/// is the framework's LandmarkEkf (shared with the local-map builder of the
/// map-joining filters); this plugin exposes it to the host, section [ekf].

#include "EkfSlamParams.h"

#include <esif/ekf/LandmarkEkf.h>
#include <esif/plugin/FilterPlugin.h>

namespace esif
{
class EkfSlam : public FilterPlugin
{
	DEFINE_MRPT_OBJECT(EkfSlam, esif)

   public:
	std::string sectionName() const override { return "ekf"; }
	void configure(const ConfigSection& section) override;
	std::vector<ParamInfo> parameters() const override { return describeParams(params_); }
	StepReport processStep(const StepInput& step) override { return filter_.processStep(step); }
	PoseEstimate robotPose() const override { return filter_.robotPose(); }
	Estimate estimate() const override { return filter_.estimate(); }
	CostFigures costFigures() const override;
	Formulation formulation() const override { return Formulation::EkfSlam; }

   private:
	EkfSlamParams params_;
	LandmarkEkf filter_;
};

}  // namespace esif
