#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include "sparse/PivotCheck.h"

#include <algorithm>
#include <cmath>

namespace esif
{
void checkPivots(const std::vector<double>& pivots, int first_position, const std::vector<int>& order, double min_ratio,
				 const InformationForm& info, const std::string& what)
{
	const int n = info.scalarDim();
	for (std::size_t k = std::max(0, first_position); k < pivots.size() && k < order.size(); ++k)
	{
		const int g = order[k];
		if (g >= n) continue;
		const double d = pivots[k], a = info.matrix().diagonalEntry(g);
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
}

}  // namespace esif
