// First-estimates Jacobians (JacobianPoints::FirstEstimates in EkfSlamCore):
// (1) the core's prediction, update and landmark initialisation against the
// textbook dense forms with Jacobians taken by finite differences at the FEJ
// points; (2) what FEJ is for: a prior variance of the global rotation is
// carried through a whole run unchanged (nothing is learnt about the
// unobservable rotation), where the plain EKF shrinks it; (3) the FEJ points
// under retainLandmarks and setState.

#include <NumericJacobian.h>

#include <esif/ekf/EkfSlamCore.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>
#include <random>

namespace
{
using namespace esif;

const Pose2 kSensor(0.2, 0.05, 0.1);
constexpr double kDeg = M_PI / 180.0;
/// The book's sensor noise (Sec. 1.3.3): 0.1 m range, 1 deg bearing.
const Eigen::Matrix2d kR = Eigen::Vector2d(0.01, std::pow(1 * kDeg, 2)).asDiagonal();

/// Central differences (NumericJacobian.h) with step 1e-6: the truncation
/// error is ~1e-12 times the third derivative (<= 1/range^2 ~ 0.1 here) and
/// the round-off ~1e-16 / 1e-6 = 1e-10.
constexpr double kStep = 1e-6;

/// The range-bearing Jacobians at (robot, landmark) by central differences.
Eigen::Matrix<double, 2, 5> numericMeasurementJacobian(const Pose2& robot, const Eigen::Vector2d& landmark)
{
	Eigen::VectorXd at(5);
	at << robot, landmark;
	const auto h = [](const Eigen::VectorXd& v) -> Eigen::VectorXd {
		return predictRangeBearing(v.head<3>(), kSensor, v.tail<2>()).z;
	};
	return test::numericJacobian(h, at, kStep, {1});
}

/// An FEJ core whose robot prior differs from its estimate (an update moved
/// it) and whose landmarks moved from their first estimates: where FEJ and
/// the textbook Jacobians differ.
EkfSlamCore movedFejCore()
{
	EkfSlamCore core(JacobianPoints::FirstEstimates);
	OdometryIncrement u;
	u.delta = {0.5, 0.1, 0.2};
	u.cov = Eigen::Vector3d(0.01, 0.02, 0.003).asDiagonal();
	core.predict(u);
	core.addLandmark({3.0, 0.4}, kR, kSensor);
	core.predict(u);
	core.addLandmark({2.0, -0.7}, kR, kSensor);
	core.addLandmark({4.0, 1.2}, kR, kSensor);
	for (int k = 0; k < 3; ++k) core.predict(u);
	std::vector<EkfSlamCore::Match> matches;
	for (std::size_t i : {0u, 2u})
		matches.push_back({i, core.predictMeasurement(i, kSensor).z + Eigen::Vector2d(0.3, 0.05), kR});
	core.update(matches, kSensor);
	return core;
}

/// Round-off of the dense references below on covariances of order 1: the
/// finite-difference errors above (1e-10) times entries of P up to ~10.
constexpr double kDenseTolerance = 1e-8;

TEST(FirstEstimatesJacobians, SetUpMovesTheEstimatesOffTheFejPoints)
{
	// Otherwise the tests below could not tell FEJ from the textbook EKF.
	const EkfSlamCore core = movedFejCore();
	EXPECT_GT((core.robot().head<2>() - core.robotPrior().head<2>()).norm(), 0.05);
	EXPECT_GT((core.landmark(0) - core.landmarkFirstEstimate(0)).norm(), 0.05);
}

TEST(FirstEstimatesJacobians, PredictionUsesTheMotionJacobianAtTheRobotPrior)
{
	EkfSlamCore core = movedFejCore();
	const Eigen::MatrixXd P0 = core.covariance();
	const Pose2 prior = core.robotPrior(), updated = core.robot();
	OdometryIncrement u;
	u.delta = {0.3, -0.2, 0.5};
	u.cov = Eigen::Vector3d(0.02, 0.01, 0.004).asDiagonal();
	core.predict(u);
	const Pose2 next = core.robot();
	EXPECT_LT((next - compose(updated, u.delta)).cwiseAbs().maxCoeff(), 1e-12);
	EXPECT_EQ(core.robotPrior(), next);

	// FEJ's F = [I, J (p_{k+1|k} - p_{k|k-1}); 0, 1] is the motion model's
	// Jacobian at the prior x_{k|k-1} for the motion carrying it to x_{k+1|k}.
	const Pose2 motion_from_prior = inverseCompose(prior, next);
	const Eigen::Matrix3d F = test::numericJacobian(
		[&](const Eigen::VectorXd& a) -> Eigen::VectorXd { return compose(a, motion_from_prior); }, prior, kStep, {2});
	Eigen::MatrixXd Fn = Eigen::MatrixXd::Identity(P0.rows(), P0.cols());
	Fn.topLeftCorner<3, 3>() = F;
	Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(P0.rows(), P0.cols());
	const Eigen::Matrix3d G = composeJacobians(updated, u.delta).d_b;  // noise Jacobian: at x_{k|k}
	Q.topLeftCorner<3, 3>() = G * u.cov * G.transpose();
	const Eigen::MatrixXd expected = Fn * P0 * Fn.transpose() + Q;
	EXPECT_LT((Eigen::MatrixXd(core.covariance()) - expected).cwiseAbs().maxCoeff(), kDenseTolerance);

	// ...and not the textbook Jacobian at x_{k|k}.
	Fn.topLeftCorner<3, 3>() = composeJacobians(updated, u.delta).d_a;
	const Eigen::MatrixXd textbook = Fn * P0 * Fn.transpose() + Q;
	EXPECT_GT((Eigen::MatrixXd(core.covariance()) - textbook).cwiseAbs().maxCoeff(), 1e-4);
}

TEST(FirstEstimatesJacobians, UpdateUsesTheMeasurementJacobianAtPriorAndFirstEstimates)
{
	EkfSlamCore core = movedFejCore();
	OdometryIncrement u;
	u.delta = {0.4, 0.0, 0.1};
	u.cov = Eigen::Vector3d(0.01, 0.01, 0.002).asDiagonal();
	core.predict(u);
	// A second update at the same step: the robot moves off its prior again.
	std::vector<EkfSlamCore::Match> first = {{1, core.predictMeasurement(1, kSensor).z + Eigen::Vector2d(-0.2, 0.03), kR}};
	core.update(first, kSensor);
	ASSERT_GT((core.robot().head<2>() - core.robotPrior().head<2>()).norm(), 0.01);

	const Eigen::VectorXd x0 = core.state();
	const Eigen::MatrixXd P0 = core.covariance();
	std::vector<EkfSlamCore::Match> matches;
	for (std::size_t i : {0u, 1u, 2u})
		matches.push_back({i, core.predictMeasurement(i, kSensor).z + Eigen::Vector2d(0.05, -0.01 * i), kR});

	Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2 * matches.size(), x0.size());
	Eigen::VectorXd nu(2 * matches.size());
	for (std::size_t j = 0; j < matches.size(); ++j)
	{
		const std::size_t i = matches[j].landmark;
		const auto HJ = numericMeasurementJacobian(core.robotPrior(), core.landmarkFirstEstimate(i));
		H.block<2, 3>(2 * j, 0) = HJ.leftCols<3>();
		H.block<2, 2>(2 * j, 3 + 2 * i) = HJ.rightCols<2>();
		// The innovation at the current estimate.
		nu.segment<2>(2 * j) = matches[j].z - predictRangeBearing(x0.head<3>(), kSensor, x0.segment<2>(3 + 2 * i)).z;
	}
	Eigen::MatrixXd S = H * P0 * H.transpose();
	for (std::size_t j = 0; j < matches.size(); ++j) S.block<2, 2>(2 * j, 2 * j) += kR;
	// The association input is the covariance the update assumes.
	EXPECT_LT((core.predictionCovariance({0, 1, 2}, kSensor) - H * P0 * H.transpose()).cwiseAbs().maxCoeff(),
			  kDenseTolerance);
	const Eigen::MatrixXd K = P0 * H.transpose() * S.inverse();	 // dense reference only

