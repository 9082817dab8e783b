#include <esif/core/Errors.h>
#include <esif/core/InputBounds.h>
#include <esif/core/NumberToken.h>
#include <esif/core/TextInput.h>
#include <esif/safeio/AtomicFile.h>
#include <esif/formats/MeasurementTruth.h>

#include <array>
#include <optional>
#include <sstream>

namespace esif
{
namespace
{
/// The file's value for "no landmark" (MRPT's INVALID_LANDMARK_ID).
constexpr long long kNoLandmark = -1;

/// The integers of a row 'step measurement rawlog_id true_id'; nullopt
/// unless `line` holds exactly four.
std::optional<std::array<long long, 4>> rowOf(const std::string& line)
{
	const auto tokens = whitespaceTokens(line);
	std::array<long long, 4> out{};
	if (tokens.size() != out.size()) return std::nullopt;
	for (std::size_t i = 0; i < out.size(); ++i)
	{
		const auto v = integerToken<long long>(tokens[i]);
		if (!v) return std::nullopt;
		out[i] = *v;
	}
	return out;
}
}  // namespace

std::string measurementTruthFileOf(const std::string& prefix) { return prefix + "_ground_truth_measurement_ids.txt"; }

void saveMeasurementTruth(const MeasurementTruth& truth, const std::string& prefix)
{
	std::ostringstream out;
	out << "% True landmark of every measurement, in rawlog order (true_id -1: spurious return, no landmark)\n";
	out << "% Columns are: step measurement rawlog_id true_id\n";
	for (std::size_t k = 0; k < truth.size(); ++k)
		for (std::size_t i = 0; i < truth[k].size(); ++i)
			out << k << ' ' << i << ' ' << truth[k][i].rawlog_id << ' '
				<< (truth[k][i].true_id ? static_cast<long long>(*truth[k][i].true_id) : kNoLandmark) << '\n';
	writeTextAtomically(measurementTruthFileOf(prefix), out.str());
}

std::optional<std::vector<std::vector<std::optional<LandmarkId>>>> loadMeasurementTruth(
	const std::string& prefix, std::size_t steps)
{
	const std::string path = measurementTruthFileOf(prefix);
	if (!pathPresent(path)) return std::nullopt;
	TextLineReader in(path, "ground-truth measurement IDs");
	std::vector<std::vector<std::optional<LandmarkId>>> ids;
	for (std::string line; in.next(line);)
	{
		const auto first = line.find_first_not_of(" \t\r");
		if (first == std::string::npos || line[first] == '%') continue;
		const auto row = rowOf(line);
		if (!row || (*row)[0] < 0 || (*row)[1] < 0 || (*row)[3] < kNoLandmark || (*row)[3] > kMaxLandmarkId)
			in.fail(
				"expected 'step measurement rawlog_id true_id' (integers, true_id -1 or a landmark ID in [0, " +
				std::to_string(kMaxLandmarkId) + "])");
		const auto [step, index, rawlog_id, true_id] = *row;
		if (static_cast<unsigned long long>(step) >= steps)
			in.fail("step " + std::to_string(step) + " but the rawlog has " + std::to_string(steps) + " steps");
		const auto k = static_cast<std::size_t>(step);
		if (k + 1 < ids.size() || (k < ids.size() && static_cast<std::size_t>(index) != ids[k].size()) ||
			(k >= ids.size() && index != 0))
			in.fail(
				"step " + std::to_string(step) + " measurement " + std::to_string(index) +
				" out of order (rows go by step, then measurement, from 0)");
		if (k >= ids.size()) ids.resize(k + 1);
		ids[k].push_back(true_id == kNoLandmark ? std::nullopt : std::optional<LandmarkId>(true_id));
	}
	return ids;
}

}  // namespace esif
