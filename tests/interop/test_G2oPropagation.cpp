// The x-y landmark edge (EDGE_SE2_XY) carries the range-bearing noise
// propagated to first order, J R J^T with J = d p / d(range, bearing) through
// the sensor's mounting: checked against a numeric Jacobian and against the
// covariance of sampled measurements pushed through the exact conversion;
// and the information written is the inverse of that covariance.

#include <NumericJacobian.h>

#include <esif/formats/G2oFormat.h>
#include <esif/models/Se2.h>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include <random>
#include <sstream>

namespace
{
using namespace esif;

RangeBearingFactor measurement()
{
	RangeBearingFactor m;
	m.range_m = 4.0;
	m.bearing_rad = 0.7;
	m.cov << 0.01, 2e-5, 2e-5, 3e-4;  // 0.1 m, ~1 deg, slightly correlated
	m.sensor_on_robot = Pose2(0.3, -0.1, 0.2);
	return m;
}

/// The exact conversion: the point in the robot frame.
Eigen::Vector2d toRobotFrame(const Pose2& sensor, double range, double bearing)
{
	return transformPoint(sensor, Eigen::Vector2d(range * std::cos(bearing), range * std::sin(bearing)));
}

TEST(G2oPropagation, CovarianceIsTheNumericJacobianSandwich)
{
	const RangeBearingFactor m = measurement();
	const PointInRobotFrame p = pointInRobotFrame(m);
	EXPECT_LT((p.position - toRobotFrame(m.sensor_on_robot, m.range_m, m.bearing_rad)).norm(), 1e-15);
	const Eigen::MatrixXd J = test::numericJacobian(
		[&](const Eigen::VectorXd& z) { return Eigen::VectorXd(toRobotFrame(m.sensor_on_robot, z(0), z(1))); },
		Eigen::Vector2d(m.range_m, m.bearing_rad));
	const Eigen::Matrix2d expected = J * m.cov * J.transpose();
	// Central differences with h = 1e-6 on a function of scale 4 m: ~1e-9 relative.
	EXPECT_LT((p.cov - expected).cwiseAbs().maxCoeff(), 1e-8 * expected.cwiseAbs().maxCoeff());
}

TEST(G2oPropagation, CovarianceMatchesSampledMeasurements)
{
	const RangeBearingFactor m = measurement();
	const PointInRobotFrame p = pointInRobotFrame(m);
	const Eigen::Matrix2d L = m.cov.llt().matrixL();
	std::mt19937 rng(5);
	std::normal_distribution<double> n01;
	const int N = 200000;
	Eigen::Vector2d sum = Eigen::Vector2d::Zero();
	Eigen::Matrix2d sum2 = Eigen::Matrix2d::Zero();
	for (int i = 0; i < N; ++i)
	{
		const Eigen::Vector2d z = Eigen::Vector2d(m.range_m, m.bearing_rad) + L * Eigen::Vector2d(n01(rng), n01(rng));
		const Eigen::Vector2d x = toRobotFrame(m.sensor_on_robot, z(0), z(1));
		sum += x;
		sum2 += x * x.transpose();
	}
	const Eigen::Vector2d mean = sum / N;
	const Eigen::Matrix2d sampled = sum2 / N - mean * mean.transpose();
	// Sampling: a variance estimated from N draws has relative spread
	// sqrt(2/N) = 0.3%, so 4 sigma = 1.3%; the linearisation error is second
	// order, (r sigma_b^2) / (r sigma_b) ~ sigma_b = 1.7% of the cross-range
	// sigma in the mean, far less in the covariance (sigma_b^2 ~ 3e-4). 2% of
	// the largest entry covers both.
	EXPECT_LT((sampled - p.cov).cwiseAbs().maxCoeff(), 0.02 * p.cov.cwiseAbs().maxCoeff()) << sampled << "\n" << p.cov;
}

TEST(G2oPropagation, WrittenInformationIsTheInverseOfThePropagatedCovariance)
{
	FullSlamProblem problem;
	problem.poses = {Pose2::Zero()};
	problem.landmarks[3] = Eigen::Vector2d(3, 3);
	RangeBearingFactor m = measurement();
	m.landmark = 3;
	problem.observations.push_back(m);
	std::istringstream text(g2oText(problem, G2oLandmarkEdge::PointXY, "test"));
	std::string line;
	while (std::getline(text, line) && line.rfind("EDGE_SE2_XY", 0) != 0) {}
	std::istringstream ss(line);
	std::string tag;
	long long from = 0, to = 0;
	double px = 0, py = 0, i11 = 0, i12 = 0, i22 = 0;
	ss >> tag >> from >> to >> px >> py >> i11 >> i12 >> i22;
	EXPECT_EQ(from, 0);
	EXPECT_EQ(to, 1 + 3);  // P + landmark ID
	Eigen::Matrix2d info;
	info << i11, i12, i12, i22;
	const PointInRobotFrame p = pointInRobotFrame(m);
	EXPECT_LT((info * p.cov - Eigen::Matrix2d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
	EXPECT_EQ(Eigen::Vector2d(px, py), p.position);
}

}  // namespace
