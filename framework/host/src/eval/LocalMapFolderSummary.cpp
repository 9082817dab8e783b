#include <esif/eval/LocalMapFolderSummary.h>

#include <algorithm>
#include <cstdio>
#include <set>
#include <sstream>

namespace esif
{
namespace
{
std::string plural(std::size_t n, const std::string& word) { return std::to_string(n) + " " + word + (n == 1 ? "" : "s"); }

/// Maps 2.. whose features meet fewer than kMinSharedFeatures IDs of the maps before them.
std::vector<WeaklyLinkedMap> weaklyLinkedMaps(const std::vector<LocalMap>& maps)
{
	std::vector<WeaklyLinkedMap> out;
	std::set<LandmarkId> seen;
	for (std::size_t i = 0; i < maps.size(); ++i)
	{
		std::size_t shared = 0;
		for (const auto& f : maps[i].features) shared += seen.count(f.id);
		if (i > 0 && shared < LocalMapFolderSummary::kMinSharedFeatures) out.push_back({maps[i].index, shared});
		for (const auto& f : maps[i].features) seen.insert(f.id);
	}
	return out;
}
}  // namespace

LocalMapFolderSummary summarizeLocalMapFolder(const LocalMapFolder& folder)
{
	LocalMapFolderSummary s;
	s.maps = folder.maps.size();
	std::set<LandmarkId> ids;
	double dim_sum = 0;
	for (const LocalMap& map : folder.maps)
	{
		const std::size_t dim = map.stateDim();
		s.state_dim_min = &map == &folder.maps.front() ? dim : std::min(s.state_dim_min, dim);
		s.state_dim_max = std::max(s.state_dim_max, dim);
		dim_sum += static_cast<double>(dim);
		s.steps += map.steps;
		s.feature_entries += map.features.size();
		s.linked_maps += map.link.has_value();
		for (const auto& f : map.features) ids.insert(f.id);
	}
	s.state_dim_mean = s.maps ? dim_sum / static_cast<double>(s.maps) : 0.0;
	s.distinct_ids = ids.size();
	if (folder.truth_landmarks) s.truth_landmarks = folder.truth_landmarks->size();
	if (folder.truth_end_poses) s.truth_end_poses = folder.truth_end_poses->size();
	s.weakly_linked = weaklyLinkedMaps(folder.maps);
	return s;
}

std::string weaklyLinkedText(const WeaklyLinkedMap& m)
{
	const std::string before = m.map == 2 ? "map 1" : "maps 1-" + std::to_string(m.map - 1);
	return "map " + std::to_string(m.map) + " shares " + plural(m.shared, "feature") + " with " + before;
}

std::string localMapFolderInfoText(const LocalMapFolderSummary& s, const std::string& dir)
{
	std::ostringstream out;
	char mean[32];
	std::snprintf(mean, sizeof(mean), "%.1f", s.state_dim_mean);
	out << dir << ": " << plural(s.maps, "local map") << "\n";
	out << "  state dimension min/mean/max: " << s.state_dim_min << " / " << mean << " / " << s.state_dim_max << "\n";
	out << "  feature entries: " << s.feature_entries << "\n";
	out << "  distinct feature IDs: " << s.distinct_ids << "\n";
	if (s.linked_maps) out << "  maps linked by odometry (links.txt): " << s.linked_maps << "\n";
	out << "  ground truth: ";
	if (!s.truth_landmarks && !s.truth_end_poses) out << "none";
	if (s.truth_landmarks) out << plural(*s.truth_landmarks, "landmark");
	if (s.truth_landmarks && s.truth_end_poses) out << ", ";
	if (s.truth_end_poses) out << plural(*s.truth_end_poses, "end pose");
	out << "\n";
	if (s.weakly_linked.empty())
		out << "  every map shares at least " << LocalMapFolderSummary::kMinSharedFeatures
			<< " features with the maps before it (D-SLAM map joining, Sec. 4.4.4)\n";
	else
	{
		out << "  maps sharing fewer than " << LocalMapFolderSummary::kMinSharedFeatures
			<< " features with the maps before them (D-SLAM map joining needs 2, Sec. 4.4.4): "
			<< s.weakly_linked.size() << "\n";
		for (const auto& m : s.weakly_linked) out << "    " << weaklyLinkedText(m) << "\n";
	}
	return out.str();
}

}  // namespace esif
