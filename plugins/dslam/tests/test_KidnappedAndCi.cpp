// D-SLAM's two localisation building blocks against hand-computed cases:
// the "kidnapped robot" solution, eq. (3.17)-(3.18), and covariance
// intersection, eq. (3.20)-(3.21), plus the robot-marginal replacement used
// by `fusion = robot`, and the recasting round trips eq. (3.14), (3.18).

#include "CovarianceIntersection.h"
#include "KidnappedRobot.h"
#include "KidnappedTestCase.h"

#include <NumericJacobian.h>
#include <esif/core/Errors.h>
#include <esif/relative/RelativeGeometry.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>

namespace
{
using namespace esif;
using namespace esif::dslam;
using namespace esif::relative;

using esif::dslam::cases::kSigmaF;
using esif::dslam::cases::kSigmaR;
using esif::dslam::cases::kSigmaT;
using esif::dslam::cases::twoFeatureCase;

TEST(KidnappedRobot, HandComputedTwoFeatureCase)
{
	const auto in = twoFeatureCase();
	const GaussianState s = solveKidnappedRobot(in);
	// Exact measurements at the truth: the mean is the truth.
	EXPECT_LT(s.mean.head<3>().norm(), 1e-12);
	EXPECT_LT((s.mean.tail<4>() - in.features).norm(), 1e-12);

	// Jacobians at the truth, written out by hand for h = (r, atan2(dy, dx) - phi):
	//   f1 (dx, dy) = (2, 0):  dr  = [-1  0  0 |  1  0]    dth = [0 -1/2 -1 | 0 1/2]
	//   f2 (dx, dy) = (0, 2):  dr  = [ 0 -1  0 |  0  1]    dth = [1/2 0 -1 | -1/2 0]
	Eigen::MatrixXd H = Eigen::MatrixXd::Zero(4, 7);
	H.row(0) << -1, 0, 0, 1, 0, 0, 0;
	H.row(1) << 0, -0.5, -1, 0, 0.5, 0, 0;
	H.row(2) << 0, -1, 0, 0, 0, 0, 1;
	H.row(3) << 0.5, 0, -1, 0, 0, -0.5, 0;
	const Eigen::Vector4d r_inv(1 / (kSigmaR * kSigmaR), 1 / (kSigmaT * kSigmaT), 1 / (kSigmaR * kSigmaR),
								1 / (kSigmaT * kSigmaT));
	Eigen::MatrixXd info = H.transpose() * r_inv.asDiagonal() * H;
	info.bottomRightCorner(4, 4) += Eigen::MatrixXd::Identity(4, 4) / (kSigmaF * kSigmaF);
	const Eigen::MatrixXd expected = info.inverse();
	// Both are inverses of the same 7x7 matrix (condition < 1e5): 1e-9 relative.
	EXPECT_LT((s.cov - expected).norm(), 1e-9 * expected.norm());
	// And a plain check of the physics: the robot is no better known than a
	// feature it is located from, nor worse than features + one range.
	EXPECT_GT(s.cov(0, 0), kSigmaF * kSigmaF / 2);
	EXPECT_LT(s.cov(0, 0), kSigmaF * kSigmaF + kSigmaR * kSigmaR);
}

TEST(KidnappedRobot, OneStepFromASmallPerturbationAndTooFewFeatures)
{
	auto in = twoFeatureCase();
	in.initial_robot = Pose2(0.01, -0.01, 0.5 * M_PI / 180);
	const GaussianState s = solveKidnappedRobot(in);
	// One linearised step from 1 cm / 0.5 deg: the error left is second order (< 1e-3).
	EXPECT_LT(s.mean.head<3>().norm(), 1e-3);

	in.z_loc.pop_back();
	in.features.conservativeResize(2);
	in.features_cov = in.features_cov.topLeftCorner(2, 2).eval();
	EXPECT_THROW(solveKidnappedRobot(in), NumericalError);
}

TEST(CovarianceIntersection, SymmetricCaseHasOmegaOneHalf)
{
	// trace P_CI(w) = 1/(w + (1-w)/4) + 1/(w/4 + (1-w)) + 1 is symmetric
	// about w = 1/2, its minimum; there P_CI = diag(1.6, 1.6, 1) and
	// x_CI = P_CI (0.5 P1^-1 x1 + 0.5 P2^-1 x2).
	const GaussianState a{Eigen::Vector3d(1, 2, 0.1), Eigen::Vector3d(1, 4, 1).asDiagonal().toDenseMatrix()};
	const GaussianState b{Eigen::Vector3d(3, -2, 0.3), Eigen::Vector3d(4, 1, 1).asDiagonal().toDenseMatrix()};
	const CiResult ci = covarianceIntersection(a, b);
	EXPECT_NEAR(ci.omega, 0.5, 1e-4);  // Brent's tolerance is 2^-20 in w; the trace is flat at its minimum
	const Eigen::Vector3d diag(1.6, 1.6, 1.0);
	EXPECT_LT((ci.fused.cov.diagonal() - diag).norm(), 1e-6);
	const Eigen::Vector3d x(1.6 * (0.5 * 1 + 0.125 * 3), 1.6 * (0.125 * 2 + 0.5 * -2), 0.5 * 0.1 + 0.5 * 0.3);
	EXPECT_LT((ci.fused.mean - x).norm(), 1e-5);
}

TEST(CovarianceIntersection, DominantEstimateWinsAndHeadingsWrap)
{
	const GaussianState a{Eigen::Vector3d(1, 1, 179 * M_PI / 180), 0.01 * Eigen::Matrix3d::Identity()};
	const GaussianState b{Eigen::Vector3d(2, 2, -179 * M_PI / 180), 1.0 * Eigen::Matrix3d::Identity()};
	const CiResult ci = covarianceIntersection(a, b);
	EXPECT_NEAR(ci.omega, 1.0, 1e-4);
	EXPECT_LT((ci.fused.mean.head<2>() - a.mean.head<2>()).norm(), 1e-3);
	// Fused near +-180 deg, never near 0 (what averaging raw angles gives).
	EXPECT_GT(std::abs(ci.fused.mean(2)), 178 * M_PI / 180);
}

TEST(CovarianceIntersection, RobotMarginalReplacementKeepsTheConditional)
{
	Eigen::MatrixXd A = Eigen::MatrixXd::Random(5, 5);
	const GaussianState s{Eigen::VectorXd::Random(5), A * A.transpose() + 0.5 * Eigen::MatrixXd::Identity(5, 5)};
	EXPECT_LT((withLeadingMarginal(s, robotMarginal(s)).cov - s.cov).norm(), 1e-12);

	GaussianState robot{s.mean.head<3>() + Eigen::Vector3d(0.2, -0.1, 0.05), 0.5 * s.cov.topLeftCorner<3, 3>()};
	const GaussianState t = withLeadingMarginal(s, robot);
	const Eigen::MatrixXd K = s.cov.bottomLeftCorner(2, 3) * s.cov.topLeftCorner<3, 3>().inverse();
	EXPECT_LT((t.mean.tail<2>() - (s.mean.tail<2>() + K * Eigen::Vector3d(0.2, -0.1, 0.05))).norm(), 1e-12);
	const auto conditional = [](const Eigen::MatrixXd& P) {
		return (P.bottomRightCorner(2, 2) - P.bottomLeftCorner(2, 3) * P.topLeftCorner<3, 3>().inverse() *
												 P.topRightCorner(3, 2))
			.eval();
	};
	EXPECT_LT((conditional(t.cov) - conditional(s.cov)).norm(), 1e-10);
	EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(t.cov).eigenvalues().minCoeff(), 0.0);
}

