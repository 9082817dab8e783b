// The EKF core's sparse-Jacobian update against the textbook dense form of
// eq. (1.8)-(1.10), on a small map where the dense form is cheap.

#include "EkfCoreFixture.h"

#include <esif/core/Errors.h>
#include <esif/ekf/EkfSlamCore.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

namespace
{
using namespace esif;

using test::kSensor;

EkfSlamCore buildCore() { return test::coreWithThreeLandmarks(); }

/// Dense H (2m x n) for the given matches.
Eigen::MatrixXd denseH(const EkfSlamCore& core, const std::vector<EkfSlamCore::Match>& matches)
{
	Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2 * matches.size(), core.stateDim());
	for (std::size_t j = 0; j < matches.size(); ++j)
	{
		const auto h = core.predictMeasurement(matches[j].landmark, kSensor);
		H.block<2, 3>(2 * j, 0) = h.d_robot;
		H.block<2, 2>(2 * j, 3 + 2 * matches[j].landmark) = h.d_landmark;
	}
	return H;
}

TEST(EkfSlamCore, PredictionMatchesDenseForm)
{
	EkfSlamCore core = buildCore();
	const Eigen::MatrixXd P0 = core.covariance();
	const Pose2 x0 = core.robot();
	OdometryIncrement u;
	u.delta = {0.3, -0.2, 0.5};
	u.cov = Eigen::Vector3d(0.02, 0.01, 0.004).asDiagonal();
	core.predict(u);

	const auto J = composeJacobians(x0, u.delta);
	Eigen::MatrixXd F = Eigen::MatrixXd::Identity(P0.rows(), P0.cols());
	F.topLeftCorner<3, 3>() = J.d_a;
	Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(P0.rows(), P0.cols());
	Q.topLeftCorner<3, 3>() = J.d_b * u.cov * J.d_b.transpose();
	const Eigen::MatrixXd expected = F * P0 * F.transpose() + Q;
	EXPECT_LT((Eigen::MatrixXd(core.covariance()) - expected).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(EkfSlamCore, BatchUpdateMatchesDenseForm)
{
	EkfSlamCore core = buildCore();
	const Eigen::VectorXd x0 = core.state();
	const Eigen::MatrixXd P0 = core.covariance();
	const Eigen::Matrix2d R = Eigen::Vector2d(0.01, 0.0004).asDiagonal();
	std::vector<EkfSlamCore::Match> matches;
	for (std::size_t i : {0u, 2u})
	{
		const auto h = core.predictMeasurement(i, kSensor);
		matches.push_back({i, h.z + Eigen::Vector2d(0.05, -0.01), R});
	}
	const Eigen::MatrixXd H = denseH(core, matches);
	Eigen::VectorXd nu(4);
	for (std::size_t j = 0; j < 2; ++j)
		nu.segment<2>(2 * j) = matches[j].z - core.predictMeasurement(matches[j].landmark, kSensor).z;
	Eigen::MatrixXd S = H * P0 * H.transpose();
	S.block<2, 2>(0, 0) += R;
	S.block<2, 2>(2, 2) += R;
	const Eigen::MatrixXd K = P0 * H.transpose() * S.inverse();	 // dense reference only

	core.update(matches, kSensor);
	const Eigen::VectorXd x_expected = x0 + K * nu;
	const Eigen::MatrixXd P_expected = P0 - K * S * K.transpose();
	EXPECT_LT((Eigen::VectorXd(core.state()) - x_expected).cwiseAbs().maxCoeff(), 1e-10);
	EXPECT_LT((Eigen::MatrixXd(core.covariance()) - P_expected).cwiseAbs().maxCoeff(), 1e-10);
	// Exactly symmetric, and still positive definite.
	const Eigen::MatrixXd P = core.covariance();
	EXPECT_EQ((P - P.transpose()).cwiseAbs().maxCoeff(), 0.0);
	EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(P).info(), Eigen::Success);
}

TEST(EkfSlamCore, NewLandmarkCovarianceMatchesDenseForm)
{
	EkfSlamCore core = buildCore();
	const Eigen::MatrixXd P0 = core.covariance();
	const Eigen::Matrix2d R = Eigen::Vector2d(0.01, 0.0004).asDiagonal();
	const Eigen::Vector2d z(2.5, 0.3);
	const auto g = landmarkFromRangeBearing(core.robot(), kSensor, z(0), z(1));
	core.addLandmark(z, R, kSensor);

	const auto n = P0.rows();
	Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n + 2, n);
	G.topRows(n).setIdentity();
	G.block<2, 3>(n, 0) = g.d_robot;
	Eigen::MatrixXd expected = G * P0 * G.transpose();
	expected.bottomRightCorner<2, 2>() += g.d_measurement * R * g.d_measurement.transpose();
	EXPECT_LT((Eigen::MatrixXd(core.covariance()) - expected).cwiseAbs().maxCoeff(), 1e-12);
	EXPECT_LT((core.landmark(3) - g.position).norm(), 1e-12);
}

TEST(EkfSlamCore, NonPositiveDefiniteInnovationIsANumericalError)
{
	EkfSlamCore core = buildCore();
	const Eigen::Matrix2d bad = Eigen::Vector2d(-10.0, -10.0).asDiagonal();
	const auto h = core.predictMeasurement(0, kSensor);
	EXPECT_THROW(core.update({{0, h.z, bad}}, kSensor), NumericalError);
}

TEST(EkfSlamCore, GrowsBeyondInitialCapacity)
{
	EkfSlamCore core;
	const Eigen::Matrix2d R = Eigen::Vector2d(0.01, 0.0004).asDiagonal();
	for (int i = 0; i < 100; ++i) core.addLandmark({1.0 + 0.01 * i, 0.01 * i}, R, kSensor);
	EXPECT_EQ(core.landmarkCount(), 100u);
	EXPECT_EQ(core.stateDim(), 203u);
	EXPECT_NEAR(core.landmark(99).x(), kSensor.x() + 1.99 * std::cos(kSensor.z() + 0.99), 1e-12);
}

}  // namespace
