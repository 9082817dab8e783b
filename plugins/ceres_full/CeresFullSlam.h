#pragma once
/// \file CeresFullSlam.h
/// Full SLAM by nonlinear least squares (book Sec. 1.2.2.2, eq. 1.17-1.22):
/// the maximum-a-posteriori estimate of every robot pose and every landmark
/// given all odometry and all measurements, solved by Ceres
/// (a trust region on sparse normal equations, CHOLMOD). It is the optimum
/// every filter is measured against. It does not associate: it uses the
/// measurements' landmark IDs (from the rawlog, or another run's decisions
/// through [esif] associations_from). It solves incrementally (SolveSchedule)
/// so that the final solve starts inside the optimum's basin, checks the
/// solution (SolutionChecks) and never loses a run to a covariance that
/// cannot be computed: the estimate is then reported without covariances.

#include "CeresFullParams.h"
#include "FullSlamGraph.h"
#include "SolutionChecks.h"
#include "SolveSchedule.h"
#include "SolverOptions.h"

#include <esif/plugin/PluginWithParams.h>

#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

namespace esif
{
class CeresFullSlam : public PluginWithParams<ceres_full::CeresFullParams>
{
	DEFINE_MRPT_OBJECT(CeresFullSlam, esif)

   public:
	std::string sectionName() const override { return "ceres_full"; }
	StepReport processStep(const StepInput& step) override;
	void finish() override;
	PoseEstimate robotPose() const override;
	Estimate estimate() const override;
	CostFigures costFigures() const override;
	Formulation formulation() const override { return Formulation::FullSlamOptimum; }
	bool needsLandmarkIds() const override { return true; }
	/// Started from another run's poses and landmarks (`[esif] initial_run`)
	/// instead of odometry and first sightings.
	bool usesInitialEstimate() const override { return true; }
	void setInitialEstimate(InitialEstimate estimate) override { guess_ = std::move(estimate); }
	std::optional<std::vector<PoseEstimate>> smoothedTrajectory() const override;
	/// The step reports with every measurement the outlier gate dropped
	/// marked rejected; nullopt when none was.
	std::optional<std::vector<StepReport>> finalReports() const override;
	std::optional<InformationPattern> informationPattern() const override;
	std::optional<StateInformation> stateInformation() const override;

	/// Statistics of the solves so far.
	struct SolveTally
	{
		int solves = 0;
		int failed_solves = 0;	///< re-solves during the run that Ceres gave up (the final one: converged = 0)
		int iterations = 0;	 ///< over all solves
		int final_iterations = 0;  ///< of the last solve
		double solve_s = 0;	 ///< over all solves [s]
		double final_solve_s = 0;
		double final_initial_cost = 0;	///< Ceres cost (half the sum of squares) before the last solve
		double final_cost = 0;	///< ... and after it
		bool converged = false;	 ///< the last solve met a tolerance (not the iteration limit)
		double covariance_s = 0;
		bool covariances_available = false;
		std::size_t outliers_dropped = 0;  ///< measurements the outlier gate removed
		int outlier_rounds = 0;	 ///< plain solves after a drop
		double outlier_gate_sigma = 0;	///< the gate, as a whitened residual norm (last round)
		std::size_t excess_outliers = 0;  ///< beyond the gate but too many to drop
		std::string final_failure;	///< Ceres' message when the final solve failed
		double largest_dropped_sigma = 0;  ///< whitened residual norm of the worst one dropped
		std::optional<ceres_full::SolutionCheck> check;	 ///< of the final solve
	};

   private:
	/// The trust region's and the damping's clamps ordered (Ceres would
	/// otherwise fail at the first solve, or clamp silently).
	void validate(const ceres_full::CeresFullParams& params, const ConfigSection& section) const override;
	void start() override;
	/// Runs Ceres; false when it failed (the last accepted estimate stays).
	bool solve(ceres_full::SolveKind kind);
	/// The final solve of the answer, its failure told on stderr.
	void finalSolve();
	void solveDroppingOutliers();
	double outlierGate() const;
	void checkFinalSolution();
	void computeCovariances();
	std::unique_ptr<ceres::LossFunction> makeLoss() const;
	/// The loss of the run's solves when outliers are dropped (Huber).
	std::unique_ptr<ceres::LossFunction> outlierLoss() const;
	Pose2 warmStart(const OdometryIncrement& odometry, const std::optional<Scan>& scan) const;
	Association observe(const RangeBearing& m, const Pose2& sensor, const std::string& where);
	int threads() const;
	PoseEstimate poseEstimate(std::size_t pose) const;

	std::unique_ptr<ceres_full::FullSlamGraph> graph_ = std::make_unique<ceres_full::FullSlamGraph>();
	std::optional<InitialEstimate> guess_;
	std::optional<ceres_full::SolveSchedule> schedule_;
	std::size_t current_pose_ = 0;
	std::vector<std::size_t> step_pose_;  ///< pose index after each step
	std::vector<StepReport> reports_;  ///< what processStep returned, per step
	/// (step, measurement index) of every observation, in the graph's order.
	std::vector<std::pair<std::size_t, std::size_t>> observation_origin_;
	std::unordered_map<const double*, Eigen::MatrixXd> marginals_;
	SolveTally tally_;
	bool finished_ = false;

	/// J^T J at the current values over the estimated blocks (poses 1..N,
	/// then landmarks), evaluated once for both info_matrix.png and
	/// state_nees; nullopt for a collapsed solution (a derivative not
	/// finite). Forgotten by every processStep() and finish().
	const std::optional<Eigen::SparseMatrix<double>>& informationAtOptimum() const;
	mutable bool information_evaluated_ = false;
	mutable std::optional<Eigen::SparseMatrix<double>> information_;
};

}  // namespace esif
