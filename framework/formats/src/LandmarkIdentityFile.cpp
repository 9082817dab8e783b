/// \file LandmarkIdentityFile.cpp
/// landmark_identities.txt written and read back strictly (every token a
/// whole integer, every row consistent with itself and with the `# truth`
/// line), so a damaged or hand-edited file is reported at its line instead
/// of pairing landmarks wrongly; see LandmarkIdentityFile.h.

#include <esif/core/Errors.h>
#include <esif/core/InputBounds.h>
#include <esif/core/NumberToken.h>
#include <esif/core/TextInput.h>
#include <esif/formats/LandmarkIdentityFile.h>
#include <esif/safeio/AtomicFile.h>

#include <map>
#include <sstream>

namespace esif
{
namespace
{
/// The value of a `# truth yes|no` comment; nullopt for any other comment.
std::optional<bool> truthLineOf(const std::vector<std::string>& toks, const TextLineReader& in)
{
	if (toks.size() < 2 || toks[0] != "#" || toks[1] != "truth") return std::nullopt;
	if (toks.size() != 3 || (toks[2] != "yes" && toks[2] != "no")) in.fail("expected '# truth yes' or '# truth no'");
	return toks[2] == "yes";
}

bool isLandmarkId(LandmarkId id) { return id >= 0 && id <= kMaxLandmarkId; }

/// One data row, checked on its own and against the `# truth` line.
LandmarkIdentity identityRow(const std::vector<std::string>& toks, const TextLineReader& in, bool truth)
{
	static const std::string kColumns = "'landmark_id true_id votes measurements'";
	if (toks.size() != 4) in.fail("expected " + kColumns + ", found " + std::to_string(toks.size()) + " values");
	const auto landmark = integerToken<LandmarkId>(toks[0]);
	const auto true_id = integerToken<LandmarkId>(toks[1]);
	const auto votes = integerToken<std::size_t>(toks[2]);
	const auto measurements = integerToken<std::size_t>(toks[3]);
	if (!landmark || !true_id || !votes || !measurements)
		in.fail("every value must be a whole number (expected " + kColumns + ")");
	const std::string range = " is not a landmark ID in [0, " + std::to_string(kMaxLandmarkId) + "]";
	if (!isLandmarkId(*landmark)) in.fail("landmark_id " + toks[0] + range);
	if (*true_id != -1 && !isLandmarkId(*true_id)) in.fail("true_id " + toks[1] + range + " nor -1");
	if (*votes > *measurements) in.fail("more votes (" + toks[2] + ") than measurements (" + toks[3] + ")");
	if ((*true_id == -1) != (*votes == 0))
		in.fail("true_id -1 goes with 0 votes and a true landmark with at least one");
	if (!truth && *true_id != -1) in.fail("a true landmark under '# truth no'");
	LandmarkIdentity row;
	row.landmark = *landmark;
	if (*true_id != -1) row.true_id = *true_id;
	row.votes = *votes;
	row.measurements = *measurements;
	return row;
}
}  // namespace

std::string landmarkIdentityFileText(const LandmarkIdentities& identities)
{
	std::ostringstream out;
	out << "# esif landmark_identities.txt: the true landmark of each landmark of landmarks.txt, the one most of "
		   "its measurements came from\n"
		<< "# columns: landmark_id true_id votes measurements (true_id -1: none; votes: its measurements from "
		   "true_id; measurements: all the filter used on it)\n"
		<< "# truth " << (identities.truth ? "yes" : "no") << "\n";
	for (const LandmarkIdentity& l : identities.landmarks)
		out << l.landmark << ' ' << l.true_id.value_or(-1) << ' ' << l.votes << ' ' << l.measurements << '\n';
	return out.str();
}

void writeLandmarkIdentityFile(const std::string& path, const LandmarkIdentities& identities)
{
	writeTextAtomically(path, landmarkIdentityFileText(identities));
}

LandmarkIdentities readLandmarkIdentityFile(const std::string& path)
{
	TextLineReader in(path, "landmark identity file");
	LandmarkIdentities out;
	std::optional<bool> truth;
	std::map<LandmarkId, std::size_t> line_of;
	for (std::string line; in.next(line);)
	{
		const auto toks = whitespaceTokens(line);
		if (toks.empty()) continue;
		if (toks[0][0] == '#')
		{
			if (const auto declared = truthLineOf(toks, in))
			{
				if (truth) in.fail("a second '# truth' line");
				truth = declared;
			}
			continue;
		}
		if (!truth) in.fail("a row before the '# truth yes|no' line");
		const LandmarkIdentity row = identityRow(toks, in, *truth);
		if (const auto [it, added] = line_of.emplace(row.landmark, in.lineNumber()); !added)
			in.fail("landmark " + toks[0] + " listed twice (first on line " + std::to_string(it->second) + ")");
		out.landmarks.push_back(row);
	}
	if (!truth) throw InputError(path + ": no '# truth yes|no' line (not an esif landmark_identities.txt)");
	out.truth = *truth;
	return out;
}

}  // namespace esif
