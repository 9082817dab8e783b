// State and covariance recovery of the sparse information core (book Sec.
// 3.3) against a dense reference (Eigen LLT and inverse) on random
// SLAM-like problems, for every recovery method, reordering and reorder trigger.

#include "SparseTestProblem.h"

#include <esif/core/Errors.h>
#include <esif/sparse/SparseInformationCore.h>

#include <Eigen/Dense>
#include <algorithm>
#include <gtest/gtest.h>

namespace
{
using namespace esif;
using esif::test::relativeDifference;
using esif::test::SparseTestProblem;

/// Agreement with the dense reference. A backward-stable direct solve errs
/// by about cond(I) * eps; the problems below keep cond(I) < 1e5 (asserted),
/// so 1e-9 leaves a margin of ~50. PCG runs with a relative residual
/// tolerance of 1e-15 in these tests, so its error cond(I) * 1e-15 is
/// within the same bound.
constexpr double kTolerance = 1e-9;
constexpr double kMaxCondition = 1e5;

struct Dense
{
	Eigen::VectorXd x;
	Eigen::MatrixXd P;
	double condition = 0;
};

Dense denseReference(const InformationForm& info)
{
	const Eigen::MatrixXd I = info.matrix().toDense();
	const Eigen::LLT<Eigen::MatrixXd> llt(I);
	EXPECT_EQ(llt.info(), Eigen::Success);
	const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(I, Eigen::EigenvaluesOnly).eigenvalues();
	return {llt.solve(info.vector()), llt.solve(Eigen::MatrixXd::Identity(I.rows(), I.cols())),
			ev.maxCoeff() / ev.minCoeff()};
}

Eigen::MatrixXd denseBlock(const Eigen::MatrixXd& P, const std::vector<int>& s)
{
	Eigen::MatrixXd B(s.size(), s.size());
	for (std::size_t a = 0; a < s.size(); ++a)
		for (std::size_t b = 0; b < s.size(); ++b) B(a, b) = P(s[a], s[b]);
	return B;
}

SparseRecoveryParams paramsFor(RecoveryMethod method, Reordering reordering, int n0 = 60)
{
	SparseRecoveryParams p;
	p.recovery = method;
	p.reordering = reordering;
	p.n0 = n0;  // small against the ~600 scalars, so both Case (i) and (ii) occur
	p.pcg_relative_tolerance = 1e-15;
	return p;
}

class SparseRecovery : public ::testing::TestWithParam<std::tuple<RecoveryMethod, Reordering>>
{
   protected:
	SparseRecoveryParams params(int n0 = 60) const
	{
		return paramsFor(std::get<0>(GetParam()), std::get<1>(GetParam()), n0);
	}
};

TEST_P(SparseRecovery, StateAndCovarianceBlocksMatchDense)
{
	const SparseTestProblem problem(220, 7);
	SparseInformationCore core(params());
	int compared = 0;
	for (std::size_t k = 0; k < problem.steps().size(); ++k)
	{
		SparseTestProblem::apply(problem.steps()[k], core);
		const Eigen::VectorXd x = core.recoverState();
		if (k % 40 != 39) continue;
		const Dense ref = denseReference(core.information());
		ASSERT_LT(ref.condition, kMaxCondition);
		EXPECT_LT(relativeDifference(x, ref.x), kTolerance) << "step " << k;
		// Joint covariance of the newest pose, an old variable and a recent one.
		const int nv = core.variableCount();
		const std::vector<VarId> set = {VarId{nv - 1}, VarId{3}, VarId{nv / 2}};
		EXPECT_LT(relativeDifference(core.covariance(set), denseBlock(ref.P, core.information().scalarIndices(set))),
				  kTolerance)
			<< "step " << k;
		++compared;
	}
	EXPECT_EQ(compared, 5);
	const auto c = core.counters();
	// Both cases of Sec. 3.3.1.1 / 3.3.2.1 must have run for this test to mean anything.
	// Unconstrained AMD and nested dissection leave the newest variables
	// anywhere in the order, so n0 = 60 rebuilds the factor more often than
	// under CAMD or distance.
	if (std::get<0>(GetParam()) != RecoveryMethod::FreshCholesky)
	{
		const bool unconstrained = std::get<1>(GetParam()) == Reordering::Amd ||
			std::get<1>(GetParam()) == Reordering::NestedDissection;
		EXPECT_GT(c.partial_refactorisations, unconstrained ? 20u : 50u);
	}
	EXPECT_GT(c.full_reorders, 1u);
}

TEST_P(SparseRecovery, MarginalsOfEveryVariableMatchDenseInverse)
{
	const SparseTestProblem problem(200, 11);
	SparseInformationCore core(params());
	for (const auto& step : problem.steps())
	{
		SparseTestProblem::apply(step, core);
		core.recoverState();
	}
	const Dense ref = denseReference(core.information());
	ASSERT_LT(ref.condition, kMaxCondition);
	const auto marginals = core.marginalCovariances();
	ASSERT_EQ(static_cast<int>(marginals.size()), core.variableCount());
	double worst = 0;
	for (int v = 0; v < core.variableCount(); ++v)
	{
		const auto s = core.information().scalarIndices({VarId{v}});
		ASSERT_EQ(marginals[v].rows(), static_cast<Eigen::Index>(s.size()));
		worst = std::max(worst, relativeDifference(marginals[v], denseBlock(ref.P, s)));
	}
	EXPECT_LT(worst, kTolerance);
}

TEST_P(SparseRecovery, DistanceAndCamdReorderingsGiveTheSameEstimate)
{
	// The ordering changes the factor, never the solution.
	const SparseTestProblem problem(160, 23);
	auto p_distance = params(), p_camd = params();
	p_distance.reordering = Reordering::Distance;
	p_camd.reordering = Reordering::Camd;
	SparseInformationCore a(p_distance), b(p_camd);
	for (const auto& step : problem.steps())
	{
		SparseTestProblem::apply(step, a);
		SparseTestProblem::apply(step, b);
		const Eigen::VectorXd xa = a.recoverState();
		const Eigen::VectorXd xb = b.recoverState();
		ASSERT_LT(relativeDifference(xa, xb), kTolerance);
	}
	const std::vector<VarId> set = {VarId{0}, VarId{a.variableCount() - 1}};
	EXPECT_LT(relativeDifference(a.covariance(set), b.covariance(set)), kTolerance);
	EXPECT_GT(b.counters().full_reorders, 0u);
}

TEST_P(SparseRecovery, UnobservedVariableIsReportedNotEstimated)
{
	SparseInformationCore core(params());
	const SparseTestProblem problem(30, 3);
	for (const auto& step : problem.steps()) SparseTestProblem::apply(step, core);
	core.recoverState();
	const Eigen::VectorXd before = core.state();
	const VarId lonely = core.addPoint({1.0, 2.0});
	try
	{
		core.recoverState();
		FAIL() << "a variable without information was recovered";
	}
	catch (const NumericalError& e)
	{
		EXPECT_NE(std::string(e.what()).find("variable " + std::to_string(lonely.value)), std::string::npos)
			<< e.what();
	}
	// The estimate is left as it was: no NaN reaches the caller.
	EXPECT_TRUE(core.state().head(before.size()).isApprox(before));
	EXPECT_TRUE(core.state().allFinite());
}

TEST_P(SparseRecovery, IllConditionedVariableIsReported)
{
	SparseInformationCore core(params());
	const SparseTestProblem problem(30, 5);
	for (const auto& step : problem.steps()) SparseTestProblem::apply(step, core);
	core.recoverState();
	// A point seen twice along almost the same direction (rows 1e-7 apart):
	// J^T J is singular to about 1e-14 relative, past what the pivots can
	// resolve (min_pivot_ratio 1e-12). Mere bad scaling (a tiny diagonal)
	// would not do: Cholesky is invariant to diagonal scaling.
	const VarId weak = core.addPoint({0.5, 0.5});
	Eigen::Matrix2d J;
	J << 1.0, 1.0, 1.0, 1.0 + 1e-7;
	core.addMeasurement({weak}, J, 0.01 * Eigen::Matrix2d::Identity(), Eigen::Vector2d(0.1, 0.1));
	try
	{
		core.recoverState();
		FAIL() << "an ill-conditioned information matrix was accepted";
	}
	catch (const NumericalError& e)
	{
		const std::string what = e.what();
		EXPECT_NE(what.find("variable " + std::to_string(weak.value)), std::string::npos) << what;
		EXPECT_TRUE(what.find("singular") != std::string::npos || what.find("positive definite") != std::string::npos)
			<< what;
	}
	EXPECT_TRUE(core.state().allFinite());
}

TEST_P(SparseRecovery, UnanchoredMapIsReportedAsSingular)
{
	// Relative measurements only: the map can slide, I is singular.
	SparseInformationCore core(params());
	const VarId a = core.addPoint({0, 0}), b = core.addPoint({1, 0}), c = core.addPoint({0, 1});
	Eigen::MatrixXd J(2, 4);
	J << -Eigen::Matrix2d::Identity(), Eigen::Matrix2d::Identity();
	core.addMeasurement({a, b}, J, 0.01 * Eigen::Matrix2d::Identity(), Eigen::Vector2d(0.01, 0));
	core.addMeasurement({a, c}, J, 0.01 * Eigen::Matrix2d::Identity(), Eigen::Vector2d(0, 0.01));
	EXPECT_THROW(core.recoverState(), NumericalError);
	EXPECT_TRUE(core.state().allFinite());
}

TEST_P(SparseRecovery, RecoversAfterAnErrorOnceTheProblemIsFixed)
{
	SparseInformationCore core(params());
	const SparseTestProblem problem(40, 9);
	for (const auto& step : problem.steps()) SparseTestProblem::apply(step, core);
	core.recoverState();
	const VarId lonely = core.addPoint({1.0, 2.0});
	EXPECT_THROW(core.recoverState(), NumericalError);
	core.addPrior(lonely, Eigen::Vector2d(1.0, 2.0), 100.0 * Eigen::Matrix2d::Identity());
	const Eigen::VectorXd x = core.recoverState();
	const Dense ref = denseReference(core.information());
	EXPECT_LT(relativeDifference(x, ref.x), kTolerance);
}

/// One incremental-Cholesky run under the fill-growth trigger.
struct FillTriggerRun
{
	double worst_error = 0;  ///< state and a covariance block against dense, every 40 steps
	SparseCounters counters;
	int scalars = 0;  ///< of the final state
};

FillTriggerRun runWithFillTrigger(double max_fill_growth)
{
	auto p = paramsFor(RecoveryMethod::IncrementalCholesky, Reordering::Amd);
	p.reorder_trigger = ReorderTrigger::FillGrowth;
	p.max_fill_growth = max_fill_growth;
	const SparseTestProblem problem(220, 7);
	SparseInformationCore core(p);
	FillTriggerRun run;
	for (std::size_t k = 0; k < problem.steps().size(); ++k)
	{
		SparseTestProblem::apply(problem.steps()[k], core);
		const Eigen::VectorXd x = core.recoverState();
		if (k % 40 != 39) continue;
		const Dense ref = denseReference(core.information());
		const std::vector<VarId> set = {VarId{core.variableCount() - 1}, VarId{3}};
		run.worst_error = std::max({run.worst_error, relativeDifference(x, ref.x),
									relativeDifference(core.covariance(set),
													   denseBlock(ref.P, core.information().scalarIndices(set)))});
	}
	run.counters = core.counters();
	run.scalars = core.information().scalarDim();
	return run;
}

TEST(SparseRecoveryFillTrigger, TheEstimateIsExactWhateverTheTrigger)
{
	for (double growth : {1e-6, 0.2, 1e6}) EXPECT_LT(runWithFillTrigger(growth).worst_error, kTolerance) << growth;
}

TEST(SparseRecoveryFillTrigger, ReordersAsTheFactorFillsIn)
{
	// 1e-6: any fill-in since the fresh factor rebuilds it; 1e6: only the
	// padding rows running out do. A stale ordering fills in (the problem's
	// loop closures join old and new variables), and the trigger trades
	// that fill for reorders.
	const auto eager = runWithFillTrigger(1e-6), shipped = runWithFillTrigger(0.2), lazy = runWithFillTrigger(1e6);
	EXPECT_GT(eager.counters.full_reorders, shipped.counters.full_reorders);
	EXPECT_GT(shipped.counters.full_reorders, lazy.counters.full_reorders);
	EXPECT_LT(eager.counters.factor_nnz, lazy.counters.factor_nnz);
}

TEST(SparseRecoveryFillTrigger, CountsTheWorkOfUpdatesAndOfFreshFactorisations)
{
	// Rebuilding on any fill-in pays in fresh factorisations what applying
	// every update in place pays in update/downdate flops; CHOLMOD counts
	// rank x (6 + 4 x nnz) flops for each column it modifies, so at least 10,
	// and no refactorisation modifies more columns than the factor has.
	const auto eager = runWithFillTrigger(1e-6), lazy = runWithFillTrigger(1e6);
	EXPECT_GT(eager.counters.fresh_factor_flops, 2 * lazy.counters.fresh_factor_flops);
	EXPECT_GT(lazy.counters.partial_refactorisations, 0u);
	EXPECT_GT(lazy.counters.updated_path_columns, lazy.counters.partial_refactorisations);
	EXPECT_GE(lazy.counters.updown_flops, 10.0 * static_cast<double>(lazy.counters.updated_path_columns));
	EXPECT_LE(lazy.counters.updated_path_columns,
			  lazy.counters.partial_refactorisations * static_cast<std::size_t>(lazy.scalars));
}

TEST(SparseCounters, AddsARetiredCoresCounts)
{
	SparseCounters total, part;
	total.full_reorders = 2;
	total.pcg_iterations_max = 9;
	total.factor_nnz = 100;
	part.full_reorders = 3;
	part.pcg_iterations_max = 4;
	part.updown_flops = 1.5;
	part.updated_path_columns = 7;
	part.factor_nnz = 50;
	part.top_separator_scalars = 40;
	total += part;
	EXPECT_EQ(total.full_reorders, 5u);
	EXPECT_EQ(total.pcg_iterations_max, 9u);
	EXPECT_EQ(total.updown_flops, 1.5);
	EXPECT_EQ(total.updated_path_columns, 7u);
	EXPECT_EQ(total.factor_nnz, 100u);  // sizes, not counts
	EXPECT_EQ(total.top_separator_scalars, 0u);
}

TEST(SparseRecoveryFillTrigger, OtherMethodsKeepTheirOwnRule)
{
	// A plugin's default of fill_growth must not stop a user choosing PCG or
	// fresh factorisations: they recover exactly under their own rule.
	for (RecoveryMethod m : {RecoveryMethod::Pcg, RecoveryMethod::FreshCholesky})
	{
		auto p = paramsFor(m, Reordering::Camd);
		p.reorder_trigger = ReorderTrigger::FillGrowth;
		const SparseTestProblem problem(120, 5);
		SparseInformationCore core(p);
		for (const auto& step : problem.steps()) SparseTestProblem::apply(step, core);
		const Eigen::VectorXd x = core.recoverState();
		EXPECT_LT(relativeDifference(x, denseReference(core.information()).x), kTolerance) << recoveryMethodName(m);
	}
}

TEST(SparseRecoveryOnDemand, EveryReadEqualsTheWholeRecovery)
{
	// Core `whole` recovers x after every step; core `on_demand` defers the
	// back substitution to the reads: the newest pose (what a filter reads
	// next), an old point, and every 40 steps the whole state. Both see the
	// same updates, and each update reads its linearisation point from the
	// estimate (i += J^T R^-1 (innovation + J x^)), so a stale read would
	// move on_demand's information vector and its solution away.
	auto p = paramsFor(RecoveryMethod::IncrementalCholesky, Reordering::Amd);
	p.reorder_trigger = ReorderTrigger::FillGrowth;
	const SparseTestProblem problem(220, 7);
	SparseInformationCore whole(p), on_demand(p);
	for (std::size_t k = 0; k < problem.steps().size(); ++k)
	{
		SparseTestProblem::apply(problem.steps()[k], whole);
		SparseTestProblem::apply(problem.steps()[k], on_demand);
		whole.recoverState();
		on_demand.recoverStateOnDemand();
		const int newest = on_demand.variableCount() - 1;
		for (const VarId v : {VarId{newest}, VarId{std::min(1, newest)}})
			EXPECT_LT(relativeDifference(on_demand.estimate(v), whole.estimate(v)), kTolerance) << "step " << k;
		if (k % 40 == 39)
		{
			EXPECT_LT(relativeDifference(on_demand.state(), whole.state()), kTolerance) << "step " << k;
		}
	}
	// The reads cost paths of the factor, not its every column.
	EXPECT_LT(on_demand.counters().back_substitution_columns, whole.counters().back_substitution_columns / 2);
}

TEST(SparseRecoveryOnDemand, ARefreshMovesTheEstimateToTheNewestInformation)
{
	// Between recoveries, estimates are x = I^-1 i of the information as of
	// the last refresh: a covariance() after an update refreshes, and the
	// reads then agree with a whole recovery at that point.
	auto p = paramsFor(RecoveryMethod::IncrementalCholesky, Reordering::Amd);
	const SparseTestProblem problem(80, 3);
	SparseInformationCore whole(p), on_demand(p);
	for (std::size_t k = 0; k + 1 < problem.steps().size(); ++k)
	{
		SparseTestProblem::apply(problem.steps()[k], whole);
		SparseTestProblem::apply(problem.steps()[k], on_demand);
	}
	whole.recoverState();
	on_demand.recoverStateOnDemand();
	const auto& last = problem.steps().back();
	SparseTestProblem::apply(last, whole);
	SparseTestProblem::apply(last, on_demand);
	on_demand.covariance({VarId{0}});
	const Eigen::VectorXd& x = whole.recoverState();
	for (int v = 0; v < on_demand.variableCount(); ++v)
	{
		const auto s = on_demand.information().scalarIndices({VarId{v}});
		EXPECT_LT(relativeDifference(on_demand.estimate(VarId{v}), x.segment(s.front(), s.size())), kTolerance) << v;
	}
}

TEST(SparseRecoveryOnDemand, MethodsWithoutACompleteFactorRecoverEverything)
{
	for (RecoveryMethod m : {RecoveryMethod::Pcg, RecoveryMethod::FreshCholesky})
	{
		const SparseTestProblem problem(60, 5);
		SparseInformationCore core(paramsFor(m, Reordering::Camd));
		for (const auto& step : problem.steps()) SparseTestProblem::apply(step, core);
		core.recoverStateOnDemand();
		EXPECT_LT(relativeDifference(core.state(), denseReference(core.information()).x), kTolerance)
			<< recoveryMethodName(m);
	}
}

std::string paramName(const ::testing::TestParamInfo<SparseRecovery::ParamType>& info)
{
	return std::string(recoveryMethodName(std::get<0>(info.param))) + "_" + reorderingName(std::get<1>(info.param));
}

INSTANTIATE_TEST_SUITE_P(AllMethods, SparseRecovery,
						 ::testing::Combine(::testing::Values(RecoveryMethod::IncrementalCholesky, RecoveryMethod::Pcg,
															  RecoveryMethod::FreshCholesky),
											::testing::Values(Reordering::Distance, Reordering::Camd, Reordering::Amd,
																			Reordering::NestedDissection)),
						 paramName);

}  // namespace
