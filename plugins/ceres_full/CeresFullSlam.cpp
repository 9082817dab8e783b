#include "CeresFullSlam.h"

#include "MarginalCovariances.h"
#include "PoseRefiner.h"
#include "QuietCeresLogging.h"

#include <esif/association/Chi2.h>
#include <esif/core/Elapsed.h>
#include <esif/core/Errors.h>
#include <esif/models/RangeBearingModel.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <thread>

IMPLEMENTS_MRPT_OBJECT(CeresFullSlam, FilterPlugin, esif)

namespace esif
{
using namespace ceres_full;

namespace
{
/// One line on stderr: the run goes on, its stats say what went wrong.
void warn(const std::string& what) { std::cerr << "esif: warning: ceres_full: " << what << "\n"; }
}  // namespace

void CeresFullSlam::validate(const CeresFullParams& p, const ConfigSection& section) const
{
	if (p.max_trust_region_radius < p.initial_trust_region_radius)
		throw ConfigError(section.describeKey(
			"max_trust_region_radius", formatNumber(p.max_trust_region_radius) + " is below initial_trust_region_radius " +
										   formatNumber(p.initial_trust_region_radius)));
	if (p.max_lm_diagonal < p.min_lm_diagonal)
		throw ConfigError(section.describeKey(
			"max_lm_diagonal",
			formatNumber(p.max_lm_diagonal) + " is below min_lm_diagonal " + formatNumber(p.min_lm_diagonal)));
}

void CeresFullSlam::start()
{
	graph_ = std::make_unique<FullSlamGraph>(params_.outliers == OutlierPolicy::Drop ? outlierLoss() : makeLoss());
	schedule_.emplace(
		params_.resolve_growth, static_cast<std::size_t>(params_.resolve_min_new_poses),
		static_cast<std::size_t>(params_.resolve_every_steps));
}

std::unique_ptr<ceres::LossFunction> CeresFullSlam::outlierLoss() const
{
	// Huber, not Cauchy: a landmark first seen through an outlier starts
	// metres off, where Cauchy's vanishing influence discounts every correct
	// measurement of it (wrong_ids: 33 correct measurements of such a
	// landmark dropped with the 147 misreads); Huber's bounded one pulls it
	// back (exactly the 148 misreads dropped).
	return std::make_unique<ceres::HuberLoss>(params_.robust_loss_scale);
}

std::unique_ptr<ceres::LossFunction> CeresFullSlam::makeLoss() const
{
	// Ceres losses act on the squared whitened norm s; both keep rho(s) ~ s
	// below scale^2, so inliers are weighted as in eq. 1.21.
	switch (params_.robust_loss)
	{
		case RobustLoss::Huber: return std::make_unique<ceres::HuberLoss>(params_.robust_loss_scale);
		case RobustLoss::Cauchy: return std::make_unique<ceres::CauchyLoss>(params_.robust_loss_scale);
		case RobustLoss::None: break;
	}
	return nullptr;
}

StepReport CeresFullSlam::processStep(const StepInput& step)
{
	information_evaluated_ = false;
	if (step.odometry && !isStandStill(*step.odometry))
	{
		// The starting value of the new pose: odometry composed onto the
		// current estimate (eq. 1.3; the optimum of the last re-solve, and
		// the warm starts since), or the pose another run estimated for this step.
		const Pose2 initial = guess_ ? guess_->poseAfterStep(step.index) : warmStart(*step.odometry, step.scan);
		current_pose_ = graph_->addPose(current_pose_, *step.odometry, initial, "odometry");
	}
	step_pose_.push_back(current_pose_);

	StepReport report;
	if (step.scan)
	{
		const Pose2 sensor = step.scan->sensor_on_robot;
		const auto& ms = step.scan->measurements;
		for (std::size_t i = 0; i < ms.size(); ++i)
		{
			const std::size_t before = graph_->observations().size();
			report.associations.push_back(observe(ms[i], sensor, "measurement " + std::to_string(i)));
			if (graph_->observations().size() > before) observation_origin_.emplace_back(reports_.size(), i);
		}
	}
	if (schedule_ && schedule_->due(step_pose_.size(), graph_->poseCount())) solve(SolveKind::Intermediate);
	reports_.push_back(report);
	return report;
}

Pose2 CeresFullSlam::warmStart(const OdometryIncrement& odometry, const std::optional<Scan>& scan) const
{
	const Pose2 previous = graph_->pose(current_pose_);
	const Pose2 composed = compose(previous, odometry.delta);
	if (!params_.refine_new_poses || !scan) return composed;
	std::vector<MappedMeasurement> seen;
	for (const RangeBearing& m : scan->measurements)
		if (m.id && graph_->hasLandmark(*m.id))
			seen.push_back({graph_->landmark(*m.id), m, scan->sensor_on_robot});
	return refineNewPose(previous, odometry, composed, seen, graph_->loss());
}

Association CeresFullSlam::observe(const RangeBearing& m, const Pose2& sensor, const std::string& where)
{
	// Without an ID the measurement cannot be placed in eq. 1.18: the run
	// that provided the associations rejected it.
	if (!m.id) return {Association::Kind::Rejected, -1};
	const LandmarkId id = *m.id;
	Association a{Association::Kind::Matched, id};
	if (!graph_->hasLandmark(id))
	{
		// First sighting: the inverse observation model from the current
		// pose estimate, unless another run mapped this landmark.
		const auto from_guess = guess_ ? guess_->landmark(id) : std::nullopt;
		graph_->addLandmark(
			id, from_guess ? *from_guess
						   : landmarkFromRangeBearing(graph_->pose(current_pose_), sensor, m.range_m, m.bearing_rad)
								 .position);
		a.kind = Association::Kind::New;
	}
	graph_->addObservation(current_pose_, id, m, sensor, where);
	return a;
}

int CeresFullSlam::threads() const
{
	if (params_.threads > 0) return params_.threads;
	return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

bool CeresFullSlam::solve(SolveKind kind)
{
	if (graph_->residualDim() == 0) return true;
	const auto t0 = std::chrono::steady_clock::now();
	ceres::Solver::Summary summary;
	{
		const QuietCeresLogging quiet;	// a failure is told below, in one line
		ceres::Solve(solverOptions(params_, kind, threads()), &graph_->problem(), &summary);
	}
	if (schedule_) schedule_->solved(graph_->poseCount());
	// A failed solve (a non-finite Jacobian, a failed factorization) keeps
	// the last accepted estimate: the run goes on and its stats say it did
	// not converge. Failed re-solves are counted; the final one is told
	// (finalSolve).
	const bool failed =
		summary.termination_type == ceres::FAILURE || summary.termination_type == ceres::USER_FAILURE;
	if (failed && kind == SolveKind::Intermediate) ++tally_.failed_solves;
	tally_.final_failure = failed ? summary.message : "";

	++tally_.solves;
	tally_.final_iterations = static_cast<int>(summary.iterations.size()) - 1;  // entry 0 is the start
	tally_.iterations += tally_.final_iterations;
	tally_.final_solve_s = secondsSince(t0);
	tally_.solve_s += tally_.final_solve_s;
	tally_.final_initial_cost = summary.initial_cost;
	tally_.final_cost = summary.final_cost;
	tally_.converged = summary.termination_type == ceres::CONVERGENCE;
	return !failed;
}

void CeresFullSlam::finalSolve()
{
	if (!solve(SolveKind::Final)) warn("the final solve failed: " + tally_.final_failure);
}

void CeresFullSlam::finish()
{
	information_evaluated_ = false;
	if (params_.outliers == OutlierPolicy::Drop)
		solveDroppingOutliers();
	else
		finalSolve();
	checkFinalSolution();
	computeCovariances();
	finished_ = true;
}

double CeresFullSlam::outlierGate() const
{
	const double n = static_cast<double>(std::max<std::size_t>(1, graph_->liveObservations()));
	return chi2Quantile(1 - params_.outlier_false_drop_rate / n, 2);
}

void CeresFullSlam::solveDroppingOutliers()
{
	// The run's solves down-weighted outliers (outlierLoss), so the estimate
	// never followed one: converged so, an outlier stands out from the
	// inliers' residuals instead of being shared among them. (A robust solve
	// started only at the end, from a plain optimum that outliers had
	// already dragged, settled in a wrong minimum: MRCLAM robot 5 dropped 163
	// measurements.) Nothing is judged by a solve that failed: the plain
	// solve follows.
	const bool converged_robustly = solve(SolveKind::Final);
	bool plain_solved = false;
	constexpr int kMaxRounds = 5;  // each round drops what the last solve exposed
	for (int round = 0; round < kMaxRounds && converged_robustly; ++round)
	{
		const double gate = outlierGate();
		tally_.outlier_gate_sigma = std::sqrt(gate);
		const std::vector<DroppedObservation> beyond = graph_->observationsAbove(gate);
		if (static_cast<double>(beyond.size()) >
			params_.max_outlier_share * static_cast<double>(graph_->liveObservations()))
		{
			tally_.excess_outliers = beyond.size();	 // a wrong solution: keep them, report it
			break;
		}
		if (beyond.empty() && plain_solved) return;
		graph_->dropObservations(beyond);
		for (const auto& d : beyond)
			tally_.largest_dropped_sigma = std::max(tally_.largest_dropped_sigma, std::sqrt(d.chi2));
		tally_.outliers_dropped += beyond.size();
		graph_->setObservationLoss(makeLoss());	 // the configured loss (none: eq. 1.21)
		++tally_.outlier_rounds;
		finalSolve();
		plain_solved = true;
		if (beyond.empty()) return;
	}
	if (plain_solved) return;
	graph_->setObservationLoss(makeLoss());
	finalSolve();
}

std::optional<std::vector<StepReport>> CeresFullSlam::finalReports() const
{
	if (tally_.outliers_dropped == 0) return std::nullopt;
	std::vector<StepReport> out = reports_;
	for (std::size_t i = 0; i < graph_->observations().size(); ++i)
		if (!graph_->observations()[i].block)
		{
			const auto [step, j] = observation_origin_[i];
			out[step].associations[j] = {Association::Kind::Rejected, -1};
		}
	return out;
}

void CeresFullSlam::checkFinalSolution()
{
	const double dof = static_cast<double>(graph_->residualDim()) - static_cast<double>(graph_->parameterDim());
	tally_.check = checkSolution(
		graph_->plainChi2(threads()), dof, countDegeneratePoses(*graph_, params_.degenerate_distance_m),
		params_.max_chi2_per_dof, tally_.excess_outliers);
	if (!tally_.check->plausible) warn(tally_.check->warning(params_.max_chi2_per_dof));
	if (tally_.outliers_dropped > 0)
		warn(std::to_string(tally_.outliers_dropped) + " of " +
			 std::to_string(tally_.outliers_dropped + graph_->liveObservations()) +
			 " measurements dropped as outliers (whitened residual above " + std::to_string(tally_.outlier_gate_sigma) +
			 " sigma, the largest " + std::to_string(tally_.largest_dropped_sigma) +
			 "); the optimum is that of the others");
}

void CeresFullSlam::computeCovariances()
{
	if (params_.covariance == CovarianceScope::None) return;
	std::vector<const double*> blocks;
	for (const LandmarkId id : graph_->landmarkIds()) blocks.push_back(graph_->landmarkBlock(id));
	if (params_.covariance == CovarianceScope::AllPoses)
	{
		for (std::size_t i = 1; i < graph_->poseCount(); ++i) blocks.push_back(graph_->poseBlock(i));
	}
	else if (!FullSlamGraph::isGauge(current_pose_))
		blocks.push_back(graph_->poseBlock(current_pose_));
	if (blocks.empty()) return;
	const auto t0 = std::chrono::steady_clock::now();
	try
	{
		marginals_ = marginalCovariances(graph_->problem(), blocks, threads());
		tally_.covariances_available = true;
	}
	catch (const NumericalError& e)
	{
		// The estimate is still the solver's: report it with zero
		// covariances, the framework's "no covariance" (no NEES, no ellipse).
		marginals_.clear();
		warn(std::string(e.what()) + "; the estimate is reported without covariances");
	}
	tally_.covariance_s = secondsSince(t0);
}

PoseEstimate CeresFullSlam::poseEstimate(std::size_t pose) const
{
	PoseEstimate p;
	p.mean = graph_->pose(pose);
	const auto it = marginals_.find(graph_->poseBlock(pose));
	if (it != marginals_.end()) p.cov = it->second;
	return p;
}

PoseEstimate CeresFullSlam::robotPose() const { return poseEstimate(current_pose_); }

Estimate CeresFullSlam::estimate() const
{
	Estimate e;
	e.robot = robotPose();
	for (const LandmarkId id : graph_->landmarkIds())
	{
		LandmarkEstimate l;
		l.id = id;
		l.mean = graph_->landmark(id);
		const auto it = marginals_.find(graph_->landmarkBlock(id));
		if (it != marginals_.end()) l.cov = it->second;
		e.landmarks.push_back(l);
	}
	return e;
}

std::optional<std::vector<PoseEstimate>> CeresFullSlam::smoothedTrajectory() const
{
	if (!finished_) return std::nullopt;
	std::vector<PoseEstimate> out;
	out.reserve(step_pose_.size());
	for (const std::size_t pose : step_pose_) out.push_back(poseEstimate(pose));
	return out;
}

CostFigures CeresFullSlam::costFigures() const
{
	CostFigures c;
	c.state_dim = graph_->parameterDim();
	c.poses_in_state = graph_->poseCount() - 1;	 // the gauge pose is fixed, not estimated
	c.info_nnz = graph_->informationNonZeros();
	const auto add = [&](const char* name, double v) { c.counters.emplace_back(name, v); };
	add("residuals", static_cast<double>(graph_->residualDim()));
	const double dof = static_cast<double>(graph_->residualDim()) - static_cast<double>(graph_->parameterDim());
	add("chi2_dof", dof);
	// Ceres' cost is half the (robustified) sum of squares; chi2 is the plain
	// sum of squared whitened residuals, the same as 2 x cost without a loss.
	const double objective = 2 * tally_.final_cost;
	add("chi2", tally_.check ? tally_.check->chi2 : objective);
	add("objective", objective);
	add("initial_chi2", 2 * tally_.final_initial_cost);  // objective before the final solve
	add("chi2_per_dof", tally_.check ? tally_.check->chi2PerDof() : (dof > 0 ? objective / dof : std::nan("")));
	add("degenerate_poses", tally_.check ? static_cast<double>(tally_.check->degenerate_poses) : 0);
	add("optimum_plausible", tally_.check && tally_.check->plausible ? 1 : 0);
	add("covariances_available", tally_.covariances_available ? 1 : 0);
	add("robust_loss_used", static_cast<double>(static_cast<int>(params_.robust_loss)));
	add("solves", tally_.solves);
	add("failed_intermediate_solves", tally_.failed_solves);
	add("iterations", tally_.iterations);
	add("final_iterations", tally_.final_iterations);
	add("solve_s", tally_.solve_s);
	add("final_solve_s", tally_.final_solve_s);
	add("converged", tally_.converged ? 1 : 0);
	add("covariance_s", tally_.covariance_s);
	add("outliers_dropped", static_cast<double>(tally_.outliers_dropped));
	add("outlier_rounds", tally_.outlier_rounds);
	add("outlier_gate_sigma", tally_.outlier_gate_sigma);
	add("excess_outliers", static_cast<double>(tally_.excess_outliers));
	add("largest_dropped_sigma", tally_.largest_dropped_sigma);
	return c;
}

const std::optional<Eigen::SparseMatrix<double>>& CeresFullSlam::informationAtOptimum() const
{
	if (!information_evaluated_)
	{
		information_.reset();
		try
		{
			information_ = graph_->informationMatrix(threads());
		}
		catch (const NumericalError&)
		{
			// a collapsed solution, already reported by finish()
		}
		information_evaluated_ = true;
	}
	return information_;
}

std::optional<InformationPattern> CeresFullSlam::informationPattern() const
{
	// J^T J at the optimum, poses first then landmarks (the gauge pose left out).
	if (graph_->residualDim() == 0 || !informationAtOptimum()) return std::nullopt;
	InformationPattern p;
	p.information = *informationAtOptimum();
	return p;
}

std::optional<StateInformation> CeresFullSlam::stateInformation() const
{
	// The Laplace approximation at the optimum: mean = the solution,
	// information = J^T J, over the blocks informationMatrix() orders.
	if (!finished_ || graph_->residualDim() == 0 || !informationAtOptimum()) return std::nullopt;
	StateInformation s;
	s.information = *informationAtOptimum();
	std::vector<std::optional<std::size_t>> step_of_pose(graph_->poseCount());
	for (std::size_t k = 0; k < step_pose_.size(); ++k) step_of_pose[step_pose_[k]] = k;
	s.mean.resize(static_cast<Eigen::Index>(graph_->parameterDim()));
	Eigen::Index at = 0;
	for (std::size_t i = 1; i < graph_->poseCount(); ++i, at += 3)
	{
		s.variables.push_back(StateVariable::poseOf(step_of_pose[i]));
		s.mean.segment<3>(at) = graph_->pose(i);
	}
	for (const LandmarkId id : graph_->landmarkIds())
	{
		s.variables.push_back(StateVariable::landmarkOf(id));
		s.mean.segment<2>(at) = graph_->landmark(id);
		at += 2;
	}
	return s;
}

}  // namespace esif
