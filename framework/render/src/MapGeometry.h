#pragma once
/// \file MapGeometry.h
/// Private helpers shared by the scene and image writers: option checks,
/// bounds, path decimation, covariance ellipses and "nice" grid steps. Kept
/// header-only so the map writers need no extra source file.

#include <esif/core/Errors.h>
#include <esif/formats/RunRecord.h>
#include <esif/render/MapRender.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace esif::map_geometry
{
/// Smallest and largest accepted MapWriterOptions::image_size_px.
constexpr int kMinImageSizePx = 200;
constexpr int kMaxImageSizePx = 16384;

/// Throws ConfigError naming the first invalid field of `options`.
inline void validateOptions(const MapWriterOptions& options)
{
	if (options.image_size_px < kMinImageSizePx || options.image_size_px > kMaxImageSizePx)
		throw ConfigError(
			"image_size_px = " + std::to_string(options.image_size_px) + ": must be in [" +
			std::to_string(kMinImageSizePx) + ", " + std::to_string(kMaxImageSizePx) + "]");
	if (!std::isfinite(options.ellipse_sigmas) || options.ellipse_sigmas <= 0)
		throw ConfigError(
			"ellipse_sigmas = " + std::to_string(options.ellipse_sigmas) + ": must be a finite number > 0");
}

inline bool isFinite(const Eigen::Vector2d& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); }

/// Axis-aligned bounds of the drawn items; empty until a finite point is added.
struct Bounds
{
	double x_min = std::numeric_limits<double>::infinity();
	double x_max = -std::numeric_limits<double>::infinity();
	double y_min = std::numeric_limits<double>::infinity();
	double y_max = -std::numeric_limits<double>::infinity();

	bool empty() const { return x_min > x_max; }

	/// Non-finite points are ignored: one diverged landmark must not blow the
	/// whole picture up to an infinite extent.
	void add(const Eigen::Vector2d& p)
	{
		if (!isFinite(p)) return;
		x_min = std::min(x_min, p.x());
		x_max = std::max(x_max, p.x());
		y_min = std::min(y_min, p.y());
		y_max = std::max(y_max, p.y());
	}

	double width() const { return empty() ? 0 : x_max - x_min; }
	double height() const { return empty() ? 0 : y_max - y_min; }

	/// Grows the box to at least `min_span` on each axis (around its centre) and
	/// then by `margin` times its largest side on every edge. An empty box
	/// becomes a `min_span` square around the origin.
	Bounds padded(double min_span, double margin) const
	{
		Bounds b = *this;
		if (b.empty()) b.x_min = b.x_max = b.y_min = b.y_max = 0;
		const auto widen = [&](double& lo, double& hi) {
			if (hi - lo < min_span)
			{
				const double c = 0.5 * (lo + hi);
				lo = c - 0.5 * min_span;
				hi = c + 0.5 * min_span;
			}
		};
		widen(b.x_min, b.x_max);
		widen(b.y_min, b.y_max);
		const double pad = margin * std::max(b.x_max - b.x_min, b.y_max - b.y_min);
		b.x_min -= pad;
		b.x_max += pad;
		b.y_min -= pad;
		b.y_max += pad;
		return b;
	}
};

/// Symmetric, positive-semidefinite version of a 2x2 covariance (negative
/// eigenvalues from round-off clamped to zero). Non-finite input gives zero.
inline Eigen::Matrix2d sanitizedCov(const Eigen::Matrix2d& cov)
{
	if (!cov.allFinite()) return Eigen::Matrix2d::Zero();
	const Eigen::Matrix2d sym = 0.5 * (cov + cov.transpose());
	Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(sym);
	const Eigen::Vector2d ev = es.eigenvalues().cwiseMax(0.0);
	return es.eigenvectors() * ev.asDiagonal() * es.eigenvectors().transpose();
}

/// Closed polygon (first point repeated last) of the `sigmas`-sigma ellipse of
/// a 2-D Gaussian: mean + sigmas * V * sqrt(D) * (cos t, sin t).
inline std::vector<Eigen::Vector2d> ellipsePolygon(
	const Eigen::Vector2d& mean, const Eigen::Matrix2d& cov, double sigmas, int segments = 36)
{
	Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(sanitizedCov(cov));
	const Eigen::Matrix2d axes =
		sigmas * es.eigenvectors() * es.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
	std::vector<Eigen::Vector2d> pts;
	pts.reserve(static_cast<std::size_t>(segments) + 1);
	for (int i = 0; i <= segments; ++i)
	{
		const double t = 2.0 * M_PI * (i % segments) / segments;
		pts.push_back(mean + axes * Eigen::Vector2d(std::cos(t), std::sin(t)));
	}
	return pts;
}

/// Half extents (x, y) of the axis-aligned box around the `sigmas`-sigma
/// ellipse of `cov`, used to fit the view around whole ellipses.
inline Eigen::Vector2d ellipseHalfExtent(const Eigen::Matrix2d& cov, double sigmas)
{
	const Eigen::Matrix2d c = sanitizedCov(cov);
	return sigmas * Eigen::Vector2d(std::sqrt(c(0, 0)), std::sqrt(c(1, 1)));
}