TEST(RelativeGeometry, RobotAndNewFeatureRoundTrips)
{
	// A robot at (3, -1, 40 deg) sees f1, f2, f3; z_rob and z_map from its
	// frame give back its pose (eq. 3.18) and f3 (eq. 3.14) in the map frame.
	const Pose2 robot(3, -1, 40 * M_PI / 180);
	const Eigen::Vector2d f1(5, 2), f2(1, 4), f3(6, -3);
	const auto inRobot = [&](const Eigen::Vector2d& f) { return transformPoint(inverseCompose(robot, Pose2::Zero()), f); };
	const Eigen::Vector3d z_rob = robotRelativeToPair(inRobot(f1), inRobot(f2));
	EXPECT_LT((robotFromPair(f1, f2, z_rob) - robot).norm(), 1e-12);
	Eigen::VectorXd pts(6);
	pts << inRobot(f1), inRobot(f2), inRobot(f3);
	const auto z = relativeGeometry(pts);
	EXPECT_LT((featureFromPair(f1, f2, z.value(2), z.value(1)) - f3).norm(), 1e-12);
}

TEST(RelativeGeometry, JacobiansMatchCentralDifferences)
{
	// Central differences with h = 1e-6 on O(1) m geometry: truncation
	// ~h^2 and round-off ~1e-16 / h, so agreement to 1e-7 is expected.
	for (int m : {2, 3, 6})
	{
		Eigen::VectorXd xy = 5 * Eigen::VectorXd::Random(2 * m);
		xy.segment<2>(2) += Eigen::Vector2d(3, 3);	// keep f2 away from f1
		std::vector<int> angles;
		for (int r = 1; r < 2 * m - 3; r += 2) angles.push_back(r);
		const auto g = [](const Eigen::VectorXd& p) { return relativeGeometry(p).value; };
		EXPECT_LT((relativeGeometry(xy).jacobian - test::numericJacobian(g, xy, 1e-6, angles)).norm(), 1e-7) << m;
	}
	// T1 with a sensor offset: covariance carried by dT1.
	const Pose2 sensor(0.3, -0.1, 0.2);
	const Eigen::VectorXd z = (Eigen::VectorXd(4) << 3, 0.4, 5, -1.2).finished();
	const Eigen::MatrixXd R = Eigen::Vector4d(0.01, 1e-4, 0.02, 3e-4).asDiagonal();
	const auto t1 = [&](const Eigen::VectorXd& v) { return pointsInRobotFrame(v, R, sensor).xy; };
	const Eigen::MatrixXd J = test::numericJacobian(t1, z);
	EXPECT_LT((pointsInRobotFrame(z, R, sensor).cov - J * R * J.transpose()).norm(), 1e-9);
}

}  // namespace
