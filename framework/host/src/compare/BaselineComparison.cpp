#include <esif/compare/BaselineComparison.h>

#include <cmath>
#include <cstdio>

namespace esif
{
namespace
{
constexpr const char* kBaselineFormulation = "full_slam";

/// run's `key` over the baseline's; nullopt when either is missing or the quotient is not finite.
std::optional<double> ratio(const Stats& run, const Stats& baseline, const std::string& key)
{
	const auto value = run.number(key);
	const auto base = baseline.number(key);
	if (!value || !base || *base == 0) return std::nullopt;
	const double r = *value / *base;
	return std::isfinite(r) ? std::optional<double>(r) : std::nullopt;
}
}  // namespace

std::string labelOf(const Stats& run) { return run.text("label").value_or("?"); }

std::string runFormulation(const Stats& run) { return run.text("formulation").value_or("other"); }

BaselineChoice findBaseline(const std::vector<Stats>& runs)
{
	BaselineChoice choice;
	std::vector<std::string> labels;
	for (std::size_t i = 0; i < runs.size(); ++i)
		if (runFormulation(runs[i]) == kBaselineFormulation)
		{
			if (!choice.index) choice.index = i;
			labels.push_back(labelOf(runs[i]));
		}
	if (labels.size() > 1)
	{
		std::string list;
		for (const auto& l : labels) list += (list.empty() ? "" : ", ") + l;
		choice.warning = "several full-SLAM runs (" + list + "): the optimization baseline is the first, '" +
						 labels.front() + "'";
	}
	return choice;
}

bool hasGroundTruthFigures(const std::vector<Stats>& runs)
{
	for (const auto& run : runs)
		if (run.number("landmark_rmse_m")) return true;
	return false;
}

const std::vector<std::string>& baselineRatioKeys()
{
	static const std::vector<std::string> keys = {"base_landmark_rmse_ratio", "base_ate_ratio"};
	return keys;
}

void setBaselineRatios(std::vector<Stats>& runs, std::size_t baseline)
{
	const Stats base = runs.at(baseline);  // a copy: its own row changes below
	for (auto& run : runs)
	{
		run.set("base_landmark_rmse_ratio", ratio(run, base, "landmark_rmse_m"));
		run.set("base_ate_ratio", ratio(run, base, "ate_rmse_m"));
	}
}

std::string baselineNote(const std::string& label)
{
	return "base_*: ratio to the optimization baseline '" + label + "' (1 = as accurate as the optimum)\n";
}

std::optional<std::string> baselineImplausibility(const Stats& baseline)
{
	const auto plausible = baseline.number("plugin_optimum_plausible");
	if (!plausible || *plausible != 0) return std::nullopt;
	std::string why;
	if (const auto chi2 = baseline.number("plugin_chi2_per_dof"))
	{
		char buf[48];
		std::snprintf(buf, sizeof(buf), "chi2/dof %.3g", *chi2);
		why = buf;
	}
	if (const auto degenerate = baseline.number("plugin_degenerate_poses"))
		why += (why.empty() ? "" : ", ") + std::to_string(static_cast<long long>(*degenerate)) + " degenerate poses";
	return "baseline '" + labelOf(baseline) + "' implausible" + (why.empty() ? std::string() : ": " + why) +
		   "; ratios and differences against it are not trustworthy";
}

}  // namespace esif
