/// \file AssociationFile.cpp
/// associations.txt written from the replay's step reports and read back
/// strictly: every token must be a whole integer or a known kind, and rows
/// must come in step and measurement order, so a damaged or hand-edited file
/// is reported at its line instead of silently shifting the association.

#include <esif/core/Errors.h>
#include <esif/core/InputBounds.h>
#include <esif/core/NumberToken.h>
#include <esif/core/TextInput.h>
#include <esif/formats/AssociationFile.h>

#include <esif/safeio/AtomicFile.h>

#include <functional>
#include <optional>
#include <sstream>

namespace esif
{
namespace
{
const char* kindName(Association::Kind kind)
{
	switch (kind)
	{
		case Association::Kind::New: return "new";
		case Association::Kind::Matched: return "matched";
		case Association::Kind::Rejected: break;
	}
	return "rejected";
}

std::optional<Association::Kind> kindOf(const std::string& text)
{
	if (text == "new") return Association::Kind::New;
	if (text == "matched") return Association::Kind::Matched;
	if (text == "rejected") return Association::Kind::Rejected;
	return std::nullopt;
}

/// The N of a `# steps N` comment, which must be the rawlog's step count;
/// nullopt for any other comment.
std::optional<std::size_t> stepCountOf(
	const std::vector<std::string>& toks, const TextLineReader& in, std::size_t rawlog_steps)
{
	if (toks.size() < 2 || toks[0] != "#" || toks[1] != "steps") return std::nullopt;
	const auto n = toks.size() == 3 ? integerToken<std::size_t>(toks[2]) : std::nullopt;
	if (!n) in.fail("expected '# steps N' with N a whole number");
	if (*n != rawlog_steps)
		in.fail("recorded for " + toks[2] + " steps, the rawlog has " + std::to_string(rawlog_steps));
	return n;
}

/// Parses one data row into `out`, checking it continues the file's order
/// (`previous_step`: the step of the row before, updated).
void readRow(
	const std::vector<std::string>& toks, const TextLineReader& in, std::size_t& previous_step,
	RecordedAssociations& out)
{
	static const std::string kColumns = "'step measurement kind landmark_id'";
	if (toks.size() != 4)
		in.fail("expected " + kColumns + ", found " + std::to_string(toks.size()) + " values");
	const auto step = integerToken<std::size_t>(toks[0]);
	const auto index = integerToken<std::size_t>(toks[1]);
	const auto kind = kindOf(toks[2]);
	const auto id = integerToken<LandmarkId>(toks[3]);
	if (!step || !index || !id)
		in.fail("step, measurement and landmark_id must be whole numbers (expected " + kColumns + ")");
	if (!kind) in.fail("kind '" + toks[2] + "' is not new, matched or rejected");
	if (*kind == Association::Kind::Rejected && *id != -1)
		in.fail("a rejected measurement has landmark_id -1, found " + toks[3]);
	if (*kind != Association::Kind::Rejected && (*id < 0 || *id > kMaxLandmarkId))
		in.fail("landmark_id " + toks[3] + " is not a landmark ID in [0, " + std::to_string(kMaxLandmarkId) + "]");
	if (*step >= out.steps.size())
		in.fail("step " + toks[0] + " beyond the " + std::to_string(out.steps.size()) + " steps declared");
	if (*step < previous_step)
		in.fail(
			"step " + toks[0] + " after step " + std::to_string(previous_step) + ": rows must be in step order");
	previous_step = *step;
	auto& associations = out.steps[*step].associations;
	if (*index != associations.size())
		in.fail(
			"step " + toks[0] + " measurement " + toks[1] + " out of order (expected measurement " +
				std::to_string(associations.size()) + ")");
	associations.push_back({*kind, *id});
}
}  // namespace

std::string associationFileText(
	const std::vector<StepReport>& reports, const std::string& plugin, const std::string& rawlog)
{
	std::ostringstream out;
	out << "# esif associations.txt: data association of plugin " << plugin << " on " << rawlog << "\n"
		<< "# columns: step measurement kind landmark_id (kind new|matched|rejected; landmark_id -1 when rejected)\n"
		<< "# steps " << reports.size() << "\n";
	for (std::size_t k = 0; k < reports.size(); ++k)
		for (std::size_t j = 0; j < reports[k].associations.size(); ++j)
		{
			const Association& a = reports[k].associations[j];
			const bool used = a.kind != Association::Kind::Rejected;
			out << k << ' ' << j << ' ' << kindName(a.kind) << ' ' << (used ? a.id : LandmarkId{-1}) << '\n';
		}
	return out.str();
}

void writeAssociationFile(
	const std::string& path, const std::vector<StepReport>& reports, const std::string& plugin,
	const std::string& rawlog)
{
	writeTextAtomically(path, associationFileText(reports, plugin, rawlog));
}

RecordedAssociations readAssociationFile(const std::string& path, std::size_t rawlog_steps)
{
	TextLineReader in(path, "association file");
	RecordedAssociations out;
	bool declared = false;
	std::size_t previous_step = 0;
	for (std::string line; in.next(line);)
	{
		const auto toks = whitespaceTokens(line);
		if (toks.empty()) continue;
		if (toks[0][0] == '#')
		{
			if (const auto n = stepCountOf(toks, in, rawlog_steps))
			{
				if (declared) in.fail("a second '# steps N' line");
				out.steps.resize(*n);
				declared = true;
			}
			continue;
		}
		if (!declared) in.fail("a row before the '# steps N' line");
		readRow(toks, in, previous_step, out);
	}
	if (!declared) throw InputError(path + ": no '# steps N' line (not an esif associations.txt)");
	return out;
}

namespace
{
/// InputError naming `path` unless the recorded run had `steps` steps and
/// `measurements(k)` measurements at step k.
void checkFit(const RecordedAssociations& recorded, std::size_t steps,
			  const std::function<std::size_t(std::size_t)>& measurements, const std::string& path)
{
	if (recorded.steps.size() != steps)
		throw InputError(
			path + ": recorded for " + std::to_string(recorded.steps.size()) + " steps, the rawlog has " +
			std::to_string(steps));
	for (std::size_t k = 0; k < steps; ++k)
	{
		const std::size_t recorded_here = recorded.steps[k].associations.size();
		if (recorded_here != measurements(k))
			throw InputError(
				path + ": step " + std::to_string(k) + ": " + std::to_string(recorded_here) + " associations for " +
				std::to_string(measurements(k)) + " measurements");
	}
}
}  // namespace

void applyAssociations(Rawlog& log, const RecordedAssociations& recorded, const std::string& path)
{
	// Check every step before changing any, so that a mismatch leaves `log` as it was.
	checkFit(recorded, log.steps.size(), [&](std::size_t k) {
		const auto& scan = log.steps[k].scan;
		return scan ? scan->measurements.size() : 0;
	}, path);
	for (std::size_t k = 0; k < log.steps.size(); ++k) applyRecordedStep(log.steps[k], recorded.steps[k]);
	log.any_landmark_id = anyIdGiven(recorded);
}

void checkAssociationsFit(const Rawlog& log, const RecordedAssociations& recorded, const std::string& path)
{
	checkFit(recorded, log.stepCount(), [&](std::size_t k) { return log.true_ids[k].size(); }, path);
}

void applyRecordedStep(StepInput& step, const StepReport& recorded)
{
	if (!step.scan) return;
	auto& measurements = step.scan->measurements;
	for (std::size_t j = 0; j < measurements.size() && j < recorded.associations.size(); ++j)
	{
		const Association& a = recorded.associations[j];
		if (a.kind == Association::Kind::Rejected)
			measurements[j].id.reset();
		else
			measurements[j].id = a.id;
	}
}

bool anyIdGiven(const RecordedAssociations& recorded)
{
	for (const auto& step : recorded.steps)
		for (const auto& a : step.associations)
			if (a.kind != Association::Kind::Rejected) return true;
	return false;
}

}  // namespace esif
