#include "SolutionChecks.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <unordered_set>

namespace esif::ceres_full
{
std::size_t countDegeneratePoses(const FullSlamGraph& graph, double distance_m)
{
	std::unordered_set<std::size_t> degenerate;
	for (const ObservationRecord& o : graph.observations())
	{
		if (!o.block) continue;	 // dropped as an outlier
		const Eigen::Vector2d sensor = compose(graph.pose(o.pose), o.sensor_on_robot).head<2>();
		const double distance = (graph.landmark(o.landmark) - sensor).norm();
		if (distance < distance_m && o.range_m - distance > kDegenerateRangeSigmas * o.range_std_m)
			degenerate.insert(o.pose);
	}
	return degenerate.size();
}

double SolutionCheck::chi2PerDof() const
{
	return dof > 0 ? chi2 / dof : std::numeric_limits<double>::quiet_NaN();
}

std::string SolutionCheck::warning(double max_chi2_per_dof) const
{
	if (plausible) return {};
	std::ostringstream w;
	w << "implausible optimum:";
	if (degenerate_poses > 0) w << " " << degenerate_poses << " pose(s) on a landmark they measured further away;";
	if (excess_outliers > 0)
		w << " " << excess_outliers << " measurements beyond the outlier gate, too many to be outliers (none dropped);";
	w << " chi2 / dof = " << chi2PerDof();
	if (chi2PerDof() > max_chi2_per_dof) w << " (above max_chi2_per_dof = " << max_chi2_per_dof << ")";
	w << " - a local minimum or a wrong noise model or association";
	return w.str();
}

SolutionCheck checkSolution(
	double chi2, double dof, std::size_t degenerate_poses, double max_chi2_per_dof, std::size_t excess_outliers)
{
	SolutionCheck c{chi2, dof, degenerate_poses, excess_outliers, true};
	// NaN (no redundancy) compares false: nothing to judge the cost by.
	c.plausible = degenerate_poses == 0 && excess_outliers == 0 && !(c.chi2PerDof() > max_chi2_per_dof);
	return c;
}

}  // namespace esif::ceres_full
