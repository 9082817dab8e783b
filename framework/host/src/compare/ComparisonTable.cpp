#include <esif/compare/BaselineComparison.h>
#include <esif/compare/ComparisonTable.h>
#include <esif/eval/ReferenceResultDifference.h>
#include <esif/eval/RunDifference.h>
#include <esif/eval/SuspectResult.h>
#include <esif/formats/Markdown.h>

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace esif
{
const std::vector<std::string>& comparisonKeys()
{
	static const std::vector<std::string> keys = {
		"plugin", "steps", "landmarks", "state_dim", "info_nnz", "wall_s", "step_us_mean", "step_us_p50",
		"step_us_p99", "step_us_max", "peak_rss_mb", "da_new", "da_matched", "da_rejected", "da_wrong",
		"landmarks_true", "landmarks_found", "landmarks_duplicated", "landmarks_spurious", "da_precision",
		"da_recall", "landmark_rmse_m", "ate_rmse_m", "landmark_ospa_m", "ospa_c_m", "landmark_nees_mean",
		"pose_nees_mean", "landmark_consistent_fraction", "pose_consistent_fraction"};
	return keys;
}

namespace
{
/// Numbers with 4 significant digits for tables (the CSV keeps full precision).
std::string cell(const Stats& s, const std::string& key)
{
	const auto v = s.get(key);
	if (!v || std::holds_alternative<std::nullptr_t>(*v)) return "-";
	if (const auto* d = std::get_if<double>(&*v))
	{
		char buf[32];
		std::snprintf(buf, sizeof(buf), "%.4g", *d);
		return buf;
	}
	return statText(*v);
}

std::string label(const Stats& s) { return s.get("label") ? statText(*s.get("label")) : "?"; }

/// What map-joining runs add: maps fused and the time per fusion.
const std::vector<std::string>& localMapJoinKeys()
{
	static const std::vector<std::string> keys = {"local_maps", "join_us_mean", "join_us_max"};
	return keys;
}

/// The whole-state test (stats.json state_nees*), for information-form runs.
const std::vector<std::string>& stateNeesKeys()
{
	static const std::vector<std::string> keys = {"state_nees", "state_nees_dof", "state_nees_consistent"};
	return keys;
}

/// What a failed row adds: shown after "plugin" when any row has it.
const std::vector<std::string>& failureKeys()
{
	static const std::vector<std::string> keys = {"status", "exit_code"};
	return keys;
}

constexpr const char* kFailed = "failed";
constexpr const char* kNotRun = "not run";
constexpr const char* kSuspect = "suspect";

/// comparisonKeys(), then the whole-state test when a run has it, the
/// map-joining figures, the ratios to the
/// optimization baseline, the difference-from-reference keys and the
/// difference from a reference result (--reference-result) when a run has them.
std::vector<std::string> tableKeys(const std::vector<Stats>& runs)
{
	std::vector<std::string> keys = comparisonKeys();
	if (std::any_of(runs.begin(), runs.end(), [](const Stats& s) { return s.get("status").has_value(); }))
		keys.insert(keys.begin() + 1, failureKeys().begin(), failureKeys().end());
	const auto anyHas = [&](const std::string& k) {
		return std::any_of(runs.begin(), runs.end(), [&](const Stats& s) { return s.number(k).has_value(); });
	};
	if (anyHas("state_nees")) keys.insert(keys.end(), stateNeesKeys().begin(), stateNeesKeys().end());
	for (const auto* optional_keys :
		 {&localMapJoinKeys(), &baselineRatioKeys(), &runDifferenceKeys(), &referenceResultKeys()})
		for (const auto& k : *optional_keys)
			if (std::any_of(runs.begin(), runs.end(), [&](const Stats& s) { return s.get(k).has_value(); }))
				keys.push_back(k);
	return keys;
}

std::string csvEscape(const std::string& t)
{
	if (t.find_first_of(",\"\n") == std::string::npos) return t;
	std::string out = "\"";
	for (char c : t) out += c == '"' ? std::string("\"\"") : std::string(1, c);
	return out + "\"";
}
}  // namespace

Stats failedRunStats(const std::string& label, const std::string& plugin, int exit_code, const std::string& error)
{
	Stats s;
	s.set("label", StatValue(label));
	s.set("plugin", StatValue(plugin));
	s.set("status", StatValue(std::string(kFailed)));
	s.set("exit_code", StatValue(static_cast<long long>(exit_code)));
	s.set("error", StatValue(error));
	return s;
}

Stats notRunStats(const std::string& label, const std::string& plugin, const std::string& reason)
{
	Stats s;
	s.set("label", StatValue(label));
	s.set("plugin", StatValue(plugin));
	s.set("status", StatValue(std::string(kNotRun)));
	s.set("exit_code", StatValue(nullptr));
	s.set("error", StatValue(reason));
	return s;
}

bool isFailedRun(const Stats& run)
{
	const auto status = run.text("status");
	return status && (*status == kFailed || *status == kNotRun);
}

void markSucceededRuns(std::vector<Stats>& runs)
{
	const auto suspect = [](const Stats& run) { return !isFailedRun(run) && recordedSuspectReason(run).has_value(); };
	if (std::none_of(runs.begin(), runs.end(), isFailedRun) && std::none_of(runs.begin(), runs.end(), suspect)) return;
	for (auto& run : runs)
		if (!isFailedRun(run)) run.set("status", StatValue(std::string(suspect(run) ? kSuspect : "ok")));
}

std::string failureNote(const std::vector<Stats>& runs)
{
	std::string note;
	for (const auto& run : runs)
	{
		if (const auto reason = recordedSuspectReason(run); reason && !isFailedRun(run))
			note += "run '" + label(run) + "' is suspect: " + *reason + "\n";
		if (!isFailedRun(run)) continue;
		const std::string error = run.text("error").value_or("");
		if (run.text("status") == std::string(kNotRun))
			note += "run '" + label(run) + "' not run: " + error + "\n";
		else
			note += "run '" + label(run) + "' failed (exit " + cell(run, "exit_code") + "): " + error + "\n";
	}
	return note;
}

int comparisonExitCode(const std::vector<Stats>& runs)
{
	for (const auto& run : runs)
		if (run.text("status") == std::string(kFailed))
			if (const auto code = run.number("exit_code"); code && *code != 0) return static_cast<int>(*code);
	return 0;
}

ComparisonGrid comparisonGrid(const std::vector<Stats>& runs)
{
	ComparisonGrid g;
	for (const auto& r : runs) g.labels.push_back(label(r));
	g.keys = tableKeys(runs);
	for (const auto& k : g.keys)
	{
		std::vector<std::string> row;
		for (const auto& r : runs) row.push_back(cell(r, k));
		g.cells.push_back(std::move(row));
	}
	return g;
}

std::string comparisonText(const std::vector<Stats>& runs)
{
	const ComparisonGrid g = comparisonGrid(runs);
	std::size_t key_w = std::string("run").size();
	for (const auto& k : g.keys) key_w = std::max(key_w, k.size());
	std::vector<std::size_t> col_w;
	for (std::size_t i = 0; i < runs.size(); ++i)
	{
		std::size_t w = g.labels[i].size();
		for (const auto& row : g.cells) w = std::max(w, row[i].size());
		col_w.push_back(w);
	}
	std::ostringstream out;
	const auto line = [&](const std::string& head, const std::vector<std::string>& values) {
		out << head << std::string(key_w - head.size() + 2, ' ');
		for (std::size_t i = 0; i < values.size(); ++i)
			out << std::string(col_w[i] - values[i].size(), ' ') << values[i] << "  ";
		out << "\n";
	};
	line("run", g.labels);
	for (std::size_t k = 0; k < g.keys.size(); ++k) line(g.keys[k], g.cells[k]);
	return out.str();
}

std::string comparisonMarkdown(const std::vector<Stats>& runs)
{
	const ComparisonGrid g = comparisonGrid(runs);
	std::ostringstream out;
	out << "| metric |";
	for (const auto& l : g.labels) out << " " << markdown::text(l) << " |";
	out << "\n|---|";
	for (std::size_t i = 0; i < runs.size(); ++i) out << "---:|";
	out << "\n";
	for (std::size_t k = 0; k < g.keys.size(); ++k)
	{
		out << "| " << g.keys[k] << " |";
		for (const auto& c : g.cells[k]) out << " " << markdown::text(c) << " |";
		out << "\n";
	}
	return out.str();
}

std::string comparisonCsv(const std::vector<Stats>& runs)
{
	std::vector<std::string> keys;
	for (const auto& r : runs)
		for (const auto& kv : r.items())
			if (std::find(keys.begin(), keys.end(), kv.first) == keys.end()) keys.push_back(kv.first);
	std::ostringstream out;
	for (std::size_t i = 0; i < keys.size(); ++i) out << (i ? "," : "") << csvEscape(keys[i]);
	out << "\n";
	for (const auto& r : runs)
	{
		for (std::size_t i = 0; i < keys.size(); ++i)
		{
			const auto v = r.get(keys[i]);
			const bool empty = !v || std::holds_alternative<std::nullptr_t>(*v);
			out << (i ? "," : "") << (empty ? "" : csvEscape(statText(*v)));
		}
		out << "\n";
	}
	return out.str();
}

}  // namespace esif