	core.update(matches, kSensor);
	const Eigen::VectorXd x_expected = x0 + K * nu;
	const Eigen::MatrixXd P_expected = P0 - K * S * K.transpose();
	EXPECT_LT((Eigen::VectorXd(core.state()) - x_expected).cwiseAbs().maxCoeff(), kDenseTolerance);
	EXPECT_LT((Eigen::MatrixXd(core.covariance()) - P_expected).cwiseAbs().maxCoeff(), kDenseTolerance);
	EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(Eigen::MatrixXd(core.covariance())).info(), Eigen::Success);
}

TEST(FirstEstimatesJacobians, NewLandmarkIsLinearisedAboutTheRobotPrior)
{
	EkfSlamCore core = movedFejCore();
	const Eigen::MatrixXd P0 = core.covariance();
	const Eigen::Vector2d z(2.5, 0.3);
	const Eigen::Vector2d position = landmarkFromRangeBearing(core.robot(), kSensor, z(0), z(1)).position;
	const std::size_t i = core.addLandmark(z, kR, kSensor);
	EXPECT_LT((core.landmark(i) - position).norm(), 1e-12);	// the value from the current estimate...
	EXPECT_EQ(core.landmarkFirstEstimate(i), core.landmark(i));	 // ...is the first estimate

	// G_x: the inverse model's Jacobian at the robot prior, for the
	// measurement of the new landmark's position from there.
	const Pose2 prior = core.robotPrior();
	const Eigen::Vector2d z_prior = predictRangeBearing(prior, kSensor, position).z;
	const Eigen::Matrix<double, 2, 3> Gx = test::numericJacobian(
		[&](const Eigen::VectorXd& r) -> Eigen::VectorXd {
			return landmarkFromRangeBearing(r, kSensor, z_prior(0), z_prior(1)).position;
		},
		prior, kStep);
	const auto Gz = landmarkFromRangeBearing(core.robot(), kSensor, z(0), z(1)).d_measurement;
	const auto n = P0.rows();
	Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n + 2, n);
	G.topRows(n).setIdentity();
	G.block<2, 3>(n, 0) = Gx;
	Eigen::MatrixXd expected = G * P0 * G.transpose();
	expected.bottomRightCorner<2, 2>() += Gz * kR * Gz.transpose();
	EXPECT_LT((Eigen::MatrixXd(core.covariance()) - expected).cwiseAbs().maxCoeff(), kDenseTolerance);
}

