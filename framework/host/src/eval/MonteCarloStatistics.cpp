/// \file MonteCarloStatistics.cpp
/// ANEES with chi-square bounds, RMSE and time over a campaign's runs; see
/// MonteCarloStatistics.h.

#include <esif/eval/MonteCarloStatistics.h>

#include <esif/association/Chi2.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <tuple>

namespace esif
{
namespace
{
/// Linear interpolation between the order statistics of sorted `v` (not empty).
double sortedQuantile(const std::vector<double>& v, double p)
{
	const double at = p * static_cast<double>(v.size() - 1);
	const auto i = static_cast<std::size_t>(std::floor(at));
	const std::size_t j = std::min(i + 1, v.size() - 1);
	return v[i] + (at - static_cast<double>(i)) * (v[j] - v[i]);
}

/// What the runs hold at one step.
struct StepAccumulator
{
	std::vector<double> nees, position_nees, heading_nees;
	std::vector<double> position_errors;
	double heading_sq = 0;
};

struct LandmarkAccumulator
{
	std::vector<double> nees;
	double sq = 0;
	std::size_t n = 0;
};

double mean(const std::vector<double>& v)
{
	double sum = 0;
	for (const double x : v) sum += x;
	return sum / static_cast<double>(v.size());
}

StepStatistics stepStatistics(std::size_t step, const StepAccumulator& acc)
{
	StepStatistics s;
	s.step = step;
	s.runs = acc.nees.size();
	if (s.runs > 0)
	{
		s.anees = mean(acc.nees);
		s.bounds = aneesBounds(3, s.runs);
	}
	if (!acc.position_nees.empty())
	{
		s.anees_position = mean(acc.position_nees);
		s.bounds_position = aneesBounds(2, acc.position_nees.size());
	}
	if (!acc.heading_nees.empty())
	{
		s.anees_heading = mean(acc.heading_nees);
		s.bounds_heading = aneesBounds(1, acc.heading_nees.size());
	}
	const std::size_t reached = acc.position_errors.size();
	if (reached > 0)
	{
		double sq = 0;
		for (const double e : acc.position_errors) sq += e * e;
		s.position_rmse_m = std::sqrt(sq / static_cast<double>(reached));
		s.heading_rmse_rad = std::sqrt(acc.heading_sq / static_cast<double>(reached));
		std::vector<double> sorted = acc.position_errors;
		std::sort(sorted.begin(), sorted.end());
		s.position_error_p10_m = sortedQuantile(sorted, 0.10);
		s.position_error_p90_m = sortedQuantile(sorted, 0.90);
	}
	return s;
}

/// Per-step statistics and, into `out`, the pose ANEES summary.
void addPoseStatistics(const std::vector<CampaignRunErrors>& runs, ConfigStatistics& out)
{
	std::map<std::size_t, StepAccumulator> by_step;
	for (const auto& run : runs)
		for (const auto& row : run.poses)
		{
			auto& acc = by_step[row.step];
			if (row.nees) acc.nees.push_back(*row.nees);
			if (row.position_nees) acc.position_nees.push_back(*row.position_nees);
			if (row.heading_nees) acc.heading_nees.push_back(*row.heading_nees);
			acc.position_errors.push_back(row.error.head<2>().norm());
			acc.heading_sq += row.error(2) * row.error(2);
		}
	double anees_sum = 0;
	std::size_t with_anees = 0, inside = 0;
	std::vector<double> position, heading;
	for (const auto& [step, acc] : by_step)
	{
		out.steps.push_back(stepStatistics(step, acc));
		const auto& s = out.steps.back();
		if (s.anees_position) position.push_back(*s.anees_position);
		if (s.anees_heading) heading.push_back(*s.anees_heading);
		if (!s.anees) continue;
		anees_sum += *s.anees;
		++with_anees;
		if (s.bounds.contains(*s.anees)) ++inside;
	}
	out.pose_bounds = aneesBounds(3, runs.size());
	if (!position.empty()) out.pose_position_anees_mean = mean(position);
	if (!heading.empty()) out.pose_heading_anees_mean = mean(heading);
	if (with_anees == 0) return;
	out.pose_anees_mean = anees_sum / static_cast<double>(with_anees);
	out.pose_steps_inside_fraction = static_cast<double>(inside) / static_cast<double>(with_anees);
}

void addLandmarkStatistics(const std::vector<CampaignRunErrors>& runs, ConfigStatistics& out)
{
	std::map<LandmarkId, LandmarkAccumulator> by_id;
	double nees_sum = 0;
	std::size_t pairs = 0;
	for (const auto& run : runs)
		for (const auto& row : run.landmarks)
		{
			auto& acc = by_id[row.true_id];
			acc.sq += row.error.squaredNorm();
			++acc.n;
			if (!row.nees) continue;
			acc.nees.push_back(*row.nees);
			nees_sum += *row.nees;
			++pairs;
		}
	std::size_t with_anees = 0, inside = 0;
	for (const auto& [id, acc] : by_id)
	{
		LandmarkStatistics s;
		s.true_id = id;
		s.runs = acc.nees.size();
		s.rmse_m = std::sqrt(acc.sq / static_cast<double>(acc.n));
		if (s.runs > 0)
		{
			s.anees = mean(acc.nees);
			s.bounds = aneesBounds(2, s.runs);
			++with_anees;
			if (s.bounds.contains(s.anees)) ++inside;
		}
		out.landmarks.push_back(s);
	}
	out.landmark_bounds = aneesBounds(2, runs.size());
	if (pairs > 0) out.landmark_anees = nees_sum / static_cast<double>(pairs);
	if (with_anees > 0) out.landmarks_inside_fraction = static_cast<double>(inside) / static_cast<double>(with_anees);
}

/// sqrt(mean |e|^2) of a run's trajectory positions and of its landmarks.
double trajectoryRmse(const std::vector<PoseError>& rows)
{
	double sq = 0;
	for (const auto& r : rows) sq += r.error.head<2>().squaredNorm();
	return rows.empty() ? 0.0 : std::sqrt(sq / static_cast<double>(rows.size()));
}

double landmarkRmse(const std::vector<LandmarkError>& rows)
{
	double sq = 0;
	for (const auto& r : rows) sq += r.error.squaredNorm();
	return rows.empty() ? 0.0 : std::sqrt(sq / static_cast<double>(rows.size()));
}
}  // namespace

AneesBounds aneesBounds(int dof, std::size_t runs, double confidence)
{
	if (dof < 1 || runs < 1) throw std::invalid_argument("aneesBounds: dof and runs must be >= 1");
	if (!(confidence > 0 && confidence < 1)) throw std::invalid_argument("aneesBounds: confidence must be in (0, 1)");
	const double n = static_cast<double>(runs);
	const double total_dof = dof * n;  // the sum of `runs` chi-square(dof) NEES values
	if (total_dof > std::numeric_limits<int>::max())
		throw std::invalid_argument("aneesBounds: dof x runs exceeds the largest chi-square dof supported");
	const int k = static_cast<int>(total_dof);
	return {chi2Quantile((1 - confidence) / 2, k) / n, chi2Quantile((1 + confidence) / 2, k) / n};
}

Quantiles quantilesOf(std::vector<double> values)
{
	if (values.empty()) throw std::invalid_argument("quantilesOf: no values");
	std::sort(values.begin(), values.end());
	return {sortedQuantile(values, 0.5), sortedQuantile(values, 0.25), sortedQuantile(values, 0.75), values.front(),
			values.back()};
}

MeanSpread meanSpreadOf(const std::vector<double>& values)
{
	if (values.empty()) throw std::invalid_argument("meanSpreadOf: no values");
	double sum = 0;
	for (const double v : values) sum += v;
	const double mean = sum / static_cast<double>(values.size());
	if (values.size() == 1) return {mean, 0.0};
	double sq = 0;
	for (const double v : values) sq += (v - mean) * (v - mean);
	return {mean, std::sqrt(sq / static_cast<double>(values.size() - 1))};
}

namespace
{
void addStateStatistics(const std::vector<CampaignRunErrors>& runs, ConfigStatistics& out)
{
	double nees = 0;
	std::size_t dof = 0, inside = 0;
	for (const auto& run : runs)
	{
		if (!run.state_nees || run.state_nees_dof == 0) continue;
		++out.state_runs;
		nees += *run.state_nees;
		dof += run.state_nees_dof;
		const AneesBounds own = aneesBounds(static_cast<int>(run.state_nees_dof), 1);
		if (own.contains(*run.state_nees)) ++inside;
	}
	if (out.state_runs == 0) return;
	out.state_anees_per_dof = nees / static_cast<double>(dof);
	out.state_bounds = aneesBounds(1, dof);	 // chi2(D) / D: D runs of one dof have the same bounds
	out.state_runs_inside_fraction = static_cast<double>(inside) / static_cast<double>(out.state_runs);
}
}  // namespace

namespace
{
/// The values of `field` over the runs that have one.
std::vector<double> presentValues(
	const std::vector<CampaignRunErrors>& runs, std::optional<double> CampaignRunErrors::*field)
{
	std::vector<double> out;
	for (const auto& run : runs)
		if (run.*field) out.push_back(*(run.*field));
	return out;
}

/// The sum of `field` over the runs, and how many runs have it above 0.
std::pair<long long, std::size_t> totalOf(
	const std::vector<CampaignRunErrors>& runs, std::optional<double> CampaignRunErrors::*field)
{
	long long total = 0;
	std::size_t runs_with = 0;
	for (const double v : presentValues(runs, field))
	{
		total += static_cast<long long>(v);
		runs_with += v > 0;
	}
	return {total, runs_with};
}

void addMapScoreStatistics(const std::vector<CampaignRunErrors>& runs, ConfigStatistics& out)
{
	if (const auto v = presentValues(runs, &CampaignRunErrors::landmarks_true); !v.empty())
		out.landmarks_true_median = quantilesOf(v).median;
	if (const auto v = presentValues(runs, &CampaignRunErrors::landmarks_found); !v.empty())
		out.landmarks_found_median = quantilesOf(v).median;
	std::tie(out.landmarks_duplicated_total, out.runs_with_duplicated) =
		totalOf(runs, &CampaignRunErrors::landmarks_duplicated);
	std::tie(out.landmarks_spurious_total, out.runs_with_spurious) =
		totalOf(runs, &CampaignRunErrors::landmarks_spurious);
	if (const auto v = presentValues(runs, &CampaignRunErrors::da_precision); !v.empty()) out.da_precision = quantilesOf(v);
	if (const auto v = presentValues(runs, &CampaignRunErrors::da_recall); !v.empty()) out.da_recall = quantilesOf(v);
	if (const auto v = presentValues(runs, &CampaignRunErrors::landmark_ospa_m); !v.empty())
		out.landmark_ospa_m = meanSpreadOf(v);
}
}  // namespace

ConfigStatistics aggregateRuns(const std::string& name, const std::vector<CampaignRunErrors>& runs)
{
	if (runs.empty()) throw std::invalid_argument("aggregateRuns: " + name + ": no finished run");
	ConfigStatistics out;
	out.name = name;
	out.runs = runs.size();
	addPoseStatistics(runs, out);
	addLandmarkStatistics(runs, out);
	addStateStatistics(runs, out);
	addMapScoreStatistics(runs, out);
	std::vector<double> trajectory, landmarks, wall;
	for (const auto& run : runs)
	{
		trajectory.push_back(trajectoryRmse(run.poses));
		landmarks.push_back(landmarkRmse(run.landmarks));
		wall.push_back(run.wall_s);
		out.da_wrong_total += run.da_wrong;
		if (run.da_wrong > 0) ++out.runs_with_da_wrong;
	}
	out.trajectory_rmse_m = meanSpreadOf(trajectory);
	out.landmark_rmse_m = meanSpreadOf(landmarks);
	out.wall_s = quantilesOf(wall);
	return out;
}

}  // namespace esif
