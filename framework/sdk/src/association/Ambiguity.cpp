#include <esif/association/Ambiguity.h>
#include <esif/association/Chi2.h>

namespace esif
{
double ambiguityMarginDistance2(double quantile) { return quantile > 0 ? chi2Quantile(quantile, 2) : 0; }

bool ambiguousMatch(const Eigen::VectorXd& d2, Eigen::Index chosen, double margin_d2,
					const std::function<double(Eigen::Index)>& sensor_separation_d2)
{
	if (margin_d2 <= 0) return false;
	for (Eigen::Index j = 0; j < d2.size(); ++j)
		if (j != chosen && d2(j) < d2(chosen) + margin_d2 && sensor_separation_d2(j) >= margin_d2) return true;
	return false;
}

}  // namespace esif
