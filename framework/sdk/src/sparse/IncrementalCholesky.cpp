#include <esif/core/Errors.h>
#include "sparse/IncrementalCholesky.h"
#include "sparse/EliminationTreeSolves.h"
#include "sparse/PivotCheck.h"
#include "sparse/StaircaseUpdate.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace esif
{
namespace
{
const std::string kCholeskyWhat = "sparse recovery (incremental Cholesky)";

/// Padding rows reserved beyond the current dimension at each fresh
/// factorisation: enough for many steps of new features, few enough that
/// the identity rows cost nothing noticeable in the solves.
int capacityFor(int n)
{
	return n + std::max(64, n / 4);
}
}  // namespace

IncrementalCholesky::IncrementalCholesky(const SparseRecoveryParams& params, SparseCounters& counters,
										 CholmodCommon& common)
	: params_(params), counters_(counters), common_(common)
{
}

void IncrementalCholesky::noteUpdate(const InformationForm& info, const UpdateTerm& term)
{
	if (!L_) return;
	if (info.scalarDim() > capacity_) updates_.overflow();  // out of padding rows: Case (ii)
	updates_.record(info, term, ordering_.position, trailingLimit());
}

int IncrementalCholesky::trailingLimit() const
{
	return params_.reorder_trigger == ReorderTrigger::TrailingDimension ? params_.n0 : capacity_ + 1;
}

bool IncrementalCholesky::filledInTooMuch() const
{
	return params_.reorder_trigger == ReorderTrigger::FillGrowth &&
		static_cast<double>(factorNonZeros()) >
		(1.0 + params_.max_fill_growth) * fresh_nnz_per_scalar_ * static_cast<double>(factored_dim_);
}

void IncrementalCholesky::refresh(const InformationForm& info, const Eigen::Vector2d& reference)
{
	if (info.scalarDim() == 0) throw NumericalError(kCholeskyWhat + ": the information form has no variables");
	if (!L_ || updates_.overflowed() || info.scalarDim() > capacity_)
		factorAfresh(info, reference);
	else if (!updates_.empty() || info.scalarDim() > factored_dim_)
		refactorTrailingPart(info);
}

void IncrementalCholesky::factorAfresh(const InformationForm& info, const Eigen::Vector2d& reference)
{
	const int n = info.scalarDim();
	capacity_ = capacityFor(n);
	const ScalarOrdering wanted = expandOrdering(info, reorderVariables(info, reference, params_, common_), capacity_);

	// A = I bordered by identity padding rows, in natural order; the
	// ordering goes to CHOLMOD as given.
	auto A = naturalLowerToCholmod(info.matrix(), capacity_, common_);
	common_.useGivenOrderingForModification();
	std::vector<int> perm = wanted.order;
	L_ = ownFactor(cholmod_analyze_p(A.get(), perm.data(), nullptr, 0, common_.get()), common_);
	if (!L_) common_.check(kCholeskyWhat + ": analysis");
	counters_.fresh_factor_flops += common_.get()->fl;  // set by the analysis for this ordering
	cholmod_factorize(A.get(), L_.get(), common_.get());
	common_.check(kCholeskyWhat + ": factorisation");

	const auto* p = static_cast<const int*>(L_->Perm);
	if (!std::equal(wanted.order.begin(), wanted.order.end(), p))
		throw std::logic_error(kCholeskyWhat + ": CHOLMOD did not keep the given ordering");
	ordering_ = wanted;
	factored_dim_ = n;
	fresh_nnz_per_scalar_ = static_cast<double>(factorNonZeros()) / n;
	try
	{
		checkFactor(info);
	}
	catch (...)
	{
		L_.reset();  // never keep a factor that failed its check
		throw;
	}
	counters_.top_separator_scalars = static_cast<std::size_t>(denseTrailingColumns(*L_, n));
	forwardSolve(info);
	partial_.invalidate();
	delta_b_ = zeroDense(capacity_, 1, common_);
	updates_.restart(n);
	++counters_.full_reorders;
}

void IncrementalCholesky::refactorTrailingPart(const InformationForm& info)
{
	partial_.invalidate();
	try
	{
		const std::vector<int> touched = touchedPositions(info);
		applyPendingUpdates();
		removePaddingDiagonals(info);
		// The modifications changed only the columns on the paths of the
		// rows they touched: the other pivots passed their check before.
		const std::vector<int> paths = pathsToRoots(*L_, touched);
		checkPivotsAt(*L_, paths, ordering_.order, params_.min_pivot_ratio, info, kCholeskyWhat);
		counters_.updated_path_columns += paths.size();
	}
	catch (...)
	{
		L_.reset();  // the factor is unusable; the next refresh starts over
		throw;
	}
	factored_dim_ = info.scalarDim();
	updates_.restart(factored_dim_);
	++counters_.partial_refactorisations;
	// The factor is exact and serves this refresh's solves; the stale
	// ordering is replaced at the next one.
	if (filledInTooMuch()) updates_.overflow();
}

std::vector<int> IncrementalCholesky::touchedPositions(const InformationForm& info) const
{
	std::vector<int> out;
	for (const auto& term : updates_.terms())
		for (const int g : term.scalars) out.push_back(position(g));
	// A new scalar no update touched still needs its (zero) pivot checked.
	for (int g = factored_dim_; g < info.scalarDim(); ++g) out.push_back(position(g));
	return out;
}

void IncrementalCholesky::applyPendingUpdates()
{
	// C of all pending updates side by side, rows permuted by L->Perm
	// (cholmod_updown works on the rows of L, not of A), each in staircase
	// form. A new variable's rows go to its padding position (still an
	// identity row): the update gives it 1 + its information there, and
	// removePaddingDiagonals() takes the 1 back.
	std::vector<PositionedColumns> updates;
	for (const auto& term : updates_.terms()) updates.push_back(staircaseAtPositions(term));
	auto C = packColumns(updates, capacity_, common_);
	if (!C) return;
	cholmod_updown_solve(true, C.get(), L_.get(), y_.get(), delta_b_.get(), common_.get());
	common_.check(kCholeskyWhat + ": update of the trailing factor");
	counters_.updown_flops += common_.get()->modfl;
}

IncrementalCholesky::PositionedColumns IncrementalCholesky::staircaseAtPositions(const TrailingUpdates::Term& term)
{
	auto* db = static_cast<double*>(delta_b_->x);
	std::vector<std::pair<int, int>> rows;  // (position, row of term.C)
	for (std::size_t r = 0; r < term.scalars.size(); ++r)
	{
		rows.emplace_back(position(term.scalars[r]), static_cast<int>(r));
		db[rows.back().first] += term.delta_i[r];
	}
	std::sort(rows.begin(), rows.end());
	PositionedColumns out;
	Eigen::MatrixXd sorted(term.C.rows(), term.C.cols());
	for (std::size_t r = 0; r < rows.size(); ++r)
	{
		sorted.row(static_cast<Eigen::Index>(r)) = term.C.row(rows[r].second);
		out.positions.push_back(rows[r].first);
	}
	out.columns = staircase(sorted);
	return out;
}

CholmodSparsePtr IncrementalCholesky::packColumns(const std::vector<PositionedColumns>& updates, int rows,
												  CholmodCommon& c)
{
	// Column j of a staircase is stored from its row j down, zeros included:
	// every touched position stays in C's pattern (column 0 holds them
	// all), so cholmod_updown_solve applies its delta_b there.
	int columns = 0;
	std::size_t nnz = 0;
	for (const auto& u : updates)
		for (Eigen::Index j = 0; j < u.columns.cols(); ++j, ++columns) nnz += u.columns.rows() - j;
	if (nnz == 0) return nullptr;
	auto C = ownSparse(cholmod_allocate_sparse(rows, columns, nnz, true, true, 0, CHOLMOD_REAL, c.get()), c);
	if (!C) c.check(kCholeskyWhat + ": allocating the update");
	auto* cp = static_cast<int*>(C->p);
	auto* ci = static_cast<int*>(C->i);
	auto* cx = static_cast<double*>(C->x);
	int col = 0, k = 0;
	for (const auto& u : updates)
		for (Eigen::Index j = 0; j < u.columns.cols(); ++j, ++col)
		{
			cp[col] = k;
			for (Eigen::Index r = j; r < u.columns.rows(); ++r)
			{
				ci[k] = u.positions[static_cast<std::size_t>(r)];
				cx[k++] = u.columns(r, j);
			}
		}
	cp[columns] = k;
	return C;
}

void IncrementalCholesky::removePaddingDiagonals(const InformationForm& info)
{
	// A padding row was the identity row e_g (y_g = 0); after the update
	// its diagonal holds 1 + I(g, g). A rank-one downdate per new scalar
	// takes the 1 back, so the factor is exactly that of I. New scalars sit
	// last, so their paths, and this downdate, are short; one cholmod_rowadd
	// per new scalar instead solved a row over the paths of every variable
	// it is linked to. The downdate cancels about log10(1 + 1 / I(g, g))
	// digits: none that matter for information above 1e-2 (a feature 100 m
	// off with 10 m noise). A scalar that got no information is left with a
	// zero pivot, which the pivot check reports.
	const int added = info.scalarDim() - factored_dim_;
	if (added <= 0) return;
	auto E = ownSparse(cholmod_allocate_sparse(capacity_, added, added, true, true, 0, CHOLMOD_REAL, common_.get()),
					   common_);
	if (!E) common_.check(kCholeskyWhat + ": allocating the padding downdate");
	for (int c = 0; c < added; ++c)
	{
		static_cast<int*>(E->p)[c] = c;
		static_cast<int*>(E->i)[c] = position(factored_dim_ + c);
		static_cast<double*>(E->x)[c] = 1.0;
	}
	static_cast<int*>(E->p)[added] = added;
	cholmod_updown_solve(false, E.get(), L_.get(), y_.get(), delta_b_.get(), common_.get());
	common_.check(kCholeskyWhat + ": adding " + info.describeScalar(factored_dim_) + " and the other new variables");
	counters_.updown_flops += common_.get()->modfl;
}

void IncrementalCholesky::forwardSolve(const InformationForm& info)
{
	auto b = zeroDense(capacity_, 1, common_);
	std::copy(info.vector().data(), info.vector().data() + info.scalarDim(), static_cast<double*>(b->x));
	CholmodDensePtr pb;
	cholmodSolve(CHOLMOD_P, L_.get(), b.get(), pb, ws_, common_, kCholeskyWhat + ": permuting i");
	cholmodSolve(CHOLMOD_L, L_.get(), pb.get(), y_, ws_, common_, kCholeskyWhat + ": forward substitution");
}

void IncrementalCholesky::checkFactor(const InformationForm& info)
{
	checkPivots(factorPivots(*L_), 0, ordering_.order, params_.min_pivot_ratio, info, kCholeskyWhat);
}

void IncrementalCholesky::solveState(const InformationForm& info, Eigen::VectorXd& x)
{
	// Eq. (3.37): back substitution D L^T z = y, then x = P^T z.
	cholmodSolve(CHOLMOD_DLt, L_.get(), y_.get(), z_, ws_, common_, kCholeskyWhat + ": back substitution");
	cholmodSolve(CHOLMOD_Pt, L_.get(), z_.get(), x_, ws_, common_, kCholeskyWhat + ": permuting the state");
	counters_.back_substitution_columns += static_cast<std::size_t>(factored_dim_);
	x = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(x_->x), info.scalarDim());
}

