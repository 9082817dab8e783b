#pragma once
/// \file ComparisonPage.h
/// comparison.html: `esif compare`'s results on one self-contained page -
/// the comparison table (each row explained on hover and in a legend, from
/// ColumnMeanings.h), the notes, the book's Table 5.1 layout, the maps
/// overlay and every run's figures, inlined (Html.h).

#include <esif/formats/StatsJson.h>

#include <string>
#include <vector>

namespace esif
{
struct ComparisonPageInput
{
	std::string title;	///< e.g. "esif compare on small.rawlog"
	std::vector<Stats> runs;  ///< every row, failed ones included, in --configs order
	std::vector<std::string> run_folders;  ///< each run's folder, where its figures are read
	std::string notes;	 ///< the notes under comparison.md's table, one per line
	std::string folder;	 ///< the comparison's folder (maps_overlay.png)
};

/// The whole page.
std::string comparisonPageHtml(const ComparisonPageInput& in);

/// The page written atomically to `path`.
void writeComparisonPage(const std::string& path, const ComparisonPageInput& in);

}  // namespace esif
