/// \file ComparisonPage.cpp
/// comparison.html; see ComparisonPage.h.

#include <esif/compare/BookTable.h>
#include <esif/eval/ColumnMeanings.h>
#include <esif/compare/ComparisonTable.h>
#include <esif/compare/ComparisonPage.h>
#include <esif/report/Html.h>
#include <esif/safeio/AtomicFile.h>

#include <filesystem>

namespace fs = std::filesystem;

namespace esif
{
namespace
{
/// A run's figures besides map.png, shown when present, with their captions.
constexpr std::pair<const char*, const char*> kOptionalFigures[] = {
	{"step_times.png", "time per step against landmarks mapped"},
	{"localmap_times.png", "time per local-map fusion"},
	{"info_matrix.png", "information matrix and Cholesky factor non-zeros"},
};

std::string runColumnTitle(const ComparisonPageInput& in, std::size_t i)
{
	return "run folder " + fs::path(in.run_folders.at(i)).filename().string() + ", plugin " +
		   in.runs[i].text("plugin").value_or("?");
}

std::string comparisonTable(const ComparisonPageInput& in, const ComparisonGrid& g)
{
	html::Table t;
	t.header.push_back({"metric", "", true});
	for (std::size_t i = 0; i < g.labels.size(); ++i) t.header.push_back({g.labels[i], runColumnTitle(in, i), true});
	for (std::size_t k = 0; k < g.keys.size(); ++k)
	{
		const ColumnMeaning* m = meaningOf(comparisonColumnMeanings(), g.keys[k]);
		std::vector<html::Cell> row{{g.keys[k], m ? plainMeaning(*m) : "", true}};
		for (const auto& c : g.cells[k]) row.push_back({c, "", false});
		t.rows.push_back(std::move(row));
	}
	return html::table(t);
}

std::string comparisonLegend(const ComparisonGrid& g)
{
	std::vector<std::pair<std::string, std::string>> entries;
	for (const auto* m : meaningsShown(comparisonColumnMeanings(), g.keys))
		entries.emplace_back(columnList(*m), fullMeaning(*m));
	return html::heading(3, "Rows") + html::legend(entries, true);
}

std::string bookTable(const std::vector<Stats>& runs)
{
	std::vector<Stats> succeeded;  // as in comparison.md: failed runs have nothing to show there
	for (const auto& run : runs)
		if (!isFailedRun(run)) succeeded.push_back(run);
	const auto grid = bookTable51Grid(succeeded);
	html::Table t;
	for (const auto& h : grid[0]) t.header.push_back({h, "", true});
	for (std::size_t r = 1; r < grid.size(); ++r)
	{
		std::vector<html::Cell> row{{grid[r][0], "", true}};
		for (std::size_t c = 1; c < grid[r].size(); ++c) row.push_back({grid[r][c], "", false});
		t.rows.push_back(std::move(row));
	}
	return html::heading(2, bookTable51Title()) + html::table(t);
}

std::string overlay(const std::string& folder)
{
	const fs::path png = fs::path(folder) / "maps_overlay.png";
	std::error_code ec;
	if (!fs::exists(png, ec)) return "";
	return html::heading(2, "Maps over the reference") + html::pngFigure(png.string(), "maps_overlay.png");
}

std::string runSection(const ComparisonPageInput& in, std::size_t i)
{
	const Stats& run = in.runs[i];
	const fs::path dir(in.run_folders.at(i));
	std::string out = "<section>\n" + html::heading(3, run.text("label").value_or("?") + " (" +
												   dir.filename().string() + ")");
	if (isFailedRun(run))
		return out + html::paragraph("no figures: the run " + run.text("status").value_or("failed"), "note") +
			   "</section>\n";
	out += html::pngFigure((dir / "map.png").string(), "map.png: landmarks with 2-sigma ellipses, path, ground truth");
	for (const auto& [file, caption] : kOptionalFigures)
	{
		std::error_code ec;
		if (fs::exists(dir / file, ec)) out += html::pngFigure((dir / file).string(), std::string(file) + ": " + caption);
	}
	return out + "</section>\n";
}

std::string runSections(const ComparisonPageInput& in)
{
	std::string out = html::heading(2, "Runs") + "<div class=\"runs\">\n";
	for (std::size_t i = 0; i < in.runs.size(); ++i) out += runSection(in, i);
	return out + "</div>\n";
}
}  // namespace

std::string comparisonPageHtml(const ComparisonPageInput& in)
{
	const ComparisonGrid g = comparisonGrid(in.runs);
	const std::string body = html::heading(2, "Comparison") + comparisonTable(in, g) + comparisonLegend(g) +
							 html::paragraphs(in.notes) + bookTable(in.runs) + overlay(in.folder) +
							 runSections(in);
	return html::page(in.title, body);
}

void writeComparisonPage(const std::string& path, const ComparisonPageInput& in)
{
	writeTextAtomically(path, comparisonPageHtml(in));
}

}  // namespace esif
