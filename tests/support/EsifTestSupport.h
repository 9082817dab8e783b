#pragma once
/// \file EsifTestSupport.h
/// Helpers shared by the test suites: temporary folders, running a plugin
/// in-process on a rawlog, running the `esif` binary as a user would, and
/// third-party data made into rawlogs on the fly.

#include <esif/config/ConfigFile.h>
#include <esif/eval/Evaluator.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/RawlogReader.h>
#include <esif/formats/StatsJson.h>
#include <esif/loader/PluginLoader.h>
#include <esif/run/Replay.h>
#include <esif/sim/Scenario.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace esif::test
{
/// A fresh folder under the system temp dir, removed when the object dies.
class TempDir
{
   public:
	TempDir()
	{
		std::random_device rd;
		path_ = std::filesystem::temp_directory_path() / ("esif_test_" + std::to_string(rd()) + std::to_string(rd()));
		std::filesystem::create_directories(path_);
	}
	~TempDir()
	{
		std::error_code ec;
		std::filesystem::remove_all(path_, ec);
	}
	std::string path() const { return path_.string(); }
	std::string file(const std::string& name) const { return (path_ / name).string(); }

   private:
	std::filesystem::path path_;
};

inline std::string sourcePath(const std::string& relative) { return std::string(ESIF_SOURCE_DIR) + "/" + relative; }

/// Creates plugin `class_name` from the build's plugin folder, configured
/// from the INI text of its section.
inline FilterPlugin::Ptr makePlugin(const std::string& class_name, const std::string& section_text)
{
	static PluginLoader loader({ESIF_PLUGIN_DIR});
	loader.loadAll();
	auto plugin = loader.create(class_name);
	const auto cfg = ConfigFile::fromText("[" + plugin->sectionName() + "]\n" + section_text, "test.ini");
	const auto section = cfg.section(plugin->sectionName());
	plugin->configure(section);
	section.rejectUnknownKeys();
	return plugin;
}

/// The counter `name` of `plugin`'s CostFigures (stats.json plugin_<name>);
/// a test failure and NaN when it reports none.
inline double pluginCounter(const FilterPlugin& plugin, const std::string& name)
{
	for (const auto& [key, value] : plugin.costFigures().counters)
		if (key == name) return value;
	ADD_FAILURE() << "no counter " << name;
	return std::nan("");
}

/// Result of running the esif binary.
struct CommandResult
{
	int exit_code = -1;
	std::string out;  ///< stdout and stderr, merged
};

/// Runs `command` through the shell; its stdout and stderr merged.
inline CommandResult runShell(const std::string& command)
{
	CommandResult r;
	FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
	if (!pipe) return r;
	char buf[4096];
	while (std::fgets(buf, sizeof(buf), pipe)) r.out += buf;
	const int status = ::pclose(pipe);
	r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
	return r;
}

/// Runs `esif ARGS` through the shell (ARGS already quoted as needed).
inline CommandResult runEsif(const std::string& args) { return runShell(std::string(ESIF_BINARY) + " " + args); }

/// `word` single-quoted for runEsif's shell (paths of temporary folders hold no quote).
inline std::string quoted(const std::string& word) { return "'" + word + "'"; }

/// The command failed with `exit_code` (1: bad input, config or command
/// line) and printed exactly one line, an "esif: error: " naming `phrase`.
inline void expectOneErrorLine(const CommandResult& r, const std::string& phrase, int exit_code = 1)
{
	EXPECT_EQ(r.exit_code, exit_code) << r.out;
	EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
	EXPECT_NE(r.out.find("esif: error: "), std::string::npos) << r.out;
	EXPECT_NE(r.out.find(phrase), std::string::npos) << "expected '" << phrase << "' in: " << r.out;
}

/// The whole content of a text file ("" when it cannot be read).
inline std::string readText(const std::string& path)
{
	std::ifstream in(path);
	std::stringstream ss;
	ss << in.rdbuf();
	return ss.str();
}

/// A CSV file esif wrote (a header line, then rows; no quoted cells) as one
/// column -> text map per row. A row with another number of cells than the
/// header is a test failure; a trailing comma is an empty last cell.
inline std::vector<std::map<std::string, std::string>> readCsvRows(const std::string& path)
{
	std::ifstream in(path);
	const auto split = [](const std::string& line) {
		std::vector<std::string> cells;
		std::stringstream ss(line);
		std::string c;
		while (std::getline(ss, c, ',')) cells.push_back(c);
		if (!line.empty() && line.back() == ',') cells.emplace_back();
		return cells;
	};
	std::string line;
	std::getline(in, line);
	const auto header = split(line);
	std::vector<std::map<std::string, std::string>> rows;
	while (std::getline(in, line))
	{
		const auto cells = split(line);
		EXPECT_EQ(cells.size(), header.size()) << path << ": " << line;
		std::map<std::string, std::string> row;
		for (std::size_t k = 0; k < header.size() && k < cells.size(); ++k) row[header[k]] = cells[k];
		rows.push_back(std::move(row));
	}
	return rows;
}

/// A figure of a run's stats.json; a test failure (and NaN) when it is absent.
inline double statNumber(const Stats& stats, const std::string& key)
{
	const auto v = stats.number(key);
	if (!v) ADD_FAILURE() << "no number " << key;
	return v.value_or(std::nan(""));
}

/// A replay scored against the ground truth with prefix `truth_prefix`
/// (groundTruthPrefixFor(rawlog) for one written beside its rawlog), in
/// the frame of the initial pose, as `esif run` scores it. A test failure
/// (and an empty Accuracy) when there is no ground truth there.
inline Accuracy scoreAgainstTruth(const ReplayResult& result, const std::string& truth_prefix)
{
	const auto truth = loadGroundTruth(truth_prefix);
	if (!truth)
	{
		ADD_FAILURE() << "no ground truth at " << truth_prefix;
		return {};
	}
	return evaluate(truth->inInitialPoseFrame(), result.record.trajectory, result.record.final_estimate,
					result.audit.filterToTrue());
}

/// A plugin's counters (costFigures()) by name.
inline std::map<std::string, double> countersOf(const FilterPlugin& plugin)
{
	std::map<std::string, double> out;
	for (const auto& [name, value] : plugin.costFigures().counters) out[name] = value;
	return out;
}

/// The scenario of a committed INI file, `relative_path` from the source
/// root (e.g. "configs/sim/long_gap.ini").
inline Scenario loadScenario(const std::string& relative_path)
{
	return Scenario::fromConfig(ConfigFile::load(sourcePath(relative_path)));
}

/// Runs `esif simulate` on configs/sim/small.ini (200 steps, 16 features),
/// writing `rawlog` and its ground truth beside it; `extra` adds options
/// (e.g. "--seed 7").
inline CommandResult simulateSmall(const std::string& rawlog, const std::string& extra = "")
{
	return runEsif(
		"simulate --config '" + sourcePath("configs/sim/small.ini") + "' " + extra + (extra.empty() ? "" : " ") +
		"--out '" + rawlog + "'");
}

/// Writes `simulation_section` (the [simulation] keys of a scenario, without
/// the section line) to DIR/NAME.ini and runs `esif simulate` on it into
/// DIR/NAME.rawlog, with its ground truth beside it.
inline CommandResult simulateScenario(const TempDir& dir, const std::string& name,
									  const std::string& simulation_section)
{
	const std::string ini = dir.file(name + ".ini");
	std::ofstream(ini) << "[simulation]\n" << simulation_section;
	return runEsif("simulate --config " + quoted(ini) + " --out " + quoted(dir.file(name + ".rawlog")));
}

/// The Victoria Park dataset (third-party data: read from the shared data
/// folder beside the checkout, never committed, nor anything made from it).
inline std::string victoriaParkDataset() { return sourcePath("../shared/data/victoria_park/victoria_park.txt"); }

/// Makes `dir`/vicpark.rawlog from victoriaParkDataset() with `esif import
/// victoria-park` and the importer's defaults (landmark IDs kept, 0.5 m /
/// 2 deg noise), as README.md tells users to, and returns its path; nullopt
/// when the dataset is absent, for the caller to
/// `GTEST_SKIP() << test::victoriaParkDataset() << " not present"`.
/// One rawlog per TempDir, because ctest runs the tests of one binary in
/// parallel processes. A failed import is a test failure, not a skip.
inline std::optional<std::string> importVictoriaPark(const TempDir& dir)
{
	const std::string dataset = victoriaParkDataset();
	if (!std::filesystem::exists(dataset)) return std::nullopt;
	const std::string rawlog = dir.file("vicpark.rawlog");
	const auto r = runEsif("import victoria-park --in '" + dataset + "' --out '" + rawlog + "'");
	EXPECT_EQ(r.exit_code, 0) << r.out;
	return rawlog;
}

/// Dataset 6 of UTIAS MRCLAM (third-party data, read from the shared data
/// folder beside the checkout, never committed).
inline std::string mrclamDataset() { return sourcePath("../shared/data/mrclam/MRCLAM_Dataset6"); }

/// Makes `dir`/rN.rawlog (and its ground truth) from robot `robot` of
/// mrclamDataset() with `esif import mrclam` and its defaults; nullopt when
/// the dataset is absent, for the caller to
/// `GTEST_SKIP() << test::mrclamDataset() << " not present"`.
inline std::optional<std::string> importMrclam(const TempDir& dir, int robot, const std::string& extra = "")
{
	const std::string dataset = mrclamDataset();
	if (!std::filesystem::exists(dataset)) return std::nullopt;
	const std::string rawlog = dir.file("r" + std::to_string(robot) + ".rawlog");
	const auto r = runEsif("import mrclam --dataset '" + dataset + "' --robot " + std::to_string(robot) + " " + extra +
						   " --out '" + rawlog + "'");
	EXPECT_EQ(r.exit_code, 0) << r.out;
	return rawlog;
}

}  // namespace esif::test
