#pragma once
/// \file VariableOrdering.h
/// Reorderings of the state vector for the factor rebuilt in Case (ii) of
/// book Sec. 3.3.1.1 / 3.3.2.1. The first two keep the variables near the reference
/// point (the robot, or a reference feature) at the end of the ordering, so
/// that the next updates, which touch what is near, touch only a short
/// trailing part of the factor (Case i). Variables stay contiguous (block
/// orderings), as CHOLMOD's supernodes would group them anyway. The other
/// two, unconstrained AMD and nested dissection, trade that for less fill.

#include "sparse/Cholmod.h"
#include <esif/sparse/InformationForm.h>
#include <esif/sparse/SparseRecoveryParams.h>

#include <Eigen/Core>
#include <vector>

namespace esif
{
/// A permutation of scalars: order[k] is the scalar at position k, and
/// position[g] the position of scalar g.
struct ScalarOrdering
{
	std::vector<int> order;
	std::vector<int> position;

	/// Appends scalar g at the next position.
	void append(int g);
};

/// The book's ordering: variables by decreasing distance of their estimate
/// from `reference`, farthest first, nearest last (ties by creation).
std::vector<VarId> orderByDistance(const InformationForm& info, const Eigen::Vector2d& reference);

/// CAMD (minimum degree) on the graph of variables, constrained so that the
/// nearest variables come last: they fill `near_sets` sets of about
/// `set_dim` scalars each, ordered from far to near; all others form the
/// first set.
std::vector<VarId> orderByCamd(const InformationForm& info, const Eigen::Vector2d& reference, int set_dim,
							   int near_sets, CholmodCommon& c);

/// AMD (minimum degree) on the graph of variables with no constraint: the
/// least fill, wherever the near variables end up. An update then touches
/// the elimination-tree paths of its variables from wherever they sit, which
/// cholmod_updown pays for path by path; so it pairs with the fill-growth
/// trigger, not with the book's n0, which would rebuild at nearly every update.
std::vector<VarId> orderByAmd(const InformationForm& info, CholmodCommon& c);

/// CHOLMOD's nested dissection on the graph of variables with no
/// constraint: METIS vertex separators, ordered last, and constrained
/// minimum degree (CAMD) within the parts. On a map that spreads in two
/// dimensions the separators stay about sqrt(n) wide, so the factor fills in
/// as n log n where a minimum-degree ordering, blind to geometry, fills
/// faster once the map is large.
std::vector<VarId> orderByNestedDissection(const InformationForm& info, CholmodCommon& c);

/// The reordering chosen by `params` (n0/2 scalars per CAMD near set).
std::vector<VarId> reorderVariables(const InformationForm& info, const Eigen::Vector2d& reference,
									const SparseRecoveryParams& params, CholmodCommon& c);

/// The scalars of `vars` in that order, followed by the scalars
/// info.scalarDim() .. size-1 (padding rows) in natural order.
ScalarOrdering expandOrdering(const InformationForm& info, const std::vector<VarId>& vars, int size);

}  // namespace esif
