/// \file MonteCarloPage.cpp
/// summary.html; see MonteCarloPage.h.

#include <esif/eval/ColumnMeanings.h>
#include <esif/report/Html.h>
#include <esif/montecarlo/MonteCarloPage.h>
#include <esif/safeio/AtomicFile.h>

#include <filesystem>

namespace fs = std::filesystem;

namespace esif
{
namespace
{
/// The campaign's figures (MonteCarloFigures.h) with their captions.
constexpr std::pair<const char*, const char*> kFigures[] = {
	{"anees_pose.png", "pose ANEES per step with its 95% bounds"},
	{"rmse.png", "position and heading RMSE per step"},
	{"landmark_anees.png", "final ANEES of each landmark with its 95% bounds"},
};

std::string summaryTable(const std::vector<ConfigStatistics>& configs)
{
	html::Table t;
	for (const auto& m : monteCarloSummaryColumns())
		for (const auto& column : m.columns) t.header.push_back({column, plainMeaning(m), true});
	for (const auto& cells : monteCarloSummaryCells(configs))
	{
		std::vector<html::Cell> row;
		for (std::size_t i = 0; i < cells.size(); ++i) row.push_back({cells[i], "", i == 0});
		t.rows.push_back(std::move(row));
	}
	return html::table(t);
}

std::string summaryLegend()
{
	std::vector<std::pair<std::string, std::string>> entries;
	for (const auto& m : monteCarloSummaryColumns()) entries.emplace_back(columnList(m), fullMeaning(m));
	return html::heading(3, "Columns") + html::legend(entries, false) + html::paragraph(monteCarloCampaignNote());
}

std::string gapLists(const CampaignGaps& gaps)
{
	std::string out;
	if (!gaps.failed.empty() || !gaps.pending.empty())
	{
		std::vector<std::string> lines = gaps.failed;
		lines.insert(lines.end(), gaps.pending.begin(), gaps.pending.end());
		out += html::heading(2, "Runs not aggregated") + html::list(lines);
	}
	if (!gaps.suspect.empty()) out += html::heading(2, "Suspect runs (aggregated)") + html::list(gaps.suspect);
	return out;
}

std::string figures(const std::string& dir)
{
	std::string out = html::heading(2, "Figures");
	for (const auto& [file, caption] : kFigures)
		out += html::pngFigure((fs::path(dir) / file).string(), std::string(file) + ": " + caption);
	return out;
}
}  // namespace

std::string monteCarloPageHtml(
	const std::string& title, const std::vector<ConfigStatistics>& configs, const CampaignGaps& gaps,
	const std::string& dir)
{
	return html::page(
		title, html::heading(2, "Summary") + summaryTable(configs) + summaryLegend() + gapLists(gaps) + figures(dir));
}

void writeMonteCarloPage(
	const std::string& title, const std::vector<ConfigStatistics>& configs, const CampaignGaps& gaps,
	const std::string& dir)
{
	writeTextAtomically((fs::path(dir) / "summary.html").string(), monteCarloPageHtml(title, configs, gaps, dir));
}

}  // namespace esif
