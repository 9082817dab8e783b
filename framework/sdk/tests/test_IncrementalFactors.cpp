// The incremental factors themselves (book App. B): after a Case (i) update
// the leading columns are untouched, and after thousands of updates the
// incremental complete factor is still the Cholesky factor a fresh
// factorisation of the same ordering gives.

#include "SparseTestProblem.h"

#include "sparse/IncrementalCholesky.h"
#include "sparse/IncrementalPreconditioner.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <random>

namespace
{
using namespace esif;
using esif::test::SparseTestProblem;

/// Dense L (unit diagonal) and D of a simplicial LDL^T CHOLMOD factor.
void denseLdl(const cholmod_factor& F, Eigen::MatrixXd& L, Eigen::VectorXd& D)
{
	const int n = static_cast<int>(F.n);
	L = Eigen::MatrixXd::Identity(n, n);
	D.resize(n);
	const auto* p = static_cast<const int*>(F.p);
	const auto* nz = static_cast<const int*>(F.nz);
	const auto* li = static_cast<const int*>(F.i);
	const auto* lx = static_cast<const double*>(F.x);
	for (int j = 0; j < n; ++j)
	{
		D[j] = lx[p[j]];
		for (int t = p[j] + 1; t < p[j] + nz[j]; ++t) L(li[t], j) = lx[t];
	}
}

/// Column j of a simplicial factor, as (row, value) pairs.
std::vector<std::pair<int, double>> factorColumn(const cholmod_factor& F, int j)
{
	const auto* p = static_cast<const int*>(F.p);
	const auto* nz = static_cast<const int*>(F.nz);
	std::vector<std::pair<int, double>> out;
	for (int t = p[j]; t < p[j] + nz[j]; ++t)
		out.emplace_back(static_cast<const int*>(F.i)[t], static_cast<const double*>(F.x)[t]);
	return out;
}

/// Applies one problem step to a bare information form and a solver.
template <class Solver>
void applyStep(const esif::test::TestStep& step, InformationForm& info, Solver& solver)
{
	for (const auto& [kind, x0] : step.new_vars) info.addVariable(kind, x0);
	for (const auto& m : step.measurements)
		solver.noteUpdate(info, info.addMeasurement(m.vars, m.J, m.R, m.innovation));
}

/// First position the step's measurements touch among the variables
/// already there (the new ones go last): the p of eq. (3.27)/(3.32).
template <class Position>
int firstTouched(const esif::test::TestStep& step, const InformationForm& info, Position position)
{
	int first = info.scalarDim();
	for (const auto& m : step.measurements)
		for (VarId v : m.vars)
			if (v.value < info.variableCount())
				for (int g : info.scalarIndices({v})) first = std::min(first, position(g));
	return first;
}

SparseRecoveryParams smallN0()
{
	SparseRecoveryParams p;
	p.n0 = 60;  // many Case (i) and (ii) over a few thousand scalars
	return p;
}

TEST(IncrementalCholesky, CaseOneKeepsTheLeadingColumnsBitForBit)
{
	const SparseRecoveryParams params = smallN0();
	SparseCounters counters;
	CholmodCommon common;
	InformationForm info;
	IncrementalCholesky chol(params, counters, common);
	const SparseTestProblem problem(300, 17);
	int checked = 0;
	for (const auto& step : problem.steps())
	{
		// Where this step will touch the ordering (new variables go last).
		const std::size_t partial_before = counters.partial_refactorisations;
		const bool have_factor = chol.choleskyFactor() != nullptr;
		std::vector<std::vector<std::pair<int, double>>> leading;
		int first = info.scalarDim();
		if (have_factor)
		{
			first = firstTouched(step, info, [&](int g) {
				return chol.position(g);
			});
			for (int j = 0; j < first; ++j) leading.push_back(factorColumn(*chol.choleskyFactor(), j));
		}
		applyStep(step, info, chol);
		chol.refresh(info, step.robot);
		if (have_factor && counters.partial_refactorisations > partial_before)
		{
			// Eq. (3.35): L11 and L21 are those of the previous factor.
			for (int j = 0; j < first; ++j) ASSERT_EQ(factorColumn(*chol.choleskyFactor(), j), leading[j]) << j;
			++checked;
		}
	}
	EXPECT_GT(checked, 100);
	EXPECT_GT(counters.full_reorders, 2u);
}

/// Points on a 15-wide grid, each with a weak prior, and a robot wandering
/// along them: each update links 2 to 5 points near the robot, now and then
/// one far away (a loop). Thousands of updates on a few hundred scalars.
class LocalUpdates
{
   public:
	explicit LocalUpdates(int points) : rng_(41)
	{
		for (int k = 0; k < points; ++k)
		{
			const VarId v = info.addVariable(VarKind::Point2, Eigen::Vector2d(k % 15, k / 15));
			info.addPrior(v, info.position(v), Eigen::Matrix2d::Identity());
		}
	}