TEST(FirstEstimatesJacobians, IteratedUpdateMovesTheMeanButUpdatesPAtTheFejPoints)
{
	// Robot 1.2 m and 6 deg off the prior: the FEJ linear model misses, the
	// update is iterated (Gauss-Newton at the iterates) for the mean, while
	// P gets the FEJ linearisation's reduction, so the null space survives.
	EkfSlamCore plain = movedFejCore();
	const Pose2 truth = plain.robot() + Pose2(-1.0, 0.6, 6 * kDeg);
	std::vector<EkfSlamCore::Match> matches;
	for (std::size_t i = 0; i < 3; ++i)
		matches.push_back({i, predictRangeBearing(truth, kSensor, plain.landmark(i)).z, kR});
	EkfSlamCore iterated = plain;
	plain.update(matches, kSensor);
	const auto outcome = iterated.update(matches, kSensor, IteratedUpdate{10, 1.0, 1e-6});
	ASSERT_GT(outcome.linearisations, 1);
	EXPECT_GT((Eigen::VectorXd(iterated.state()) - Eigen::VectorXd(plain.state())).cwiseAbs().maxCoeff(), 0.01);
	EXPECT_LT((Eigen::MatrixXd(iterated.covariance()) - Eigen::MatrixXd(plain.covariance())).cwiseAbs().maxCoeff(),
			  1e-12);
}

