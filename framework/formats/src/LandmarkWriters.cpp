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
#include <optional>
#include <string>

namespace esif
{
namespace
{
/// Variance given to the unestimated z of a planar landmark: small against any
/// real planar variance, but non-zero so the 3x3 covariance stays positive
/// definite for MRPT code that inverts or factors it.
constexpr float kPlanarZVariance = 1e-8f;

/// A CLandmarksMap read from the file indexes its landmarks on a dense grid
/// of 0.2 m cells (one std::vector each) spanning at least [-10, 10]^2 m and
/// growing to cover every landmark. Above this many cells (about 240 MB, a
/// map of roughly 630 x 630 m) the file is refused rather than handing MRPT's
/// tools a map they would exhaust memory on, e.g. for a landmark that
/// diverged far away.
constexpr double kGridCellM = 0.2;
constexpr double kMaxGridCells = 1e7;

bool isFinite(const LandmarkEstimate& lm) { return std::isfinite(lm.mean.x()) && std::isfinite(lm.mean.y()); }

/// The area CLandmarksMap's grid covers: [-10, 10]^2 m grown to every finite landmark.
struct GridBounds
{
	double x0 = -10, x1 = 10, y0 = -10, y1 = 10;
};

GridBounds gridBounds(const Estimate& estimate)
{
	GridBounds b;
	for (const LandmarkEstimate& lm : estimate.landmarks)
	{
		if (!isFinite(lm)) continue;
		b.x0 = std::min(b.x0, lm.mean.x());
		b.x1 = std::max(b.x1, lm.mean.x());
		b.y0 = std::min(b.y0, lm.mean.y());
		b.y1 = std::max(b.y1, lm.mean.y());
	}
	return b;
}

/// Why the 0.2 m grid a reader of the file builds (MRPT's tools,
/// CLandmarksMap::serializeFrom) would exceed kMaxGridCells, if it would.
std::optional<std::string> gridRefusal(const GridBounds& b)
{
	const double cells = ((b.x1 - b.x0) / kGridCellM + 2) * ((b.y1 - b.y0) / kGridCellM + 2);
	if (cells <= kMaxGridCells) return std::nullopt;
	char msg[256];
	std::snprintf(msg, sizeof(msg),
				  "landmarks span %.6g x %.6g m, too large for CLandmarksMap's 0.2 m grid (%.3g cells, limit %.3g)",
				  b.x1 - b.x0, b.y1 - b.y0, cells, kMaxGridCells);
	return std::string(msg);
}
}  // namespace

/// Cells per side of the lookup grid the writer gives CLandmarksMap. The grid
/// is never serialized (the file holds the landmarks alone, and a reader
/// builds its own 0.2 m grid), so the writer needs none: at 0.2 m, grown by
/// one resize per landmark that extends it, it is millions of cells for a
/// park-sized map and its filling dominated writing the file (time_landmarks_gz_s,
/// docs/results/end_to_end.md). One coarse grid, sized once, leaves the file
/// byte for byte the same.
constexpr double kWriterGridCellsPerSide = 16;

std::optional<std::string> landmarksGzRefusal(const Estimate& estimate) { return gridRefusal(gridBounds(estimate)); }

void writeLandmarksGz(const Estimate& estimate, const std::string& path)
{
	const GridBounds b = gridBounds(estimate);
	if (const auto refusal = gridRefusal(b)) throw InputError(path + ": " + *refusal + "; landmarks.txt holds the map");
	mrpt::maps::CLandmarksMap map;
	// push_back() resizes the grid only to cover a landmark outside it. The
	// bounds set here hold every landmark with a cell to spare (setSize
	// rounds them to whole cells), so it never does.
	const double cell = std::max(b.x1 - b.x0, b.y1 - b.y0) / kWriterGridCellsPerSide + kGridCellM;
	map.landmarks.getGrid()->setSize(b.x0 - cell, b.x1 + cell, b.y0 - cell, b.y1 + cell, cell);
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
