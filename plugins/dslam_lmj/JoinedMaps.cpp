#include "JoinedMaps.h"

#include <esif/localmap/LocalMapMerge.h>

namespace esif::lmj
{
JoinedMaps single(const LocalMap& map)
{
	return {map, {map.index}, {}};
}

JoinedMaps joinConsecutive(const JoinedMaps& earlier, const JoinedMaps& later)
{
	// mergeConsecutiveLocalMaps wants consecutive indices; the joined map
	// keeps the earlier one's.
	LocalMap first = earlier.map;
	first.index = later.map.index - 1;
	JoinedMaps joined;
	joined.map = mergeConsecutiveLocalMaps(first, later.map);
	joined.map.index = earlier.map.index;

	joined.originals = earlier.originals;
	joined.originals.insert(joined.originals.end(), later.originals.begin(), later.originals.end());
	joined.absorbed = earlier.absorbed;
	joined.absorbed.emplace_back(earlier.map.end_pose, earlier.map.covarianceMatrix().topLeftCorner<3, 3>());
	const Eigen::Matrix3d earlier_end_cov = joined.absorbed.back().second;
	for (const auto& [pose, cov] : later.absorbed)
	{
		// End poses the later map absorbed are in its frame: carry them into the earlier one's.
		const PoseEstimate moved =
			composeIndependent({earlier.map.end_pose, earlier_end_cov}, {pose, cov});
		joined.absorbed.emplace_back(moved.mean, moved.cov);
	}
	return joined;
}

}  // namespace esif::lmj