TEST(FirstEstimatesJacobians, RetainLandmarksKeepsFirstEstimatesAndSetStateResetsThem)
{
	EkfSlamCore core = movedFejCore();
	const Pose2 prior = core.robotPrior();
	const Eigen::Vector2d first0 = core.landmarkFirstEstimate(0), first2 = core.landmarkFirstEstimate(2);
	core.retainLandmarks({2, 0});
	ASSERT_EQ(core.landmarkCount(), 2u);
	EXPECT_EQ(core.landmarkFirstEstimate(0), first2);
	EXPECT_EQ(core.landmarkFirstEstimate(1), first0);
	EXPECT_EQ(core.robotPrior(), prior);

	Eigen::VectorXd x = core.state();
	x.segment<2>(3) += Eigen::Vector2d(1.0, -2.0);
	x(0) += 0.5;
	core.setState(x, core.covariance());
	EXPECT_EQ(core.robotPrior(), Pose2(x.head<3>()));
	EXPECT_EQ(core.landmarkFirstEstimate(0), Eigen::Vector2d(x.segment<2>(3)));
	EXPECT_EQ(core.landmarkFirstEstimate(1), Eigen::Vector2d(x.segment<2>(5)));
}

TEST(FirstEstimatesJacobians, CurrentIsTheDefault)
{
	EXPECT_EQ(EkfSlamCore().jacobianPoints(), JacobianPoints::Current);
}

// ---------------------------------------------------------------------------
// The unobservable rotation.
//
// Two filters see the same simulated run: one starts with the robot pose
// known exactly (P0 = 0), the other with a heading variance sigma0^2 about
// the origin. No relative measurement can tell the second anything about
// that initial heading: in the linearised system that is H n = 0 along the
// rotation direction n = [J p_R; 1; J p_L1; ...] of the linearisation
// points. If the Jacobians keep that null space (FEJ), P n is invisible to
// every gain (P H^T is the same in both filters), so both produce the same
// estimates, and the second's covariance exceeds the first's by exactly
// sigma0^2 n n^T at every step: the prior's rotation uncertainty, carried
// along and never reduced. The textbook EKF gains spurious information
// along n and shrinks it.

struct TwinFilters
{
	EkfSlamCore known_start;
	EkfSlamCore uncertain_heading;
};

constexpr double kSigma0 = 5 * kDeg;

/// The rotation direction at the FEJ points of `core`.
Eigen::VectorXd rotationDirectionAtFejPoints(const EkfSlamCore& core)
{
	Eigen::VectorXd n(core.stateDim());
	const Eigen::Vector2d p = core.robotPrior().head<2>();
	n.head<3>() << -p.y(), p.x(), 1;
	for (std::size_t i = 0; i < core.landmarkCount(); ++i)
	{
		const Eigen::Vector2d l = core.landmarkFirstEstimate(i);
		n.segment<2>(3 + 2 * i) << -l.y(), l.x();
	}
	return n;
}

