#pragma once
/// \file SparseRecoveryParams.h
/// Parameters of the sparse information core's state and covariance
/// recovery (book Sec. 3.3). A plugin declares them inside its own INI
/// section by calling declare() from its own parameter struct.

#include <esif/config/ParamBinder.h>

namespace esif
{
/// How x = I^-1 i and covariance columns are recovered.
enum class RecoveryMethod
{
	IncrementalCholesky,  ///< complete Cholesky kept up to date, Sec. 3.3.2 / App. B.1
	Pcg,                  ///< preconditioned conjugate gradient, incremental IC preconditioner, Sec. 3.3.1 / App. B.2
	FreshCholesky         ///< fill-reducing (AMD) factorisation from scratch at every change: the reference
};

/// How variables are reordered when the factor is rebuilt (Case ii).
enum class Reordering
{
	Distance,  ///< the book's: by distance from the reference point, farthest first
	Camd,      ///< SuiteSparse CAMD, fill-reducing within constraint sets, nearest set last
	Amd,       ///< SuiteSparse AMD, fill-reducing with no constraint (pairs with ReorderTrigger::FillGrowth)
	NestedDissection  ///< CHOLMOD's nested dissection (METIS separators, CAMD within), no constraint
};

/// When the incremental Cholesky factor is rebuilt (Case ii).
enum class ReorderTrigger
{
	TrailingDimension,  ///< the book's: an update reaches n0 scalars from the end of the ordering
	FillGrowth          ///< the factor has filled in by max_fill_growth beyond its fresh non-zeros
};

struct SparseRecoveryParams
{
	RecoveryMethod recovery = RecoveryMethod::IncrementalCholesky;  ///< incremental_cholesky | pcg | fresh_cholesky
	Reordering reordering = Reordering::Distance;                   ///< distance | camd | amd | nested_dissection
	/// n0 of Sec. 3.3.1.1 / 3.3.2.1: when the trailing part touched since the
	/// last factorisation (dimension of H_R, in scalars) reaches n0, reorder
	/// and factor afresh; below it, refactor the trailing part only. The book
	/// used 500 for the complete Cholesky (Sec. 5.5) and 100 for PCG (Sec.
	/// 3.3.1.1); PCG's trailing refactorisation, H_R + L~22 L~22^T, grows
	/// faster with n0 than CHOLMOD's update, so smaller values suit it.
	int n0 = 500;
	/// CAMD: the nearest variables fill this many constraint sets of about
	/// n0/2 scalars each, nearest last; everything else is the first set.
	int camd_near_sets = 2;
	/// The book rebuilds the factor once an update reaches n0 scalars from
	/// the end of the ordering. That position says little about the cost:
	/// cholmod_updown touches only the elimination-tree paths of the updated
	/// rows, wherever they start. What a stale ordering does cost is fill,
	/// which every later update and solve pays for. fill_growth rebuilds when
	/// nnz(L) exceeds (1 + max_fill_growth) times the non-zeros of the last
	/// fresh factorisation, scaled by the growth of the state since. Like
	/// the pcg_* keys for PCG, it concerns one method: the incremental
	/// Cholesky. PCG's preconditioner keeps the book's n0, so a plugin whose
	/// default is fill_growth still runs with `recovery = pcg`.
	ReorderTrigger reorder_trigger = ReorderTrigger::TrailingDimension;  ///< trailing_dimension | fill_growth
	double max_fill_growth = 0.2;
	double pcg_relative_tolerance = 1e-10;  ///< PCG stops when |I x - b| <= this * |b|
	int pcg_max_iterations = 200;           ///< PCG gives up (NumericalError) after this many iterations
	/// Incomplete Cholesky drops L_ij when |L_ij| sqrt(A_jj) < this * |A(j:n, j)|_1
	/// (the book used MATLAB cholinc with drop tolerance 1e-7).
	double ic_drop_tolerance = 1e-7;
	/// A pivot d_j with d_j / A_jj below this has lost all but a few digits
	/// to cancellation: the information matrix is (numerically) singular.
	double min_pivot_ratio = 1e-12;

	void declare(ParamBinder& b);
};

/// INI name of a recovery method ("incremental_cholesky", "pcg", "fresh_cholesky").
const char* recoveryMethodName(RecoveryMethod m);
/// INI name of a reordering ("distance", "camd", "amd", "nested_dissection").
const char* reorderingName(Reordering r);
/// The reordering as a figure names it ("CAMD reordering", ...).
const char* reorderingTitle(Reordering r);
/// INI name of a reorder trigger ("trailing_dimension", "fill_growth").
const char* reorderTriggerName(ReorderTrigger t);

}  // namespace esif