/// The estimated path's positions, in trajectory order.
inline std::vector<Eigen::Vector2d> trajectoryXY(const RunRecord& run)
{
	std::vector<Eigen::Vector2d> pts;
	pts.reserve(run.trajectory.size());
	for (const TrajectoryPoint& p : run.trajectory) pts.emplace_back(p.pose.mean.x(), p.pose.mean.y());
	return pts;
}

/// The true path's positions (empty without ground truth).
inline std::vector<Eigen::Vector2d> truthPathXY(const RunRecord& run)
{
	std::vector<Eigen::Vector2d> pts;
	if (!run.truth) return pts;
	pts.reserve(run.truth->path.size());
	for (const Pose2& p : run.truth->path) pts.emplace_back(p.x(), p.y());
	return pts;
}

/// Bounds of everything the scene and the image show: paths, landmarks,
/// true landmarks, the final pose, and the landmarks' `sigmas` ellipses. An
/// ellipse may stretch the view by at most a quarter of the point content's
/// size, so one diverged landmark covariance cannot shrink the map to a dot.
inline Bounds contentBounds(const RunRecord& run, double sigmas)
{
	Bounds b;
	for (const Eigen::Vector2d& p : trajectoryXY(run)) b.add(p);
	for (const Eigen::Vector2d& p : truthPathXY(run)) b.add(p);
	if (run.truth)
		for (const auto& [id, p] : run.truth->landmarks) b.add(p);
	b.add(run.final_estimate.robot.mean.head<2>());
	for (const LandmarkEstimate& lm : run.final_estimate.landmarks) b.add(lm.mean);

	const double cap = 0.25 * std::max({b.width(), b.height(), 1.0});
	Bounds with_ellipses = b;
	for (const LandmarkEstimate& lm : run.final_estimate.landmarks)
	{
		if (!isFinite(lm.mean)) continue;
		const Eigen::Vector2d h = ellipseHalfExtent(lm.cov, sigmas).cwiseMin(cap);
		with_ellipses.add(lm.mean - h);
		with_ellipses.add(lm.mean + h);
	}
	return with_ellipses;
}

/// Distance from p to the segment [a, b].
inline double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
	const Eigen::Vector2d ab = b - a;
	const double len2 = ab.squaredNorm();
	const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
	return (p - (a + t * ab)).norm();
}

/// Indices of the points of a polyline to keep so that the kept polyline
/// stays within `tolerance` of every dropped point (first and last always
/// kept, non-finite points skipped). Straight or slow stretches of a long
/// trajectory then cost a couple of vertices while the drawn shape is
/// unchanged at the chosen resolution.
inline std::vector<std::size_t> simplifiedIndices(const std::vector<Eigen::Vector2d>& pts, double tolerance)
{
	// Streaming simplification: extend the current segment from the last kept
	// point while it passes near all points in between. The run length is
	// capped so a long stationary stretch stays linear in time.
	constexpr std::size_t kMaxRun = 256;
	std::vector<std::size_t> finite;
	finite.reserve(pts.size());
	for (std::size_t i = 0; i < pts.size(); ++i)
		if (isFinite(pts[i])) finite.push_back(i);
	std::vector<std::size_t> keep;
	if (finite.empty()) return keep;
	keep.push_back(finite[0]);
	std::size_t anchor = 0;	 // position in `finite` of the last kept point
	for (std::size_t k = 1; k < finite.size(); ++k)
	{
		bool fits = k - anchor <= kMaxRun;
		for (std::size_t j = anchor + 1; fits && j < k; ++j)
			fits = distanceToSegment(pts[finite[j]], pts[finite[anchor]], pts[finite[k]]) <= tolerance;
		if (!fits)
		{
			anchor = k - 1;
			keep.push_back(finite[anchor]);
		}
	}
	if (keep.back() != finite.back()) keep.push_back(finite.back());
	return keep;
}

/// simplifiedIndices() with the tolerance doubled until at most
/// `max_vertices` remain, so files stay light even for a path that goes
/// round the same loop many times.
inline std::vector<std::size_t> simplifiedIndices(
	const std::vector<Eigen::Vector2d>& pts, double tolerance, std::size_t max_vertices)
{
	std::vector<std::size_t> keep = simplifiedIndices(pts, tolerance);
	for (int i = 0; i < 30 && keep.size() > std::max<std::size_t>(max_vertices, 2); ++i)
	{
		tolerance *= 2;
		keep = simplifiedIndices(pts, tolerance);
	}
	return keep;
}

/// A step of 1, 2 or 5 times a power of ten giving about `target_count`
/// intervals over `span` (grid lines and scale bars people can read).
inline double niceStep(double span, double target_count)
{
	if (!(span > 0) || !(target_count > 0)) return 1.0;
	const double raw = span / target_count;
	const double p = std::pow(10.0, std::floor(std::log10(raw)));
	const double f = raw / p;
	const double m = f < 1.5 ? 1 : (f < 3.5 ? 2 : (f < 7.5 ? 5 : 10));
	return m * p;
}

}  // namespace esif::map_geometry