/// Two laps of a 5 m circle among 16 landmarks, measurements within 6 m,
/// noisy odometry (5 cm and 1 deg per 0.25 m step) and measurements (kR);
/// landmarks matched by their index. Returns both filters at the end.
TwinFilters simulate(JacobianPoints points)
{
	TwinFilters run{EkfSlamCore(points), EkfSlamCore(points)};
	Eigen::MatrixXd P0 = Eigen::MatrixXd::Zero(3, 3);
	P0(2, 2) = kSigma0 * kSigma0;
	run.uncertain_heading.setState(Eigen::VectorXd::Zero(3), P0);

	std::vector<Eigen::Vector2d> landmarks;
	for (int i = 0; i < 16; ++i)
	{
		const double a = 2 * M_PI * i / 16, radius = (i % 2) ? 8.0 : 2.5;
		landmarks.emplace_back(radius * std::sin(a), 5 - radius * std::cos(a));
	}
	std::mt19937 rng(7);
	std::normal_distribution<double> normal;
	const Eigen::Vector3d odo_sigma(0.05, 0.05, 1 * kDeg);
	OdometryIncrement u;
	u.cov = odo_sigma.cwiseAbs2().asDiagonal();
	const Pose2 step_truth(0.25, 0, 0.25 / 5.0);
	Pose2 truth = Pose2::Zero();
	std::map<int, std::size_t> index_of;
	const int steps = static_cast<int>(std::ceil(2 * 2 * M_PI * 5 / 0.25));
	for (int k = 0; k < steps; ++k)
	{
		truth = compose(truth, step_truth);
		Pose2 odo = step_truth;
		for (int c = 0; c < 3; ++c) odo(c) += odo_sigma(c) * normal(rng);
		u.delta = odo;
		std::vector<EkfSlamCore::Match> matches;
		std::vector<std::pair<int, Eigen::Vector2d>> fresh;
		for (int i = 0; i < static_cast<int>(landmarks.size()); ++i)
		{
			Eigen::Vector2d z = predictRangeBearing(truth, kSensor, landmarks[i]).z;
			if (z(0) > 6.0) continue;
			z += Eigen::Vector2d(0.1 * normal(rng), 1 * kDeg * normal(rng));
			if (const auto it = index_of.find(i); it != index_of.end())
				matches.push_back({it->second, z, kR});
			else
				fresh.emplace_back(i, z);
		}
		for (EkfSlamCore* core : {&run.known_start, &run.uncertain_heading})
		{
			core->predict(u);
			core->update(matches, kSensor);
			for (const auto& [i, z] : fresh) index_of[i] = core->addLandmark(z, kR, kSensor);
		}
	}
	EXPECT_EQ(index_of.size(), landmarks.size());
	return run;
}

TEST(FirstEstimatesJacobians, PriorRotationVarianceIsCarriedThroughUnchanged)
{
	const TwinFilters run = simulate(JacobianPoints::FirstEstimates);
	const Eigen::VectorXd n = rotationDirectionAtFejPoints(run.uncertain_heading);
	const Eigen::MatrixXd gap =
		Eigen::MatrixXd(run.uncertain_heading.covariance()) - Eigen::MatrixXd(run.known_start.covariance());
	const Eigen::MatrixXd expected = kSigma0 * kSigma0 * n * n.transpose();
	// Round-off only: ~300 steps of updates on entries of order
	// sigma0^2 |n|^2 (|n| ~ 13 m): 1e-9 of that scale.
	const double scale = expected.cwiseAbs().maxCoeff();
	std::cout << "FEJ: covariance gap - sigma0^2 n n^T " << (gap - expected).cwiseAbs().maxCoeff() << " (scale "
			  << scale << "), heading variance gap / sigma0^2 " << gap(2, 2) / (kSigma0 * kSigma0) << "\n";
	EXPECT_LT((gap - expected).cwiseAbs().maxCoeff(), 1e-9 * scale);
	EXPECT_LT((Eigen::VectorXd(run.uncertain_heading.state()) - Eigen::VectorXd(run.known_start.state()))
				  .cwiseAbs()
				  .maxCoeff(),
			  1e-9);
	// Hence the heading variance exceeds the known start's by sigma0^2.
	EXPECT_NEAR(gap(2, 2), kSigma0 * kSigma0, 1e-9 * kSigma0 * kSigma0);
}

TEST(FirstEstimatesJacobians, TextbookEkfLearnsTheUnobservableRotation)
{
	const TwinFilters run = simulate(JacobianPoints::Current);
	const Eigen::MatrixXd gap =
		Eigen::MatrixXd(run.uncertain_heading.covariance()) - Eigen::MatrixXd(run.known_start.covariance());
	// The heading's prior variance is not carried through: the filter has
	// "learnt" the global rotation from relative measurements (on this run
	// 11% of sigma0^2 is left; FEJ keeps 100% to round-off, so any bound
	// well between the two separates them).
	std::cout << "textbook EKF: heading variance gap / sigma0^2 " << gap(2, 2) / (kSigma0 * kSigma0) << "\n";
	EXPECT_LT(gap(2, 2), 0.5 * kSigma0 * kSigma0);
}

}  // namespace
