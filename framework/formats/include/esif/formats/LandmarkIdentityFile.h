#pragma once
/// \file LandmarkIdentityFile.h
/// landmark_identities.txt: which true landmark each landmark of a run's
/// final map stands for, so that runs can be paired landmark by landmark
/// afterwards (`esif compare --reference`, `esif run --reference-run`)
/// whatever numbers each filter gave its own landmarks. A filter that
/// associates on its own numbers its landmarks itself; the reference,
/// solved with the rawlog's IDs, uses the true ones: only the identities
/// relate the two.
///
/// Format: '#' comment lines, one of which is `# truth yes` (the rawlog's
/// measurements carried their true landmarks, shown to the filter or hidden
/// from it) or `# truth no` (none did: no landmark has an identity), then
/// one row per landmark of landmarks.txt:
///
///     landmark_id true_id votes measurements
///
/// true_id: the true landmark most of the landmark's measurements came from
/// (-1: none, e.g. only simulated clutter, or `# truth no`); votes: how many
/// of its measurements came from true_id; measurements: every measurement
/// the filter used on it.

#include <esif/core/StepInput.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace esif
{
/// File name of a run's landmark identities, beside landmarks.txt.
constexpr const char* kLandmarkIdentityFileName = "landmark_identities.txt";

/// One landmark of a final map and its true landmark.
struct LandmarkIdentity
{
	LandmarkId landmark = 0;
	std::optional<LandmarkId> true_id;	///< none: no measurement of it carried a true landmark
	std::size_t votes = 0;	///< its measurements that came from true_id
	std::size_t measurements = 0;  ///< every measurement the filter used on it
};

struct LandmarkIdentities
{
	/// Whether any measurement of the rawlog carried its true landmark; when
	/// not, no landmark can have an identity and runs are paired otherwise.
	bool truth = false;
	std::vector<LandmarkIdentity> landmarks;  ///< in the final map's order
};

/// The text of landmark_identities.txt.
std::string landmarkIdentityFileText(const LandmarkIdentities& identities);

/// Writes landmarkIdentityFileText() to `path` atomically.
void writeLandmarkIdentityFile(const std::string& path, const LandmarkIdentities& identities);

/// Reads landmark_identities.txt. Throws InputError naming the file
/// (missing, unreadable, no `# truth yes|no` line) or "file:line" (a
/// malformed row, an ID outside MRPT's [0, 2^31 - 1], a landmark listed
/// twice, more votes than measurements, votes without a true landmark or a
/// true landmark without votes, a true landmark under `# truth no`).
LandmarkIdentities readLandmarkIdentityFile(const std::string& path);

}  // namespace esif
