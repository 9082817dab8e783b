#pragma once
/// \file G2oFormat.h
/// The full-SLAM problem in the g2o text format, read by g2o's tools and by
/// GTSAM's readG2o, and such a file (or a solver's optimised output with the
/// same vertices) read back.
///
/// Vertex IDs (g2o needs one ID space for all vertices): pose i is vertex i
/// (0 .. P-1, pose 0 the initial pose, `FIX 0`), landmark L is vertex P + L
/// (landmark IDs must be >= 0). GTSAM's readG2o keys VERTEX_XY n and the
/// landmark of a BR line as Symbol('l', n), poses as plain keys n.
///
/// Lines written (information matrices as their upper triangle, row by row):
///   VERTEX_SE2 i x y theta
///   VERTEX_XY  P+L x y
///   EDGE_SE2 i j dx dy dtheta  I11 I12 I13 I22 I23 I33      (odometry)
/// and per measurement, one of
///   EDGE_SE2_XY i P+L px py  I11 I12 I22                    (G2oLandmarkEdge::PointXY)
///   BR i P+L bearing range sigma_bearing sigma_range        (G2oLandmarkEdge::BearingRange)
/// then, after the last edge, `FIX 0` and the comment lines describing the
/// file: GTSAM's readG2o stops at the first line it cannot parse, and some
/// of its versions cannot parse either (G2oWriter.cpp).
///
/// The odometry information is that of g2o's EdgeSE2 error, which sees the
/// translation noise from the increment's end: (J Q J^T)^-1 with
/// J = diag(R(-dtheta), 1) (odometryErrorCovariance); Q^-1 itself would
/// weight a turning step's noise in the wrong directions.
///
/// Why two landmark edges: g2o's slam2d types have no range-bearing edge;
/// its EDGE_SE2_XY (EdgeSE2PointXY) is the landmark in the robot frame, so
/// the measurement is converted, p = sensor (+) (r cos b, r sin b), and its
/// covariance propagated to first order, J R J^T with J = dp/d(r, b), the
/// information written being (J R J^T)^-1. GTSAM's readG2o does not read
/// EDGE_SE2_XY at all (its 2-D parser knows EDGE_SE2, BR and LANDMARK), and its LANDMARK form replaces a
/// non-isotropic covariance by unit sigmas; its BR form is read into a
/// BearingRangeFactor<Pose2, Point2> with the given sigmas, the exact
/// measurement model, which holds for a sensor at the robot's origin and a
/// diagonal (range, bearing) covariance (otherwise BR is refused).

#include <esif/formats/FullSlamProblem.h>

#include <Eigen/Core>
#include <map>
#include <string>

namespace esif
{
enum class G2oLandmarkEdge
{
	PointXY,	  ///< EDGE_SE2_XY: g2o
	BearingRange  ///< BR: GTSAM readG2o
};

/// The landmark in the robot frame and its first-order covariance, from a
/// range-bearing measurement taken by a sensor at `sensor_on_robot`.
struct PointInRobotFrame
{
	Eigen::Vector2d position;
	Eigen::Matrix2d cov;
};
PointInRobotFrame pointInRobotFrame(const RangeBearingFactor& m);

/// The covariance of g2o's EdgeSE2 error for odometry `f`: J Q J^T, J = diag(R(-dphi), 1).
Eigen::Matrix3d odometryErrorCovariance(const OdometryFactor& f);

/// The g2o text of `problem`; `source` goes into the header comment. Throws
/// InputError when a landmark ID is negative, or (BearingRange) when a
/// measurement's sensor is off the robot's origin or its covariance is not
/// diagonal.
std::string g2oText(const FullSlamProblem& problem, G2oLandmarkEdge edge, const std::string& source);

/// Writes g2oText() to `path` atomically.
void writeG2oFile(const std::string& path, const FullSlamProblem& problem, G2oLandmarkEdge edge,
				  const std::string& source);

/// The vertices of a g2o file and how many edges of each kind it holds.
struct G2oGraph
{
	std::map<long long, Pose2> poses;	 ///< VERTEX_SE2 by vertex ID
	std::map<long long, Eigen::Vector2d> points;  ///< VERTEX_XY by vertex ID
	std::size_t odometry_edges = 0;	 ///< EDGE_SE2
	std::size_t point_edges = 0;  ///< EDGE_SE2_XY and BR
};

/// Reads a g2o file strictly: '#' lines and blank lines are skipped; the
/// tags above are read; any other tag, a malformed line, a duplicate vertex,
/// an edge naming a vertex the file does not define or of the wrong kind, an
/// information matrix (or sigma) that is not finite and positive definite,
/// throws InputError "FILE:LINE: reason".
G2oGraph readG2oFile(const std::string& path);

}  // namespace esif
