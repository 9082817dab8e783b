#pragma once
/// \file LocalMapFolderSummary.h
/// What a folder of local maps holds, for `esif localmaps info` and the
/// summary of `esif localmaps build`: sizes, ground truth, and the check a
/// user runs before D-SLAM map joining (book Sec. 4.4.4): every map after
/// the first must share at least two features with the maps before it,
/// else its relative location cannot be recovered from the map alone.

#include <esif/formats/LocalMapFiles.h>

#include <cstddef>
#include <string>
#include <vector>

namespace esif
{
/// A map k >= 2 that shares fewer than kMinSharedFeatures features with maps 1..k-1.
struct WeaklyLinkedMap
{
	std::size_t map = 0;  ///< k
	std::size_t shared = 0;	 ///< its features whose ID appears in maps 1..k-1
};

struct LocalMapFolderSummary
{
	/// The book's Ch. 4 rule: features a map must share with the maps before it.
	static constexpr std::size_t kMinSharedFeatures = 2;

	std::size_t maps = 0;
	std::size_t steps = 0;	///< the maps' steps (0 for maps read from files)
	std::size_t state_dim_min = 0, state_dim_max = 0;
	double state_dim_mean = 0;
	std::size_t feature_entries = 0;  ///< features over all maps
	std::size_t distinct_ids = 0;
	std::size_t linked_maps = 0;  ///< maps whose start is linked by odometry (links.txt)
	std::optional<std::size_t> truth_landmarks;	 ///< rows of ground_truth_landmarks.txt, if present
	std::optional<std::size_t> truth_end_poses;	 ///< rows of ground_truth_end_poses.txt, if present
	std::vector<WeaklyLinkedMap> weakly_linked;	 ///< in order of k
};

LocalMapFolderSummary summarizeLocalMapFolder(const LocalMapFolder& folder);

/// "map 132 shares 1 feature with maps 1-131" ("... with map 1" for k = 2).
std::string weaklyLinkedText(const WeaklyLinkedMap& m);

/// The report of `esif localmaps info`: one fact per line, headed by `dir`.
std::string localMapFolderInfoText(const LocalMapFolderSummary& s, const std::string& dir);

}  // namespace esif