Eigen::MatrixXd IncrementalCholesky::solveColumns(const InformationForm& info, const std::vector<int>& scalars)
{
	// Eq. (3.25) for several unit vectors at once.
	const int k = static_cast<int>(scalars.size());
	auto B = zeroDense(capacity_, k, common_);
	for (int j = 0; j < k; ++j) static_cast<double*>(B->x)[static_cast<std::size_t>(j) * capacity_ + scalars[j]] = 1.0;
	CholmodDensePtr X;
	cholmodSolve(CHOLMOD_A, L_.get(), B.get(), X, ws_, common_, kCholeskyWhat + ": covariance columns");
	const Eigen::Map<const Eigen::MatrixXd> all(static_cast<const double*>(X->x), capacity_, k);
	return all.topRows(info.scalarDim());
}

Eigen::MatrixXd IncrementalCholesky::solveCovarianceBlock(const InformationForm& info, const std::vector<int>& scalars)
{
	if (L_->is_super || L_->is_ll) return RecoverySolver::solveCovarianceBlock(info, scalars);
	// P A P^T = L D L^T, so A^-1 = P^T L^-T D^-1 L^-1 P and the entry for
	// positions a, b is sum_j y_a(j) y_b(j) / d_j with y_a = L^-1 e_a, which
	// is non-zero only on a's elimination-tree path: the k right-hand sides
	// are solved together over the union of their paths.
	std::vector<int> pos(scalars.size());
	for (std::size_t a = 0; a < scalars.size(); ++a) pos[a] = ordering_.position[scalars[a]];
	const Eigen::MatrixXd Z = scaledForwardColumns(*L_, pos, pathsToRoots(*L_, pos));
	const Eigen::MatrixXd P = Z * Z.transpose();
	return 0.5 * (P + P.transpose());
}

bool IncrementalCholesky::solvesStatePartially() const
{
	return L_ && !L_->is_super && !L_->is_ll;
}

Eigen::VectorXd IncrementalCholesky::solveStateAt(const std::vector<int>& scalars)
{
	// x = P^T z: scalar g's value is z at its position.
	std::vector<int> pos(scalars.size());
	for (std::size_t a = 0; a < scalars.size(); ++a)
	{
		if (scalars[a] >= factored_dim_) throw std::logic_error(kCholeskyWhat + ": a scalar outside the factor was read");
		pos[a] = ordering_.position[scalars[a]];
	}
	const long before = partial_.columnsSolved();
	Eigen::VectorXd x = partial_.solveAt(*L_, static_cast<const double*>(y_->x), pos);
	counters_.back_substitution_columns += static_cast<std::size_t>(partial_.columnsSolved() - before);
	return x;
}

std::size_t IncrementalCholesky::factorNonZeros() const
{
	return L_ ? countFactorNonZeros(*L_, factored_dim_) : 0;
}

}  // namespace esif
