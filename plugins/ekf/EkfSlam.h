#pragma once
/// \file EkfSlam.h
/// Classical full-covariance EKF SLAM (book Sec. 1.2.1): the reference every
/// sparse filter is compared with.

#include "EkfParams.h"

#include <esif/ekf/EkfSlamCore.h>
#include <esif/plugin/FilterPlugin.h>

#include <unordered_map>
#include <vector>

namespace esif
{
class EkfSlam : public FilterPlugin
{
	DEFINE_MRPT_OBJECT(EkfSlam, esif)

   public:
	std::string sectionName() const override { return "ekf"; }
	void configure(const ConfigSection& section) override;
	std::vector<ParamInfo> parameters() const override { return describeParams(params_); }
	StepReport processStep(const StepInput& step) override;
	PoseEstimate robotPose() const override;
	Estimate estimate() const override;
	CostFigures costFigures() const override;
	Formulation formulation() const override { return Formulation::EkfSlam; }

   private:
	/// Decides, for each measurement, match / new / rejected (the report) and
	/// the core's match list.
	StepReport associateScan(const StepInput& step, std::vector<EkfSlamCore::Match>& matches);
	StepReport associateByIds(const StepInput& step, std::vector<EkfSlamCore::Match>& matches) const;
	StepReport associateByDistance(const Scan& scan, std::vector<EkfSlamCore::Match>& matches);
	std::vector<std::size_t> candidatesFor(const Scan& scan) const;
	void addNewLandmarks(const Scan& scan, StepReport& report);

	EkfParams params_;
	double gate_distance2_new_ = 0;	 // chi-square value of new_landmark_chi2_quantile
	EkfSlamCore core_;
	std::vector<LandmarkId> ids_;  // landmark index -> ID
	std::unordered_map<LandmarkId, std::size_t> index_of_;
	LandmarkId next_own_id_ = 0;
	std::size_t jcbb_nodes_ = 0;
};

}  // namespace esif
