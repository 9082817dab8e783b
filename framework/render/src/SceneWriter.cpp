/// \file SceneWriter.cpp
/// scene.3Dscene: the run as an mrpt::opengl::COpenGLScene for MRPT's
/// SceneViewer3D — ground grid, estimated landmarks with their uncertainty
/// ellipses, estimated path, final robot pose and, when known, the ground
/// truth. Every object is named so that scripts and tests can find it.

#include <esif/core/Errors.h>
#include <esif/formats/GzArchive.h>
#include <esif/render/MapRender.h>

#include "MapGeometry.h"
#include "MapPalette.h"

#include <mrpt/img/TColor.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/opengl/CEllipsoid2D.h>
#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CPointCloud.h>
#include <mrpt/opengl/CSetOfLines.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/opengl/CText.h>
#include <mrpt/opengl/stock_objects.h>
#include <mrpt/poses/CPose3D.h>

#include <algorithm>
#include <cmath>

namespace esif
{
namespace
{
using mrpt::img::TColor;
using namespace esif::map_palette;
namespace mg = map_geometry;

// Layer heights: each layer slightly above the one below so that coincident
// lines (true and estimated path, grid) do not z-fight in the viewer.
constexpr double kZTruth = 0.01;
constexpr double kZEstimate = 0.02;
constexpr double kZRobot = 0.03;

const TColor kGridColor(200, 200, 200);
const TColor kSceneRobotEllipseColor(30, 80, 220);

/// ID labels for up to this many landmarks: beyond that they clutter the view
/// and weigh more than the rest of the scene.
constexpr std::size_t kMaxLandmarkLabels = 300;

/// Most vertices of one path in the scene: enough for any shape on screen,
/// and it keeps an 18000-step run's scene small and quick to open.
constexpr std::size_t kMaxPathVertices = 4000;

/// A line strip through `pts`, simplified to `tolerance` [m].
mrpt::opengl::CSetOfLines::Ptr lineStrip(
	const std::vector<Eigen::Vector2d>& pts, double tolerance, double z, const TColor& color, float width,
	const std::string& name)
{
	auto lines = mrpt::opengl::CSetOfLines::Create();
	lines->setName(name);
	lines->setColor_u8(color);
	lines->setLineWidth(width);
	const std::vector<std::size_t> keep = mg::simplifiedIndices(pts, tolerance, kMaxPathVertices);
	for (std::size_t k = 1; k < keep.size(); ++k)
	{
		const Eigen::Vector2d& a = pts[keep[k - 1]];
		const Eigen::Vector2d& b = pts[keep[k]];
		lines->appendLine(a.x(), a.y(), z, b.x(), b.y(), z);
	}
	return lines;
}

mrpt::math::CMatrixDouble22 toMrpt(const Eigen::Matrix2d& m)
{
	mrpt::math::CMatrixDouble22 c;
	for (int r = 0; r < 2; ++r)
		for (int k = 0; k < 2; ++k) c(r, k) = m(r, k);
	return c;
}

/// The `sigmas` ellipse of a 2-D Gaussian, or null for a zero covariance
/// (nothing to draw). Centred with setLocation() and a zero mean, the way
/// MRPT's own code places its ellipses.
mrpt::opengl::CEllipsoid2D::Ptr ellipse(
	const Eigen::Vector2d& mean, const Eigen::Matrix2d& cov, double sigmas, double z, const TColor& color)
{
	const Eigen::Matrix2d c = mg::sanitizedCov(cov);
	if (c.isZero(0.0)) return nullptr;
	auto e = mrpt::opengl::CEllipsoid2D::Create();
	e->setCovMatrix(toMrpt(c));
	e->setQuantiles(static_cast<float>(sigmas));
	e->set2DsegmentsCount(36);
	e->setLocation(mean.x(), mean.y(), z);
	e->setColor_u8(color);
	e->setLineWidth(1.5f);
	return e;
}
}  // namespace

void writeScene(const RunRecord& run, const std::string& path, const MapWriterOptions& options)
{
	mg::validateOptions(options);
	const double sigmas = options.ellipse_sigmas;
	const mg::Bounds content = mg::contentBounds(run, sigmas).padded(2.0, 0.05);
	const double span = std::max(content.width(), content.height());
	const double step = mg::niceStep(span, 10);
	const double tolerance = span / 4000;  // well under a pixel at full view

	mrpt::opengl::COpenGLScene scene;

	// Grid: whole cells, so its border lines fall on round coordinates.
	auto grid = mrpt::opengl::CGridPlaneXY::Create(
		static_cast<float>(std::floor(content.x_min / step) * step),
		static_cast<float>(std::ceil(content.x_max / step) * step),
		static_cast<float>(std::floor(content.y_min / step) * step),
		static_cast<float>(std::ceil(content.y_max / step) * step), 0.0f, static_cast<float>(step), 1.0f);
	grid->setName("grid");
	grid->setColor_u8(kGridColor);
	scene.insert(grid);

	if (run.truth)
	{
		scene.insert(lineStrip(mg::truthPathXY(run), tolerance, kZTruth, kTruthPathColor, 2.0f, "truth_path"));
		// Crosses rather than points, so true and estimated landmarks stay
		// distinguishable where they coincide.
		auto crosses = mrpt::opengl::CSetOfLines::Create();
		crosses->setName("truth_landmarks");
		crosses->setColor_u8(kTruthLandmarkColor);
		crosses->setLineWidth(2.0f);
		const double h = 0.008 * span;
		for (const auto& [id, p] : run.truth->landmarks)
		{
			if (!mg::isFinite(p)) continue;
			crosses->appendLine(p.x() - h, p.y(), kZTruth, p.x() + h, p.y(), kZTruth);
			crosses->appendLine(p.x(), p.y() - h, kZTruth, p.x(), p.y() + h, kZTruth);
		}
		scene.insert(crosses);
	}

	scene.insert(lineStrip(mg::trajectoryXY(run), tolerance, kZEstimate, kPathColor, 2.0f, "trajectory"));

	const auto& landmarks = run.final_estimate.landmarks;
	auto points = mrpt::opengl::CPointCloud::Create();
	points->setName("landmarks");
	points->setColor_u8(kLandmarkColor);
	points->setPointSize(6.0f);
	auto ellipses = mrpt::opengl::CSetOfObjects::Create();
	ellipses->setName("landmark_ellipses");
	auto labels = mrpt::opengl::CSetOfObjects::Create();
	labels->setName("landmark_ids");
	for (const LandmarkEstimate& lm : landmarks)
	{
		if (!mg::isFinite(lm.mean)) continue;
		points->insertPoint(
			static_cast<float>(lm.mean.x()), static_cast<float>(lm.mean.y()), static_cast<float>(kZEstimate));
		if (auto e = ellipse(lm.mean, lm.cov, sigmas, kZEstimate, kLandmarkColor)) ellipses->insert(e);
		if (landmarks.size() <= kMaxLandmarkLabels)
		{
			auto label = mrpt::opengl::CText::Create(std::to_string(lm.id));
			label->setLocation(lm.mean.x() + 0.005 * span, lm.mean.y() + 0.005 * span, kZEstimate);
			label->setColor_u8(kLandmarkColor);
			labels->insert(label);
		}
	}
	scene.insert(points);
	scene.insert(ellipses);
	if (labels->size() > 0) scene.insert(labels);

	// Final robot pose: axes at the pose (x red, y green, z blue) and its
	// position uncertainty at the same sigma level as the landmarks.
	const PoseEstimate& robot = run.final_estimate.robot;
	if (std::isfinite(robot.mean.x()) && std::isfinite(robot.mean.y()) && std::isfinite(robot.mean(2)))
	{
		auto corner = mrpt::opengl::stock_objects::CornerXYZSimple(static_cast<float>(0.06 * span), 3.0f);
		corner->setName("robot");
		corner->setPose(mrpt::poses::CPose3D(robot.mean.x(), robot.mean.y(), kZRobot, robot.mean(2), 0, 0));
		scene.insert(corner);
		if (auto robot_ellipse = ellipse(
				robot.mean.head<2>(), robot.cov.topLeftCorner<2, 2>(), sigmas, kZRobot,
				kSceneRobotEllipseColor))
		{
			robot_ellipse->setName("robot_ellipse");
			scene.insert(robot_ellipse);
		}
	}

	// Open SceneViewer3D looking down on the whole map rather than at a fixed
	// spot around the origin: it applies the main viewport's camera on load
	// when followCamera is set.
	auto& camera = scene.getViewport("main")->getCamera();
	camera.setPointingAt(
		static_cast<float>(0.5 * (content.x_min + content.x_max)),
		static_cast<float>(0.5 * (content.y_min + content.y_max)), 0.0f);
	camera.setZoomDistance(static_cast<float>(1.8 * span));
	camera.setAzimuthDegrees(-90.0f);
	camera.setElevationDegrees(75.0f);
	scene.enableFollowCamera(true);

	// The gzip of the serialized scene, as COpenGLScene::saveToFile writes
	// and loadFromFile reads it, but with every write checked (GzArchive.h).
	writeGzArchiveAtomically(path, [&](mrpt::serialization::CArchive& out) { out << scene; });
}

}  // namespace esif
