/// \file LandmarkWriters.cpp
/// The final landmark map twice: landmarks.gz (a serialized
/// mrpt::maps::CLandmarksMap, for MRPT tools) and landmarks.txt (plain text,
/// for scripts and plots).

#include <esif/core/Errors.h>
#include <esif/formats/GzArchive.h>
#include <esif/formats/MapWriter.h>
#include <esif/safeio/AtomicFile.h>

#include <esif/formats/NumberText.h>

#include <mrpt/maps/CLandmark.h>
#include <mrpt/maps/CLandmarksMap.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/vision/types.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace esif
{
namespace
{
/// Variance given to the unestimated z of a planar landmark: small against any
/// real planar variance, but non-zero so the 3x3 covariance stays positive
/// definite for MRPT code that inverts or factors it.
constexpr float kPlanarZVariance = 1e-8f;

/// CLandmarksMap indexes its landmarks on a dense grid of 0.2 m cells (one
/// std::vector each) spanning at least [-10, 10]^2 m and growing to cover
/// every landmark. Above this many cells (about 240 MB, a map of roughly
/// 630 x 630 m) the file is refused rather than exhausting memory, e.g. on a
/// landmark that diverged far away.
constexpr double kGridCellM = 0.2;
constexpr double kMaxGridCells = 1e7;

bool isFinite(const LandmarkEstimate& lm) { return std::isfinite(lm.mean.x()) && std::isfinite(lm.mean.y()); }

/// Throws InputError naming `path` when CLandmarksMap's grid for `estimate`
/// would exceed kMaxGridCells.
void checkGridSize(const Estimate& estimate, const std::string& path)
{
	double x0 = -10, x1 = 10, y0 = -10, y1 = 10;
	for (const LandmarkEstimate& lm : estimate.landmarks)
	{
		if (!isFinite(lm)) continue;
		x0 = std::min(x0, lm.mean.x());
		x1 = std::max(x1, lm.mean.x());
		y0 = std::min(y0, lm.mean.y());
		y1 = std::max(y1, lm.mean.y());
	}
	const double cells = ((x1 - x0) / kGridCellM + 2) * ((y1 - y0) / kGridCellM + 2);
	if (cells > kMaxGridCells)
	{
		char msg[256];
		std::snprintf(
			msg, sizeof(msg),
			": landmarks span %.6g x %.6g m, too large for CLandmarksMap's 0.2 m grid (%.3g cells, limit %.3g); "
			"landmarks.txt holds the map",
			x1 - x0, y1 - y0, cells, kMaxGridCells);
		throw InputError(path + msg);
	}
}
}  // namespace

void writeLandmarksGz(const Estimate& estimate, const std::string& path)
{
	checkGridSize(estimate, path);
	mrpt::maps::CLandmarksMap map;
	for (const LandmarkEstimate& lm : estimate.landmarks)
	{
		// A non-finite position has no grid cell (CLandmarksMap asserts); such
		// a landmark is left out here and kept, as "nan", in landmarks.txt.
		if (!isFinite(lm)) continue;
		mrpt::maps::CLandmark l;
		// MRPT's landmark I/O asserts a first feature giving the landmark type.
		l.createOneFeature();
		l.features[0].type = mrpt::vision::featBeacon;
		l.ID = lm.id;
		l.pose_mean = mrpt::math::TPoint3D(lm.mean.x(), lm.mean.y(), 0.0);
		l.pose_cov_11 = static_cast<float>(lm.cov(0, 0));
		l.pose_cov_22 = static_cast<float>(lm.cov(1, 1));
		l.pose_cov_12 = static_cast<float>(0.5 * (lm.cov(0, 1) + lm.cov(1, 0)));
		l.pose_cov_33 = kPlanarZVariance;
		l.pose_cov_13 = 0;
		l.pose_cov_23 = 0;
		l.seenTimesCount = 1;
		map.landmarks.push_back(l);
	}

	writeGzArchiveAtomically(path, [&](mrpt::serialization::CArchive& out) { out << map; });
}

void writeLandmarksTxt(const Estimate& estimate, const std::string& path)
{
	std::string text =
		"# esif landmark map: id x y cxx cxy cyy (metres, metres^2; covariance of (x, y))\n";
	text.reserve(text.size() + 96 * estimate.landmarks.size());
	for (const LandmarkEstimate& lm : estimate.landmarks)
	{
		text += std::to_string(lm.id);
		for (const double v : {lm.mean.x(), lm.mean.y(), lm.cov(0, 0), 0.5 * (lm.cov(0, 1) + lm.cov(1, 0)),
							   lm.cov(1, 1)})
		{
			text += ' ';
			number_text::append(text, v);
		}
		text += '\n';
	}
	writeTextAtomically(path, text);
}

}  // namespace esif
