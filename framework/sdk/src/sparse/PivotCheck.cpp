#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include "sparse/Cholmod.h"
#include "sparse/PivotCheck.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace esif
{
namespace
{
/// Pivot d of scalar g (position k): positive, and not cancelled below
/// min_ratio of I(g, g).
void checkPivot(double d, int g, double min_ratio, const InformationForm& info, const std::string& what)
{
	const double a = info.matrix().diagonalEntry(g);
	if (!(a > 0))
		throw NumericalError(what + ": " + info.describeScalar(g) +
							 " has no information (never observed): the information matrix is singular");
	if (!std::isfinite(d) || d <= 0)
		throw NumericalError(what + ": information matrix is not positive definite at " + info.describeScalar(g) +
							 " (pivot " + formatNumber(d) + ")");
	if (d / a < min_ratio)
		throw NumericalError(what + ": information matrix is numerically singular at " + info.describeScalar(g) +
							 " (pivot / diagonal = " + formatNumber(d / a) + " < min_pivot_ratio " +
							 formatNumber(min_ratio) + "; is every variable observed in every direction?)");
}
}  // namespace

void checkPivots(const std::vector<double>& pivots, int first_position, const std::vector<int>& order, double min_ratio,
				 const InformationForm& info, const std::string& what)
{
	const int n = info.scalarDim();
	for (std::size_t k = std::max(0, first_position); k < pivots.size() && k < order.size(); ++k)
		if (order[k] < n) checkPivot(pivots[k], order[k], min_ratio, info, what);
}

void checkPivotsAt(const cholmod_factor& L, const std::vector<int>& positions, const std::vector<int>& order,
				   double min_ratio, const InformationForm& info, const std::string& what)
{
	if (L.is_super || L.is_ll) throw std::logic_error("checkPivotsAt: needs a simplicial LDL^T factor");
	const int n = info.scalarDim();
	for (const int k : positions)
		if (k < static_cast<int>(order.size()) && order[k] < n)
			checkPivot(simplicialPivot(L, k), order[k], min_ratio, info, what);
}

}  // namespace esif
