#pragma once
/// \file FakePlugin.h
/// A minimal FilterPlugin for host tests that need no real estimator: it
/// dead-reckons the odometry, matches measurements by their IDs (rejecting
/// those without), and can pose as a smoother, as a plugin that needs IDs,
/// or as a map-joining filter that settles its reports after finish().

#include <esif/plugin/FilterPlugin.h>

#include <optional>
#include <set>
#include <vector>

namespace esif::test
{
class FakePlugin : public FilterPlugin
{
	DEFINE_MRPT_OBJECT(FakePlugin, esif::test)

   public:
	/// Returned by smoothedTrajectory() (none: a plain filter).
	std::optional<std::vector<PoseEstimate>> smoothed;
	/// Returned by finalReports() after finish() (none: reports are final online).
	std::optional<std::vector<StepReport>> final_reports;
	bool needs_ids = false;	 ///< returned by needsLandmarkIds()
	/// bytesForLandmarks(N) = N x this (none: the default, no memory model).
	std::optional<double> bytes_per_landmark;
	bool finished = false;	///< set by finish()

	std::string sectionName() const override { return "fake"; }
	void configure(const ConfigSection&) override {}
	std::vector<ParamInfo> parameters() const override { return {}; }
	StepReport processStep(const StepInput& step) override;
	void finish() override { finished = true; }
	PoseEstimate robotPose() const override { return pose_; }
	Estimate estimate() const override { return {pose_, {}}; }
	CostFigures costFigures() const override { return {}; }
	bool needsLandmarkIds() const override { return needs_ids; }
	std::optional<double> bytesForLandmarks(std::size_t landmarks) const override
	{
		if (!bytes_per_landmark) return std::nullopt;
		return static_cast<double>(landmarks) * *bytes_per_landmark;
	}
	std::optional<std::vector<PoseEstimate>> smoothedTrajectory() const override
	{
		// Like a real smoother: nothing before finish().
		return finished ? smoothed : std::nullopt;
	}
	std::optional<std::vector<StepReport>> finalReports() const override
	{
		return finished ? final_reports : std::nullopt;
	}

   private:
	PoseEstimate pose_;
	std::set<LandmarkId> seen_;
};

}  // namespace esif::test
