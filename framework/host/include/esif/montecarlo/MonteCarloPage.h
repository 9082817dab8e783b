#pragma once
/// \file MonteCarloPage.h
/// summary.html: a Monte Carlo campaign (esif montecarlo) on one
/// self-contained page - summary.md's table (each column explained on
/// hover and in a legend, from ColumnMeanings.h), the runs not aggregated
/// and the suspect ones, and the campaign's figures, inlined (Html.h).

#include <esif/eval/MonteCarloStatistics.h>
#include <esif/montecarlo/MonteCarloTables.h>

#include <string>
#include <vector>

namespace esif
{
/// The whole page; the figures are read from the campaign folder `dir`.
std::string monteCarloPageHtml(
	const std::string& title, const std::vector<ConfigStatistics>& configs, const CampaignGaps& gaps,
	const std::string& dir);

/// The page written atomically to DIR/summary.html.
void writeMonteCarloPage(
	const std::string& title, const std::vector<ConfigStatistics>& configs, const CampaignGaps& gaps,
	const std::string& dir);

}  // namespace esif
