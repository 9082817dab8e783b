/// \file MonteCarloTables.cpp
/// summary.csv, summary.md, per_step.csv, landmarks.csv; see MonteCarloTables.h.

#include <esif/eval/ColumnMeanings.h>
#include <esif/montecarlo/MonteCarloTables.h>
#include <esif/formats/Markdown.h>

#include <cmath>
#include <cstdio>

namespace esif
{
namespace
{
std::string full(double v)
{
	char buf[40];
	std::snprintf(buf, sizeof(buf), "%.17g", v);
	return buf;
}

std::string full(const std::optional<double>& v) { return v ? full(*v) : std::string(); }

std::string rounded(double v, int digits = 3)
{
	char buf[40];
	std::snprintf(buf, sizeof(buf), "%.*g", digits, v);
	return buf;
}

std::string rounded(const std::optional<double>& v, int digits = 3) { return v ? rounded(*v, digits) : "-"; }

std::string percent(const std::optional<double>& fraction)
{
	if (!fraction) return "-";
	char buf[16];
	std::snprintf(buf, sizeof(buf), "%.1f %%", 100 * *fraction);
	return buf;
}

std::string band(const AneesBounds& b) { return "[" + rounded(b.lo) + ", " + rounded(b.hi) + "]"; }

const char* const kSummaryColumns =
	"config,runs,runs_planned,pose_anees_mean,pose_bound_lo,pose_bound_hi,pose_steps_inside_fraction,"
	"landmark_anees,landmark_bound_lo,landmark_bound_hi,landmarks_inside_fraction,landmarks_scored,"
	"trajectory_rmse_mean_m,trajectory_rmse_std_m,landmark_rmse_mean_m,landmark_rmse_std_m,"
	"final_position_rmse_m,wall_s_median,wall_s_p25,wall_s_p75,wall_s_min,wall_s_max,da_wrong_total,"
	"runs_with_da_wrong,pose_position_anees_mean,pose_heading_anees_mean,state_runs,state_anees_per_dof,"
	"state_bound_lo,state_bound_hi,state_runs_inside_fraction,landmarks_true_median,landmarks_found_median,"
	"landmarks_duplicated_total,runs_with_duplicated,landmarks_spurious_total,runs_with_spurious,"
	"da_precision_median,da_precision_min,da_recall_median,da_recall_min,landmark_ospa_mean_m,landmark_ospa_std_m";

std::optional<double> medianOf(const std::optional<Quantiles>& q) { return q ? std::optional<double>(q->median) : std::nullopt; }
std::optional<double> lowestOf(const std::optional<Quantiles>& q) { return q ? std::optional<double>(q->min) : std::nullopt; }
std::optional<double> meanOf(const std::optional<MeanSpread>& m) { return m ? std::optional<double>(m->mean) : std::nullopt; }
std::optional<double> spreadOf(const std::optional<MeanSpread>& m)
{
	return m ? std::optional<double>(m->stddev) : std::nullopt;
}

/// "median [lowest]" of a share, "-" without runs.
std::string medianAndLowest(const std::optional<Quantiles>& q)
{
	return q ? rounded(q->median) + " [" + rounded(q->min) + "]" : std::string("-");
}

/// The RMSE over runs of the position at the last step all runs have.
double finalPositionRmse(const ConfigStatistics& c)
{
	return c.steps.empty() ? std::nan("") : c.steps.back().position_rmse_m;
}
}  // namespace

std::string monteCarloSummaryCsv(const std::vector<ConfigStatistics>& configs, std::size_t planned)
{
	std::string out = std::string(kSummaryColumns) + "\n";
	for (const auto& c : configs)
	{
		const std::vector<std::string> cells = {
			c.name, std::to_string(c.runs), std::to_string(planned), full(c.pose_anees_mean), full(c.pose_bounds.lo),
			full(c.pose_bounds.hi), full(c.pose_steps_inside_fraction), full(c.landmark_anees),
			full(c.landmark_bounds.lo), full(c.landmark_bounds.hi), full(c.landmarks_inside_fraction),
			std::to_string(c.landmarks.size()), full(c.trajectory_rmse_m.mean), full(c.trajectory_rmse_m.stddev),
			full(c.landmark_rmse_m.mean), full(c.landmark_rmse_m.stddev), full(finalPositionRmse(c)),
			full(c.wall_s.median), full(c.wall_s.p25), full(c.wall_s.p75), full(c.wall_s.min), full(c.wall_s.max),
			std::to_string(c.da_wrong_total), std::to_string(c.runs_with_da_wrong), full(c.pose_position_anees_mean),
			full(c.pose_heading_anees_mean), std::to_string(c.state_runs), full(c.state_anees_per_dof),
			full(c.state_bounds.lo), full(c.state_bounds.hi), full(c.state_runs_inside_fraction),
			full(c.landmarks_true_median), full(c.landmarks_found_median), std::to_string(c.landmarks_duplicated_total),
			std::to_string(c.runs_with_duplicated), std::to_string(c.landmarks_spurious_total),
			std::to_string(c.runs_with_spurious), full(medianOf(c.da_precision)), full(lowestOf(c.da_precision)),
			full(medianOf(c.da_recall)), full(lowestOf(c.da_recall)), full(meanOf(c.landmark_ospa_m)),
			full(spreadOf(c.landmark_ospa_m))};
		for (std::size_t i = 0; i < cells.size(); ++i) out += (i ? "," : "") + cells[i];
		out += "\n";
	}
	return out;
}

const std::string& monteCarloCampaignNote()
{
	static const std::string note = "Runs are independent noise draws of the same scenario (same world and path).";
	return note;
}

std::vector<std::vector<std::string>> monteCarloSummaryCells(const std::vector<ConfigStatistics>& configs)
{
	std::vector<std::vector<std::string>> rows;
	for (const auto& c : configs)
		rows.push_back(
			{c.name, std::to_string(c.runs), rounded(c.pose_anees_mean), band(c.pose_bounds),
			 percent(c.pose_steps_inside_fraction),
			 rounded(c.pose_position_anees_mean) + " / " + rounded(c.pose_heading_anees_mean),
			 rounded(c.landmark_anees), band(c.landmark_bounds), percent(c.landmarks_inside_fraction),
			 rounded(c.state_anees_per_dof), c.state_runs ? band(c.state_bounds) : std::string("-"),
			 percent(c.state_runs_inside_fraction),
			 rounded(c.trajectory_rmse_m.mean) + " ± " + rounded(c.trajectory_rmse_m.stddev, 2),
			 rounded(c.landmark_rmse_m.mean) + " ± " + rounded(c.landmark_rmse_m.stddev, 2),
			 rounded(c.wall_s.median) + " [" + rounded(c.wall_s.p25) + ", " + rounded(c.wall_s.p75) + "]",
			 std::to_string(c.da_wrong_total) + " in " + std::to_string(c.runs_with_da_wrong) + " runs",
			 rounded(c.landmarks_true_median) + " / " + rounded(c.landmarks_found_median),
			 std::to_string(c.landmarks_duplicated_total) + " in " + std::to_string(c.runs_with_duplicated) + " runs / " +
				 std::to_string(c.landmarks_spurious_total) + " in " + std::to_string(c.runs_with_spurious) + " runs",
			 medianAndLowest(c.da_precision) + " / " + medianAndLowest(c.da_recall),
			 c.landmark_ospa_m ? rounded(c.landmark_ospa_m->mean) + " ± " + rounded(c.landmark_ospa_m->stddev, 2)
							   : std::string("-")});
	return rows;
}

std::string monteCarloSummaryMarkdown(
	const std::string& title, const std::vector<ConfigStatistics>& configs, const CampaignGaps& gaps)
{
	std::string out = "# " + title + "\n\n|";
	const auto headings = columnHeadings(monteCarloSummaryColumns());
	for (const auto& h : headings) out += " " + h + " |";
	out += "\n|";
	for (std::size_t i = 0; i < headings.size(); ++i) out += "---|";
	out += "\n";
	for (const auto& row : monteCarloSummaryCells(configs))
	{
		out += "|";
		for (const auto& cell : row) out += " " + cell + " |";
		out += "\n";
	}
	out += "\n";
	for (const auto& m : monteCarloSummaryColumns()) out += "- " + columnList(m) + ": " + m.meaning + "\n";
	out += "\n" + monteCarloCampaignNote() + "\n";
	if (!gaps.failed.empty() || !gaps.pending.empty())
	{
		out += "\n## Runs not aggregated\n\n";
		for (const auto& line : gaps.failed) out += "- " + markdown::text(line) + "\n";
		for (const auto& line : gaps.pending) out += "- " + markdown::text(line) + "\n";
	}
	if (!gaps.suspect.empty())
	{
		out += "\n## Suspect runs (aggregated)\n\n";
		for (const auto& line : gaps.suspect) out += "- " + markdown::text(line) + "\n";
	}
	return out;
}

std::string monteCarloPerStepCsv(const std::vector<ConfigStatistics>& configs)
{
	std::string out =
		"config,step,runs,anees,bound_lo,bound_hi,position_rmse_m,heading_rmse_rad,position_error_p10_m,"
		"position_error_p90_m,anees_position,bound_position_lo,bound_position_hi,anees_heading,bound_heading_lo,"
		"bound_heading_hi\n";
	const auto withBounds = [](const std::optional<double>& anees, const AneesBounds& b) {
		return full(anees) + "," + (anees ? full(b.lo) + "," + full(b.hi) : std::string(","));
	};
	for (const auto& c : configs)
		for (const auto& s : c.steps)
			out += c.name + "," + std::to_string(s.step) + "," + std::to_string(s.runs) + "," +
				   withBounds(s.anees, s.bounds) + "," + full(s.position_rmse_m) + "," + full(s.heading_rmse_rad) +
				   "," + full(s.position_error_p10_m) + "," + full(s.position_error_p90_m) + "," +
				   withBounds(s.anees_position, s.bounds_position) + "," +
				   withBounds(s.anees_heading, s.bounds_heading) + "\n";
	return out;
}

std::string monteCarloLandmarksCsv(const std::vector<ConfigStatistics>& configs)
{
	std::string out = "config,true_id,runs,anees,bound_lo,bound_hi,rmse_m\n";
	for (const auto& c : configs)
		for (const auto& l : c.landmarks)
			out += c.name + "," + std::to_string(l.true_id) + "," + std::to_string(l.runs) + "," +
				   (l.runs ? full(l.anees) + "," + full(l.bounds.lo) + "," + full(l.bounds.hi) : std::string(",,")) +
				   "," + full(l.rmse_m) + "\n";
	return out;
}

}  // namespace esif
