/// \file MonteCarloCampaign.cpp
/// The campaign folder: plan, layout, job states, failure records; see
/// MonteCarloCampaign.h.

#include <esif/config/ConfigFile.h>
#include <esif/config/ConfigSection.h>
#include <esif/core/Errors.h>
#include <esif/core/NumberToken.h>
#include <esif/core/Text.h>
#include <esif/core/TextInput.h>
#include <esif/montecarlo/MonteCarloCampaign.h>
#include <esif/safeio/AtomicFile.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>
#include <string_view>

namespace fs = std::filesystem;

namespace esif
{
namespace
{
std::vector<std::string> splitList(const std::string& text)
{
	std::vector<std::string> out;
	std::stringstream ss(text);
	for (std::string item; std::getline(ss, item, ',');)
		if (!item.empty()) out.push_back(item);
	return out;
}

std::string joinList(const std::vector<std::string>& items)
{
	std::string out;
	for (const auto& item : items) out += (out.empty() ? "" : ",") + item;
	return out;
}

std::string absolute(const std::string& path) { return fs::absolute(path).lexically_normal().string(); }

/// A path campaign.ini can hold: one line, no control character (a line
/// break would end the value and start a line of its own), no comma (the
/// list separator).
std::string manifestPath(const std::string& path, const std::string& what)
{
	const std::string p = absolute(path);
	if (holdsControlCharacter(p) || p.find(',') != std::string::npos)
		throw ConfigError(
			"esif montecarlo: " + what + " '" + printableToken(p) +
			"': a campaign cannot record a path with a line break, another control character or a comma "
			"(campaign.ini holds one per line, separated by commas); rename it");
	return p;
}

bool isNameCharacter(unsigned char c) { return std::isalnum(c) || c == '_' || c == '-' || c == '+' || c == '.'; }

/// A folder name for `config` not among `used`: its file name with every
/// character isCampaignName refuses replaced by '_', then _2, _3...
std::string uniqueName(const std::string& config, const std::set<std::string>& used)
{
	std::string stem = fs::path(config).stem().string().substr(0, 90);
	for (char& c : stem)
		if (!isNameCharacter(static_cast<unsigned char>(c))) c = '_';
	if (stem.empty() || stem[0] == '.') stem = "_" + stem;
	std::string name = stem;
	for (int k = 2; used.count(name); ++k) name = stem + "_" + std::to_string(k);
	return name;
}
}  // namespace

bool isCampaignName(const std::string& name)
{
	return !name.empty() && name.size() <= 100 && name[0] != '.' &&
		   std::all_of(name.begin(), name.end(), [](char c) { return isNameCharacter(static_cast<unsigned char>(c)); });
}

CampaignPlan CampaignPlan::create(
	const std::string& scenario, const std::vector<std::string>& configs, int seed0, int runs)
{
	CampaignPlan plan;
	plan.scenario = manifestPath(scenario, "the scenario");
	plan.seed0 = seed0;
	plan.runs = runs;
	std::set<std::string> used;
	for (const auto& c : configs)
	{
		plan.configs.push_back(manifestPath(c, "the config"));
		plan.names.push_back(uniqueName(c, used));
		used.insert(plan.names.back());
	}
	return plan;
}

CampaignPlan CampaignPlan::load(const std::string& dir)
{
	const std::string path = campaign_layout::manifest(dir);
	if (!fs::is_regular_file(path)) throw InputError(path + ": missing: not a campaign folder of esif montecarlo");
	const ConfigFile file = ConfigFile::load(path);
	const ConfigSection s = file.section("montecarlo");
	CampaignPlan plan;
	plan.scenario = s.getString("scenario");
	// Checked as long integers before they become ints: 4294967297 must not wrap to 1.
	const long seed0 = s.getInt("seed0", -1), runs = s.getInt("runs", -1);
	plan.configs = splitList(s.getString("configs"));
	plan.names = splitList(s.getString("names"));
	s.rejectUnknownKeys();
	if (runs < 1 || runs > kMaxCampaignRuns)
		throw InputError(path + ": [montecarlo] runs: missing or outside [1, " + std::to_string(kMaxCampaignRuns) + "]");
	if (seed0 < 0 || seed0 > INT_MAX - runs)
		throw InputError(path + ": [montecarlo] seed0: missing, negative or leaving no room for the runs' seeds");
	plan.seed0 = static_cast<int>(seed0);
	plan.runs = static_cast<int>(runs);
	if (plan.configs.empty() || plan.configs.size() != plan.names.size())
		throw InputError(path + ": [montecarlo] configs and names: one name per config expected");
	std::set<std::string> seen;
	for (const auto& name : plan.names)
	{
		if (!isCampaignName(name))
			throw InputError(
				path + ": [montecarlo] names: '" + printableToken(name) +
				"' is not a folder name (letters, digits, _ - + . only, not starting with '.')");
		if (!seen.insert(name).second)
			throw InputError(path + ": [montecarlo] names: '" + name + "' is given twice");
	}
	return plan;
}

CampaignPlan CampaignPlan::mergedWith(const CampaignPlan& requested, const std::string& dir) const
{
	const std::string path = campaign_layout::manifest(dir);
	if (requested.scenario != scenario)
		throw ConfigError(
			path + ": this folder is a campaign of the scenario " + scenario + ", not " + requested.scenario +
			": choose another --out");
	if (requested.seed0 != seed0)
		throw ConfigError(
			path + ": this campaign starts at noise seed " + std::to_string(seed0) + ", not --seed0 " +
			std::to_string(requested.seed0) + ": choose another --out");
	CampaignPlan merged = *this;
	merged.runs = std::max(runs, requested.runs);
	std::set<std::string> used(names.begin(), names.end());
	for (const auto& c : requested.configs)
	{
		if (std::find(configs.begin(), configs.end(), c) != configs.end()) continue;
		merged.configs.push_back(c);
		merged.names.push_back(uniqueName(c, used));
		used.insert(merged.names.back());
	}
	return merged;
}

std::string CampaignPlan::iniText() const
{
	return "; esif montecarlo campaign: every config run on the scenario simulated with noise seeds seed0 .. "
		   "seed0 + runs - 1 (same world and path, new noise). Written by esif montecarlo; a re-run may add "
		   "configs and runs.\n[montecarlo]\nscenario = " +
		   scenario + "\nseed0 = " + std::to_string(seed0) + "\nruns = " + std::to_string(runs) +
		   "\nconfigs = " + joinList(configs) + "\nnames = " + joinList(names) + "\n";
}

std::optional<std::size_t> CampaignPlan::configIndex(const std::string& name) const
{
	for (std::size_t i = 0; i < names.size(); ++i)
		if (names[i] == name) return i;
	return std::nullopt;
}

std::vector<CampaignJob> campaignJobs(const CampaignPlan& plan)
{
	std::vector<CampaignJob> jobs;
	for (int r = 0; r < plan.runs; ++r)
		for (std::size_t c = 0; c < plan.configs.size(); ++c) jobs.push_back({c, plan.seed0 + r});
	return jobs;
}

namespace campaign_layout
{
std::string manifest(const std::string& dir) { return (fs::path(dir) / "campaign.ini").string(); }

std::string seedName(int noise_seed)
{
	char buf[32];
	std::snprintf(buf, sizeof(buf), "seed_%04d", noise_seed);
	return buf;
}

std::string simFolder(const std::string& dir, int noise_seed)
{
	return (fs::path(dir) / "sim" / seedName(noise_seed)).string();
}

std::string simRawlog(const std::string& dir, int noise_seed)
{
	return (fs::path(simFolder(dir, noise_seed)) / "sim.rawlog").string();
}

std::string runFolder(const std::string& dir, const std::string& name, int noise_seed)
{
	return (fs::path(dir) / "runs" / name / seedName(noise_seed)).string();
}

std::string failureFile(const std::string& dir, const std::string& name, int noise_seed)
{
	return (fs::path(dir) / "failures" / name / (seedName(noise_seed) + ".txt")).string();
}

std::string jobId(const CampaignPlan& plan, const CampaignJob& job)
{
	return plan.names.at(job.config) + "/" + seedName(job.noise_seed);
}

CampaignJob parseJobId(const CampaignPlan& plan, const std::string& id)
{
	const auto slash = id.rfind('/');
	const auto bad = [&](const std::string& why) {
		return ConfigError("esif montecarlo: --job '" + id + "': " + why);
	};
	if (slash == std::string::npos) throw bad("expected <config name>/seed_<S>");
	const auto config = plan.configIndex(id.substr(0, slash));
	if (!config) throw bad("no config of this campaign is named '" + id.substr(0, slash) + "'");
	const std::string seed = id.substr(slash + 1);
	int s = 0;
	char rest = 0;
	if (std::sscanf(seed.c_str(), "seed_%d%c", &s, &rest) != 1 || seedName(s) != seed)
		throw bad("expected seed_<S> after the '/'");
	if (s < plan.seed0 || s >= plan.seed0 + plan.runs)
		throw bad(
			"noise seed " + std::to_string(s) + " is outside this campaign's " + std::to_string(plan.seed0) + " .. " +
			std::to_string(plan.seed0 + plan.runs - 1));
	return {*config, s};
}
}  // namespace campaign_layout

void requireNoLinksInCampaign(const std::string& dir)
{
	std::error_code ec;
	for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
		if (std::error_code type_ec; it->is_symlink(type_ec))
			throw InputError(
				it->path().string() + ": a symbolic link inside the campaign folder: esif writes only inside --out "
									  "and never through a link there; replace it by what it points to");
	// A folder that does not exist (yet) holds no link; any other failure to list it is an error.
	if (ec && ec != std::errc::no_such_file_or_directory)
		throw InputError(dir + ": cannot list the campaign folder: " + ec.message());
}

JobState jobState(const std::string& dir, const CampaignPlan& plan, const CampaignJob& job)
{
	const std::string name = plan.names.at(job.config);
	std::error_code ec;
	if (fs::is_regular_file(fs::path(campaign_layout::runFolder(dir, name, job.noise_seed)) / "stats.json", ec))
		return JobState::Finished;
	if (fs::is_regular_file(campaign_layout::failureFile(dir, name, job.noise_seed), ec)) return JobState::Failed;
	return JobState::Pending;
}

void writeFailureRecord(const std::string& path, const FailureRecord& record)
{
	ensureDirectory(fs::path(path).parent_path().string());
	writeTextAtomically(
		path, "exit_code = " + std::to_string(record.exit_code) + "\nerror = " + record.error_line +
				  "\n--- stderr ---\n" + record.stderr_text);
}

FailureRecord readFailureRecord(const std::string& path)
{
	TextLineReader in(path, "failure record");
	FailureRecord record;
	std::string line;
	const std::string exit_code = "exit_code = ";
	const bool has_exit_code = in.next(line) && line.rfind(exit_code, 0) == 0;
	const auto code = has_exit_code ? integerToken<int>(std::string_view(line).substr(exit_code.size())) : std::nullopt;
	if (!code) in.fail("expected 'exit_code = N'");
	record.exit_code = *code;
	if (!in.next(line) || line.rfind("error = ", 0) != 0) in.fail("expected 'error = ...'");
	record.error_line = line.substr(8);
	in.next(line);	// the "--- stderr ---" separator
	while (in.next(line)) record.stderr_text += line + "\n";
	return record;
}

}  // namespace esif