	/// Update number k; returns the robot position (reference point).
	template <class Solver>
	Eigen::Vector2d update(int k, Solver& solver)
	{
		const int n = info.variableCount(), center = (k / 4) % n;
		std::vector<VarId> vars;
		const int count = 2 + static_cast<int>(rng_() % 4);
		for (int a = 0; a < count; ++a) vars.push_back(VarId{(center + a) % n});
		if (rng_() % 50 == 0) vars.push_back(VarId{static_cast<int>((center + n / 2) % n)});
		Eigen::MatrixXd J =
			Eigen::MatrixXd::Zero(2 * (count - 1) + (vars.size() > std::size_t(count) ? 2 : 0), 2 * vars.size());
		for (std::size_t a = 1; a < vars.size(); ++a)
		{
			J.block<2, 2>(2 * (a - 1), 0) = -Eigen::Matrix2d::Identity();
			J.block<2, 2>(2 * (a - 1), 2 * a) = Eigen::Matrix2d::Identity();
		}
		const Eigen::MatrixXd R =
			0.01 * (Eigen::MatrixXd::Identity(J.rows(), J.rows()) + Eigen::MatrixXd::Constant(J.rows(), J.rows(), 0.5));
		const Eigen::VectorXd innovation = Eigen::VectorXd::Constant(J.rows(), 0.01 * (k % 7));
		solver.noteUpdate(info, info.addMeasurement(vars, J, R, innovation));
		return info.position(VarId{center});
	}

	InformationForm info;

   private:
	std::mt19937 rng_;
};

TEST(IncrementalCholesky, ThousandsOfUpdatesStillGiveTheFreshFactor)
{
	SparseRecoveryParams params;
	params.n0 = 80;
	SparseCounters counters;
	CholmodCommon common;
	LocalUpdates problem(150);
	IncrementalCholesky chol(params, counters, common);
	for (int k = 0; k < 4000; ++k) chol.refresh(problem.info, problem.update(k, chol));
	ASSERT_GT(counters.partial_refactorisations, 2000u);
	ASSERT_GT(counters.full_reorders, 5u);
	const InformationForm& info = problem.info;
	const cholmod_factor& F = *chol.choleskyFactor();

	// P A P^T for A = I bordered by identity padding rows, in the factor's ordering.
	const int N = chol.capacity(), n = info.scalarDim();
	Eigen::MatrixXd A = Eigen::MatrixXd::Identity(N, N);
	A.topLeftCorner(n, n) = info.matrix().toDense();
	Eigen::MatrixXd PAPt(N, N);
	for (int g = 0; g < N; ++g)
		for (int h = 0; h < N; ++h) PAPt(chol.position(g), chol.position(h)) = A(g, h);

	Eigen::MatrixXd L;
	Eigen::VectorXd D;
	denseLdl(F, L, D);
	// A backward-stable factorisation reproduces the matrix to ~n eps |A|.
	EXPECT_LT((L * D.asDiagonal() * L.transpose() - PAPt).norm() / PAPt.norm(), 1e-12);
	// The Cholesky factor of a positive definite matrix in a given ordering
	// is unique: the fresh one must agree, to about cond * eps.
	const Eigen::VectorXd ev =
		Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(PAPt, Eigen::EigenvaluesOnly).eigenvalues();
	ASSERT_LT(ev.maxCoeff() / ev.minCoeff(), 1e6);
	const Eigen::LLT<Eigen::MatrixXd> fresh(PAPt);
	ASSERT_EQ(fresh.info(), Eigen::Success);
	const Eigen::MatrixXd incremental = L * D.cwiseSqrt().asDiagonal();
	const Eigen::MatrixXd reference = fresh.matrixL();
	EXPECT_LT((incremental - reference).norm() / reference.norm(), 1e-9);
	// And the state carried by the updated forward solution is the fresh one.
	Eigen::VectorXd x;
	chol.solveState(info, x);
	const Eigen::VectorXd x_ref = info.matrix().toDense().llt().solve(info.vector());
	EXPECT_LT((x - x_ref).norm() / x_ref.norm(), 1e-9);
}

TEST(IncrementalPreconditioner, CaseOneKeepsTheLeadingColumnsAndApproximatesI)
{
	const SparseRecoveryParams params = smallN0();
	SparseCounters counters;
	CholmodCommon common;
	InformationForm info;
	IncrementalPreconditioner M(params, counters, common);
	const SparseTestProblem problem(400, 31, 0.01);
	int checked = 0;
	for (const auto& step : problem.steps())
	{
		const std::size_t partial_before = counters.partial_refactorisations;
		const LowerCsc before = M.factor();
		int first = info.scalarDim();
		if (before.n > 0)
			first = firstTouched(step, info, [&](int g) {
				return M.position(g);
			});
		applyStep(step, info, M);
		M.refresh(info, step.robot);
		if (before.n > 0 && counters.partial_refactorisations > partial_before)
		{
			// Eq. (3.31): the leading columns of L~ are kept.
			const LowerCsc& after = M.factor();
			ASSERT_EQ(after.col_ptr[first], before.col_ptr[first]);
			for (int t = 0; t < before.col_ptr[first]; ++t)
			{
				ASSERT_EQ(after.row_idx[t], before.row_idx[t]);
				ASSERT_EQ(after.values[t], before.values[t]);
			}
			++checked;
		}
	}
	EXPECT_GT(checked, 100);
	// M^-1 I is close to the identity: the preconditioner is a good one
	// (drop tolerance 1e-7, errors accumulated over ~400 Case (i) steps).
	const Eigen::MatrixXd I = info.matrix().toDense();
	Eigen::MatrixXd MinvI(I.rows(), I.cols());
	Eigen::VectorXd z;
	for (int c = 0; c < I.cols(); ++c)
	{
		M.apply(I.col(c), z);
		MinvI.col(c) = z;
	}
	EXPECT_LT((MinvI - Eigen::MatrixXd::Identity(I.rows(), I.cols())).norm() / std::sqrt(double(I.rows())), 1e-3);
}

}  // namespace
