#pragma once
/// \file FilterPlugin.h
/// The one interface every SLAM back-end implements. A plugin is a concrete
/// class in its own shared library, registered by name with MRPT's RTTI and
/// created by the host from the class name given in the INI file.
///
/// Notes to implementers:
/// - Declare the class with DEFINE_MRPT_OBJECT(Name, esif), implement it with
///   IMPLEMENTS_MRPT_OBJECT(Name, FilterPlugin, esif), and register it in the
///   library's register.cpp with MRPT_INITIALIZER + mrpt::rtti::registerClass.
/// - The host calls configure() once, then processStep() for every step in
///   order, then finish() once. estimate(), robotPose() and costFigures() may
///   be called at any time after configure().
/// - Throw ConfigError for bad parameters and NumericalError (naming the
///   step) for numerical failure; never abort.

#include <esif/config/ConfigSection.h>
#include <esif/config/ParamBinder.h>
#include <esif/core/Estimate.h>
#include <esif/plugin/InitialEstimate.h>
#include <esif/core/InformationPattern.h>
#include <esif/core/StateInformation.h>
#include <esif/core/StepInput.h>

#include <mrpt/rtti/CObject.h>

#include <optional>
#include <vector>

namespace esif
{
class FilterPlugin : public mrpt::rtti::CObject
{
	DEFINE_VIRTUAL_MRPT_OBJECT(FilterPlugin)

   public:
	~FilterPlugin() override = default;

	/// Short name of the INI section holding this plugin's parameters (e.g. "ekf").
	virtual std::string sectionName() const = 0;

	/// Reads and validates the plugin's parameters; throws ConfigError.
	virtual void configure(const ConfigSection& section) = 0;

	/// The plugin's parameters with their current values (defaults before configure()).
	virtual std::vector<ParamInfo> parameters() const = 0;

	/// Processes one step; returns what was done with each measurement.
	virtual StepReport processStep(const StepInput& step) = 0;

	/// Called once after the last step (batch back-ends solve here).
	virtual void finish() {}

	/// Current robot pose estimate (cheap: called every step by the host).
	virtual PoseEstimate robotPose() const = 0;

	/// Current full estimate: robot pose and every landmark with its covariance.
	virtual Estimate estimate() const = 0;

	/// Current cost figures: state dimension, information non-zeros, counters.
	virtual CostFigures costFigures() const = 0;

	/// Which of the book's estimators this plugin is (stats.json "formulation").
	virtual Formulation formulation() const { return Formulation::Other; }

	/// True when the plugin cannot associate measurements itself and needs
	/// every measurement it should use to carry a landmark ID (from the
	/// rawlog, or from another run's decisions via [esif] associations_from).
	/// The host refuses to start such a plugin on input without any ID.
	virtual bool needsLandmarkIds() const { return false; }

	/// Called once, after configure() and before the first step, with the
	/// largest landmark ID any measurement of the run carries (the rawlog's,
	/// or a recorded association's), when one does. A plugin that numbers
	/// the landmarks of measurements without an ID itself numbers them above
	/// it: in a log whose scans carry IDs only in part (a recorded run leaves
	/// none on the measurements it rejected), its numbers would otherwise
	/// name landmarks the input names.
	virtual void reserveLandmarkIds(LandmarkId /*largest_input_id*/) {}

	/// Whether the plugin starts from another run's estimate when the config
	/// gives one (`[esif] initial_run`); the host refuses the key for a
	/// plugin that does not.
	virtual bool usesInitialEstimate() const { return false; }

	/// Called once, after configure() and before the first step, when
	/// usesInitialEstimate() and the config gives `[esif] initial_run`: the
	/// run's estimate, read and checked by the host (one pose per step).
	virtual void setInitialEstimate(InitialEstimate /*estimate*/) {}

	/// The memory [bytes] the plugin's estimate of `landmarks` landmarks
	/// takes, for a plugin whose memory is dominated by one dense matrix (the
	/// EKF's covariance): the host refuses, before the replay, a run that
	/// this machine could not hold (MemoryRequirement.h). Nullopt (the
	/// default): grows with the map in a way that needs no such check.
	virtual std::optional<double> bytesForLandmarks(std::size_t /*landmarks*/) const { return std::nullopt; }

	/// For smoothers: the pose after every step, re-estimated with all data,
	/// available after finish() (index k = step k). The host then reports
	/// this trajectory instead of the online robotPose() of each step.
	/// Filters keep the default (none).
	virtual std::optional<std::vector<PoseEstimate>> smoothedTrajectory() const { return std::nullopt; }

	/// For filters that settle the association of a step only later (the
	/// map-joining filters know a measurement's global landmark when its
	/// local map is fused): every step's report with the final landmark IDs
	/// (index k = step k), available after finish(). The host then writes
	/// these to associations.txt and scores them instead of the online ones.
	virtual std::optional<std::vector<StepReport>> finalReports() const { return std::nullopt; }

	/// Sparsity of the information matrix and its factor, for information-form
	/// back-ends; the host draws it as info_matrix.png. Called once, after
	/// finish(). Covariance-form back-ends keep the default (none).
	virtual std::optional<InformationPattern> informationPattern() const { return std::nullopt; }

	/// For information-form back-ends: the whole state they hold (features
	/// and, where the state has them, poses), its estimate and its full
	/// information matrix, for the whole-state consistency test
	/// (eval/StateNees.h, stats.json "state_nees"). Called after finish(),
	/// and by `esif localmaps check` after each joinLocalMap(). The estimate
	/// must be the recovered one. Covariance-form back-ends keep the default.
	virtual std::optional<StateInformation> stateInformation() const { return std::nullopt; }
};

}  // namespace esif
