#include <esif/core/Errors.h>
#include <esif/compare/RunOrder.h>

#include <algorithm>

namespace esif
{
namespace
{
std::string describeAssociationsFrom(const PlannedRun& run)
{
	return run.config + ": [esif] associations_from = " + run.associations_from;
}

std::optional<std::size_t> sourceOf(const std::vector<PlannedRun>& runs, std::size_t i)
{
	const PlannedRun& run = runs[i];
	if (run.associations_from.empty()) return std::nullopt;
	std::vector<std::size_t> others;
	for (std::size_t j = 0; j < runs.size(); ++j)
		if (j != i && runs[j].label == run.associations_from) others.push_back(j);
	if (others.empty() && run.label == run.associations_from)
		throw ConfigError(
			describeAssociationsFrom(run) +
			": names this config's own label (a run cannot reuse its own data association)");
	if (others.size() > 1)
	{
		std::string list;
		for (const auto j : others) list += (list.empty() ? "" : ", ") + runs[j].config;
		throw ConfigError(
			describeAssociationsFrom(run) + ": several compared configs have this label (" + list +
			"); give each its own [esif] label");
	}
	if (others.empty()) return std::nullopt;
	return others.front();
}

/// Places `i` after its source, depth first; `visiting` holds the chain being
/// placed, so meeting one of it again is a cycle.
void place(
	std::size_t i, const std::vector<PlannedRun>& runs, const std::vector<std::optional<std::size_t>>& sources,
	std::vector<bool>& placed, std::vector<std::size_t>& visiting, std::vector<std::size_t>& order)
{
	if (placed[i]) return;
	if (const auto at = std::find(visiting.begin(), visiting.end(), i); at != visiting.end())
	{
		std::string chain;
		for (auto it = at; it != visiting.end(); ++it) chain += runs[*it].config + " (" + runs[*it].label + ") -> ";
		throw ConfigError(
			"esif compare: [esif] associations_from forms a cycle: " + chain + runs[i].config +
			": no run of it can go first");
	}
	visiting.push_back(i);
	if (sources[i]) place(*sources[i], runs, sources, placed, visiting, order);
	visiting.pop_back();
	placed[i] = true;
	order.push_back(i);
}
}  // namespace

std::vector<std::optional<std::size_t>> associationSources(const std::vector<PlannedRun>& runs)
{
	std::vector<std::optional<std::size_t>> sources;
	for (std::size_t i = 0; i < runs.size(); ++i) sources.push_back(sourceOf(runs, i));
	return sources;
}

std::vector<std::size_t> runOrder(
	const std::vector<PlannedRun>& runs, const std::vector<std::optional<std::size_t>>& sources,
	std::optional<std::size_t> first)
{
	std::vector<bool> placed(runs.size(), false);
	std::vector<std::size_t> visiting, order;
	if (first) place(*first, runs, sources, placed, visiting, order);
	for (std::size_t i = 0; i < runs.size(); ++i) place(i, runs, sources, placed, visiting, order);
	return order;
}

}  // namespace esif
