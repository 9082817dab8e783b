/// \file G2oWriter.cpp
/// The full-SLAM problem as g2o text (layout and the choice of landmark edge:
/// G2oFormat.h). Numbers are written as the shortest text that parses back
/// to the same double, so the file holds exactly the values esif used.

#include <esif/core/Errors.h>
#include <esif/formats/G2oFormat.h>
#include <esif/models/RangeBearingModel.h>
#include <esif/safeio/AtomicFile.h>

#include <esif/formats/NumberText.h>

#include <Eigen/Cholesky>

#include <climits>
#include <cmath>

namespace esif
{
namespace
{
void appendNumbers(std::string& text, std::initializer_list<double> values)
{
	for (const double v : values)
	{
		text += ' ';
		number_text::append(text, v);
	}
}

/// The upper triangle, row by row, of the inverse of the SPD `cov` (solved
/// through its Cholesky factor: a 3x3 or 2x2 block, never a large matrix).
template <int N>
void appendInformation(std::string& text, const Eigen::Matrix<double, N, N>& cov)
{
	const Eigen::Matrix<double, N, N> sym = 0.5 * (cov + cov.transpose());
	Eigen::Matrix<double, N, N> info = sym.llt().solve(Eigen::Matrix<double, N, N>::Identity());
	info = 0.5 * (info + info.transpose());
	for (int r = 0; r < N; ++r)
		for (int c = r; c < N; ++c) appendNumbers(text, {info(r, c)});
}

/// Vertex IDs (G2oFormat.h): pose i -> i, landmark L -> P + L, within g2o's int IDs.
class VertexIds
{
   public:
	explicit VertexIds(std::size_t poses) : poses_(static_cast<long long>(poses)) {}
	long long pose(std::size_t i) const { return static_cast<long long>(i); }
	long long landmark(LandmarkId id) const
	{
		if (id < 0)
			throw InputError(
				"landmark ID " + std::to_string(id) + " is negative: g2o vertex IDs (pose count + landmark ID) must "
													  "not be");
		if (id > INT_MAX - poses_)
			throw InputError("landmark ID " + std::to_string(id) + " is too large for g2o's int vertex IDs");
		return poses_ + id;
	}

