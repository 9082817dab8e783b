#include "JoinedMaps.h"

#include <esif/localmap/LocalMapMarginal.h>
#include <esif/localmap/LocalMapMerge.h>
#include <esif/models/LocalMapObservation.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

namespace esif::lmj
{
JoinedMaps single(const LocalMap& map)
{
	return {map, {map.index}, {}};
}

namespace
{
/// Index of feature `id` in `map`, or -1.
int featureIndex(const LocalMap& map, LandmarkId id)
{
	for (std::size_t i = 0; i < map.features.size(); ++i)
		if (map.features[i].id == id) return static_cast<int>(i);
	return -1;
}

/// Squared Mahalanobis distance between feature i of `earlier` and feature
/// j of `later` moved into earlier's frame through its end pose.
double disagreement2(const LocalMap& earlier, const Eigen::MatrixXd& earlier_cov, int i, const LocalMap& later,
					 const Eigen::MatrixXd& later_cov, int j)
{
	const PointFromFrame moved = pointFromFrame(earlier.end_pose, later.features[j].position);
	const Eigen::Vector2d nu = earlier.features[i].position - moved.value;
	const Eigen::Index fi = 3 + 2 * i, fj = 3 + 2 * j;
	Eigen::Matrix<double, 2, 5> J;	// d nu / d [end pose; feature i] of earlier
	J << -moved.d_frame, Eigen::Matrix2d::Identity();
	const std::vector<Eigen::Index> rows = {0, 1, 2, fi, fi + 1};
	const Eigen::Matrix2d S = J * earlier_cov(rows, rows) * J.transpose() +
		moved.d_point * later_cov.block<2, 2>(fj, fj) * moved.d_point.transpose();
	const Eigen::LLT<Eigen::Matrix2d> llt(0.5 * (S + S.transpose()));
	return llt.info() == Eigen::Success ? nu.dot(llt.solve(nu)) : std::numeric_limits<double>::infinity();
}

/// `map` without the features `ids` (marginalised out), their sightings
/// reported rejected.
LocalMap withoutFeatures(const LocalMap& map, const std::vector<LandmarkId>& ids)
{
	if (ids.empty()) return map;
	const auto dropped = [&](LandmarkId id) { return std::find(ids.begin(), ids.end(), id) != ids.end(); };
	std::vector<bool> keep;
	for (const auto& f : map.features) keep.push_back(!dropped(f.id));
	LocalMap out = marginaliseFeatures(map, keep);
	for (StepReport& report : out.step_reports)
		for (Association& a : report.associations)
			if (a.kind != Association::Kind::Rejected && dropped(a.id)) a = {Association::Kind::Rejected, -1};
	return out;
}
}  // namespace

std::vector<LandmarkId> disagreeingFeatures(const LocalMap& earlier, const LocalMap& later, double gate_d2)
{
	std::vector<LandmarkId> out;
	if (std::isinf(gate_d2)) return out;
	const Eigen::MatrixXd earlier_cov = earlier.covarianceMatrix(), later_cov = later.covarianceMatrix();
	for (std::size_t j = 0; j < later.features.size(); ++j)
	{
		const int i = featureIndex(earlier, later.features[j].id);
		if (i >= 0 && disagreement2(earlier, earlier_cov, i, later, later_cov, static_cast<int>(j)) > gate_d2)
			out.push_back(later.features[j].id);
	}
	return out;
}

JoinedMaps joinConsecutive(const JoinedMaps& earlier, const JoinedMaps& later,
						   const std::vector<LandmarkId>& left_out_of_later)
{
	// mergeConsecutiveLocalMaps wants consecutive indices; the joined map
	// keeps the earlier one's.
	LocalMap first = earlier.map;
	first.index = later.map.index - 1;
	JoinedMaps joined;
	joined.map = mergeConsecutiveLocalMaps(first, withoutFeatures(later.map, left_out_of_later));
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