   private:
	long long poses_;
};

void appendOdometry(std::string& text, const OdometryFactor& f, const VertexIds& ids)
{
	text += "EDGE_SE2 " + std::to_string(ids.pose(f.from)) + ' ' + std::to_string(ids.pose(f.to));
	appendNumbers(text, {f.delta.x(), f.delta.y(), f.delta.z()});
	appendInformation<3>(text, odometryErrorCovariance(f));
	text += '\n';
}

void appendPointXY(std::string& text, const RangeBearingFactor& m, const VertexIds& ids)
{
	const PointInRobotFrame p = pointInRobotFrame(m);
	text += "EDGE_SE2_XY " + std::to_string(ids.pose(m.pose)) + ' ' + std::to_string(ids.landmark(m.landmark));
	appendNumbers(text, {p.position.x(), p.position.y()});
	appendInformation<2>(text, p.cov);
	text += '\n';
}

void appendBearingRange(std::string& text, const RangeBearingFactor& m, const VertexIds& ids)
{
	const std::string what = "step " + std::to_string(m.step) + ", measurement " + std::to_string(m.measurement);
	if (!m.sensor_on_robot.isZero(0))
		throw InputError(
			what + ": the sensor is not at the robot's origin, which GTSAM's BR line cannot express (use the x-y "
				   "landmark edge)");
	if (m.cov(0, 1) != 0 || m.cov(1, 0) != 0)
		throw InputError(
			what + ": range and bearing noise are correlated, which GTSAM's BR line (two sigmas) cannot express "
				   "(use the x-y landmark edge)");
	text += "BR " + std::to_string(ids.pose(m.pose)) + ' ' + std::to_string(ids.landmark(m.landmark));
	appendNumbers(text, {m.bearing_rad, m.range_m, std::sqrt(m.cov(1, 1)), std::sqrt(m.cov(0, 0))});
	text += '\n';
}

std::string header(const FullSlamProblem& p, G2oLandmarkEdge edge, const std::string& source)
{
	const std::string P = std::to_string(p.poses.size());
	return "# esif export g2o: the full-SLAM problem of " + source + "\n# " + P + " poses: vertices 0.." +
		   std::to_string(p.poses.size() - 1) + " (0 = the initial pose, fixed); " +
		   std::to_string(p.landmarks.size()) + " landmarks: vertex " + P + " + landmark ID\n# " +
		   std::to_string(p.odometry.size()) + " odometry edges (EDGE_SE2), " +
		   std::to_string(p.observations.size()) + " landmark edges (" +
		   (edge == G2oLandmarkEdge::PointXY ? "EDGE_SE2_XY: landmark in the robot frame, for g2o"
											 : "BR: bearing range sigma_bearing sigma_range, for GTSAM readG2o") +
		   ")\n";
}
}  // namespace

Eigen::Matrix3d odometryErrorCovariance(const OdometryFactor& f)
{
	// The increment's noise w is added to the increment in the frame of pose
	// `from` (eq. 1.19: Xi^-1 (+) Xj = u + w). g2o's EdgeSE2 error is
	// Z^-1 (+) (Xi^-1 (+) Xj) = (R(-u_phi) w_xy, w_phi): the translation noise
	// seen from the increment's end. Its covariance is J Q J^T with
	// J = diag(R(-u_phi), 1), exactly; GTSAM's BetweenFactor<Pose2>
	// (Logmap(Z^-1 Xi^-1 Xj)) agrees to first order.
	Eigen::Matrix3d J = Eigen::Matrix3d::Identity();
	const double c = std::cos(f.delta.z()), s = std::sin(f.delta.z());
	J.topLeftCorner<2, 2>() << c, s, -s, c;
	const Eigen::Matrix3d cov = J * f.cov * J.transpose();
	return 0.5 * (cov + cov.transpose());
}

PointInRobotFrame pointInRobotFrame(const RangeBearingFactor& m)
{
	// The inverse model (eq. 1.6 inverted) from the robot at the origin gives
	// the point in the robot frame and its Jacobian d p / d(range, bearing).
	const LandmarkFromMeasurement l = landmarkFromRangeBearing(Pose2::Zero(), m.sensor_on_robot, m.range_m, m.bearing_rad);
	PointInRobotFrame p;
	p.position = l.position;
	p.cov = l.d_measurement * m.cov * l.d_measurement.transpose();
	p.cov = 0.5 * (p.cov + p.cov.transpose());
	return p;
}

std::string g2oText(const FullSlamProblem& problem, G2oLandmarkEdge edge, const std::string& source)
{
	const VertexIds ids(problem.poses.size());
	std::string text;
	text.reserve(512 + 64 * problem.poses.size() + 48 * problem.landmarks.size() +
				 128 * problem.odometry.size() + 96 * problem.observations.size());
	for (std::size_t i = 0; i < problem.poses.size(); ++i)
	{
		const Pose2& x = problem.poses[i];
		text += "VERTEX_SE2 " + std::to_string(ids.pose(i));
		appendNumbers(text, {x.x(), x.y(), wrapAngle(x.z())});
		text += '\n';
	}
	for (const auto& [id, position] : problem.landmarks)
	{
		text += "VERTEX_XY " + std::to_string(ids.landmark(id));
		appendNumbers(text, {position.x(), position.y()});
		text += '\n';
	}
	// Edges in rawlog order: each step's odometry, then its measurements.
	std::size_t next_observation = 0;
	const auto appendObservationsUpTo = [&](std::size_t step_limit) {
		for (; next_observation < problem.observations.size() &&
			   problem.observations[next_observation].step < step_limit;
			 ++next_observation)
		{
			const RangeBearingFactor& m = problem.observations[next_observation];
			if (edge == G2oLandmarkEdge::PointXY)
				appendPointXY(text, m, ids);
			else
				appendBearingRange(text, m, ids);
		}
	};
	for (const OdometryFactor& f : problem.odometry)
	{
		appendObservationsUpTo(f.step);
		appendOdometry(text, f, ids);
	}
	appendObservationsUpTo(std::numeric_limits<std::size_t>::max());
	// FIX and the comments come after the last edge. GTSAM's readG2o reads a
	// tag and then, in its bearing-range parser, two vertex ids before it
	// checks the tag; on a line without two numbers after its first word
	// (a comment, "FIX 0") the stream fails and GTSAM stops reading the
	// file, silently dropping every factor after it. Here nothing is left
	// to drop. g2o reads FIX and skips comments wherever they are.
	text += "FIX 0\n";
	text += header(problem, edge, source);
	return text;
}

void writeG2oFile(const std::string& path, const FullSlamProblem& problem, G2oLandmarkEdge edge,
				  const std::string& source)
{
	std::string text;
	try
	{
		text = g2oText(problem, edge, source);
	}
	catch (const InputError& e)
	{
		throw InputError(path + ": " + e.what());
	}
	writeTextAtomically(path, text);
}

}  // namespace esif
