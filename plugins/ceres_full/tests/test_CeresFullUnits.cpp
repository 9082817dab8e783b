// The full-SLAM terms and graph on hand-made cases: residuals against the
// framework's range-bearing model and against finite differences, the
// square-root information, the J^T J non-zero count against the evaluated
// Jacobian, the marginal covariances against a dense inverse, the re-solve
// schedule's sizes and the checks of a solution (a pose collapsed onto a
// landmark, an implausible chi-square).

#include "FullSlamGraph.h"
#include "MarginalCovariances.h"
#include "Residuals.h"
#include "SolutionChecks.h"
#include "SolveSchedule.h"

#include <NumericJacobian.h>

#include <esif/core/Errors.h>
#include <esif/models/RangeBearingModel.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

namespace
{
using namespace esif;
using namespace esif::ceres_full;

/// Residual and Jacobians (column-major, one per block) of a cost function.
struct Evaluated
{
	Eigen::VectorXd r;
	std::vector<Eigen::MatrixXd> jacobians;
};

Evaluated evaluate(const ceres::CostFunction& f, const std::vector<const double*>& blocks)
{
	Evaluated e;
	e.r.resize(f.num_residuals());
	std::vector<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> rm;
	std::vector<double*> jac;
	for (std::size_t i = 0; i < blocks.size(); ++i)
		rm.emplace_back(f.num_residuals(), f.parameter_block_sizes()[i]);
	for (auto& m : rm) jac.push_back(m.data());
	EXPECT_TRUE(f.Evaluate(blocks.data(), e.r.data(), jac.data()));
	for (const auto& m : rm) e.jacobians.emplace_back(m);
	return e;
}

Eigen::Matrix2d randomCov(std::mt19937& rng)
{
	std::uniform_real_distribution<double> u(-1, 1);
	Eigen::Matrix2d a;
	a << u(rng), u(rng), u(rng), u(rng);
	return a * a.transpose() * 0.01 + Eigen::Matrix2d::Identity() * 1e-3;
}

TEST(CeresFullResiduals, SqrtInformationWhitensWithoutInverting)
{
	Eigen::Matrix3d cov;
	cov << 0.04, 0.01, 0.002, 0.01, 0.09, -0.003, 0.002, -0.003, 0.01;
	Eigen::Matrix3d w;
	ASSERT_TRUE(sqrtInformation<3>(cov, w));
	EXPECT_TRUE((w.transpose() * w * cov).isApprox(Eigen::Matrix3d::Identity(), 1e-12));
	EXPECT_FALSE(sqrtInformation<3>(Eigen::Matrix3d::Zero(), w));
	Eigen::Matrix3d indefinite = Eigen::Vector3d(1, -1, 1).asDiagonal();
	EXPECT_FALSE(sqrtInformation<3>(indefinite, w));
	Eigen::Matrix3d nan = cov;
	nan(1, 1) = std::nan("");
	EXPECT_FALSE(sqrtInformation<3>(nan, w));
}

TEST(CeresFullResiduals, RangeBearingMatchesTheFrameworkModelAndItsJacobians)
{
	// The residual is W (h - z) with h and its Jacobians from eq. 1.6 as the
	// EKF uses them; bearings straddle +-pi to exercise the wrap.
	std::mt19937 rng(7);
	std::uniform_real_distribution<double> u(-1, 1);
	for (int trial = 0; trial < 200; ++trial)
	{
		const Pose2 robot(5 * u(rng), 5 * u(rng), M_PI * u(rng));
		const Pose2 sensor(0.3 * u(rng), 0.2 * u(rng), 0.5 * u(rng));
		const Eigen::Vector2d lm(robot.head<2>() + Eigen::Vector2d(4 * u(rng), 4 * u(rng)));
		const auto h = predictRangeBearing(robot, sensor, lm);
		const Eigen::Vector2d z(h.z.x() + 0.05 * u(rng), wrapAngle(h.z.y() + 0.05 * u(rng)));
		Eigen::Matrix2d w;
		ASSERT_TRUE(sqrtInformation<2>(randomCov(rng), w));
		const std::unique_ptr<ceres::CostFunction> f(RangeBearingResidual::create(z, w, sensor));
		const auto e = evaluate(*f, {robot.data(), lm.data()});
		const Eigen::Vector2d innovation(h.z.x() - z.x(), wrapAngle(h.z.y() - z.y()));
		EXPECT_TRUE(e.r.isApprox(w * innovation, 1e-9)) << e.r.transpose() << " vs " << (w * innovation).transpose();
		EXPECT_TRUE(e.jacobians[0].isApprox(w * h.d_robot, 1e-9));
		EXPECT_TRUE(e.jacobians[1].isApprox(w * h.d_landmark, 1e-9));
	}
}

TEST(CeresFullResiduals, OdometryIsTheWhitenedNoiseAndItsJacobianMatchesFiniteDifferences)
{
	std::mt19937 rng(3);
	std::uniform_real_distribution<double> u(-1, 1);
	for (int trial = 0; trial < 200; ++trial)
	{
		const Pose2 a(10 * u(rng), 10 * u(rng), M_PI * u(rng));
		const Pose2 delta(0.5 * u(rng), 0.1 * u(rng), 0.3 * u(rng));
		const Eigen::Vector3d noise(0.02 * u(rng), 0.02 * u(rng), 0.02 * u(rng));
		// Pose b = a (+) (delta + noise): the residual must be W noise.
		const Pose2 b = compose(a, delta + noise);
		Eigen::Matrix3d cov = Eigen::Vector3d(4e-4, 2e-4, 1e-4).asDiagonal();
		cov(0, 1) = cov(1, 0) = 5e-5;
		Eigen::Matrix3d w;
		ASSERT_TRUE(sqrtInformation<3>(cov, w));
		const std::unique_ptr<ceres::CostFunction> f(OdometryResidual::create(delta, w));
		const auto e = evaluate(*f, {a.data(), b.data()});
		EXPECT_TRUE(e.r.isApprox(w * noise, 1e-9)) << e.r.transpose();

		const auto residual_of = [&](const Eigen::VectorXd& ab) -> Eigen::VectorXd
		{
			const Eigen::Vector3d pa = ab.head<3>(), pb = ab.tail<3>();
			Eigen::VectorXd r(3);
			const std::unique_ptr<ceres::CostFunction> g(OdometryResidual::create(delta, w));
			const double* blocks[] = {pa.data(), pb.data()};
			g->Evaluate(blocks, r.data(), nullptr);
			return r;
		};
		Eigen::VectorXd ab(6);
		ab << a, b;
		const Eigen::MatrixXd numeric = test::numericJacobian(residual_of, ab, 1e-6);
		EXPECT_TRUE(e.jacobians[0].isApprox(numeric.leftCols(3), 1e-6));
		EXPECT_TRUE(e.jacobians[1].isApprox(numeric.rightCols(3), 1e-6));
	}
}

TEST(CeresFullResiduals, HeadingResidualWrapsAcrossPi)
{
	// Poses at +179 deg and -179 deg differ by 2 deg, not -358 deg.
	const double deg = M_PI / 180;
	const Pose2 a(0, 0, M_PI - deg), b(0, 0, -M_PI + deg);
	const std::unique_ptr<ceres::CostFunction> f(
		OdometryResidual::create(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()));
	const auto e = evaluate(*f, {a.data(), b.data()});
	EXPECT_NEAR(e.r.z(), 2 * deg, 1e-12);
}

/// A small graph: a square loop of 8 poses seeing 4 landmarks.
FullSlamGraph smallGraph()
{
	FullSlamGraph g;
	OdometryIncrement odo;
	odo.delta = {1.0, 0.0, M_PI / 4};
	odo.cov = Eigen::Vector3d(1e-3, 1e-3, 1e-4).asDiagonal();
	const std::vector<Eigen::Vector2d> lms = {{0.5, 1.5}, {1.5, 0.5}, {-0.5, 1}, {1, 2.5}};
	for (std::size_t i = 0; i < lms.size(); ++i) g.addLandmark(static_cast<LandmarkId>(10 + i), lms[i]);
	std::size_t pose = 0;
	for (int k = 0; k < 8; ++k)
	{
		if (k > 0) pose = g.addPose(pose, odo, compose(g.pose(pose), odo.delta), "odometry");
		for (std::size_t i = 0; i < lms.size(); ++i)
		{
			if ((k + i) % 3 == 0) continue;	 // not every landmark from every pose
			const auto h = predictRangeBearing(g.pose(pose), Pose2::Zero(), lms[i]);
			RangeBearing m;
			m.range_m = h.z.x() + 0.01;
			m.bearing_rad = h.z.y() - 0.005;
			m.cov = Eigen::Vector2d(1e-2, 3e-4).asDiagonal();
			g.addObservation(pose, static_cast<LandmarkId>(10 + i), m, Pose2::Zero(), "measurement");
		}
	}
	return g;
}

TEST(CeresFullGraph, CountsAndNonZerosMatchTheEvaluatedJacobian)
{
	FullSlamGraph g = smallGraph();
	EXPECT_EQ(g.poseCount(), 8u);
	EXPECT_EQ(g.parameterDim(), 7u * 3 + 4 * 2);
	// 7 odometry terms, and 8 poses x 4 landmarks minus the skipped pairs.
	std::size_t observations = 0;
	for (int k = 0; k < 8; ++k)
		for (int i = 0; i < 4; ++i) observations += (k + i) % 3 != 0;
	EXPECT_EQ(g.residualDim(), 7u * 3 + 2 * observations);
	// Counted from the block structure vs Ceres' evaluated Jacobian.
	const auto info = g.informationMatrix(1);
	EXPECT_EQ(g.informationNonZeros(), static_cast<std::size_t>(info.nonZeros()));
}

TEST(CeresFullGraph, MarginalCovariancesEqualTheDenseInverseOfJtJ)
{
	FullSlamGraph g = smallGraph();
	const Eigen::MatrixXd dense_cov = Eigen::MatrixXd(g.informationMatrix(1)).inverse();  // tiny: 29 x 29
	std::vector<const double*> blocks;
	for (const LandmarkId id : g.landmarkIds()) blocks.push_back(g.landmarkBlock(id));
	blocks.push_back(g.poseBlock(7));
	const auto marginals = marginalCovariances(g.problem(), blocks, 1);
	// Landmark l's block sits after the 7 non-gauge poses.
	for (std::size_t l = 0; l < 4; ++l)
		EXPECT_TRUE(marginals.at(blocks[l]).isApprox(dense_cov.block<2, 2>(21 + 2 * l, 21 + 2 * l), 1e-8)) << l;
	EXPECT_TRUE(marginals.at(blocks[4]).isApprox(dense_cov.block<3, 3>(18, 18), 1e-8));
}

TEST(CeresFullGraph, BadCovariancesNameTheTerm)
{
	FullSlamGraph g;
	OdometryIncrement odo;
	odo.cov = Eigen::Matrix3d::Zero();
	odo.delta = {1, 0, 0};
	try
	{
		g.addPose(0, odo, Pose2(1, 0, 0), "odometry");
		FAIL() << "no error";
	}
	catch (const NumericalError& e)
	{
		EXPECT_STREQ(e.what(), "odometry: covariance is not symmetric positive definite");
	}
	g.addLandmark(1, {1, 1});
	RangeBearing m;
	m.range_m = 1;
	m.cov << 1, 2, 2, 1;  // indefinite
	EXPECT_THROW(g.addObservation(0, 1, m, Pose2::Zero(), "measurement 0"), NumericalError);
	EXPECT_EQ(g.residualDim(), 0u);
}

TEST(CeresFullSchedule, GrowthRuleGivesGeometricSolveSizesAndAboutLinearTotalWork)
{
	// 10 % growth, at least 20 new poses: solves at 20, 40, ..., 200, then
	// x1.1. Over 10,000 poses the solved sizes sum to about (1 + 1/g) N = 11 N
	// (the geometric series), not the N^2 / (2K) of a fixed every-K rule.
	SolveSchedule s(0.1, 20, 0);
	std::vector<std::size_t> sizes;
	for (std::size_t poses = 1; poses <= 10000; ++poses)
		if (s.due(poses, poses))
		{
			sizes.push_back(poses);
			s.solved(poses);
		}
	ASSERT_GE(sizes.size(), 10u);
	EXPECT_EQ(sizes[0], 20u);
	EXPECT_EQ(sizes[9], 200u);
	EXPECT_EQ(sizes[10], 220u);
	for (std::size_t i = 10; i < sizes.size(); ++i)
		EXPECT_EQ(sizes[i] - sizes[i - 1], static_cast<std::size_t>(std::ceil(0.1 * sizes[i - 1]))) << i;
	const double total = std::accumulate(sizes.begin(), sizes.end(), 0.0);
	EXPECT_LT(total, 11.0 * 10000);
	EXPECT_GT(total, 9.0 * 10000);	// the last solve is within 10 % of N: the series sums to ~10 N
	// 10 solves up to 200 poses, then 40 of x1.1 (rounded up) to 9221:
	// ln(9221 / 200) / ln(1.1) = 40.2.
	EXPECT_EQ(sizes.size(), 50u);
	EXPECT_EQ(sizes.back(), 9221u);

	// The fixed rule: every K steps regardless of poses; growth 0 disables the other.
	SolveSchedule every(0, 20, 100);
	EXPECT_TRUE(every.due(100, 3));
	EXPECT_FALSE(every.due(150, 150));
	SolveSchedule never(0, 20, 0);
	EXPECT_FALSE(never.due(1000, 1000));
}

/// One pose at `robot` seeing landmark 1 at `landmark` with measured range `range`.
FullSlamGraph onePoseOneLandmark(const Pose2& robot, const Eigen::Vector2d& landmark, double range)
{
	FullSlamGraph g;
	OdometryIncrement odo;
	odo.delta = {robot.x(), robot.y(), robot.z()};
	odo.cov = Eigen::Vector3d(1e-2, 1e-2, 1e-3).asDiagonal();
	const std::size_t pose = g.addPose(0, odo, robot, "odometry");
	g.addLandmark(1, landmark);
	RangeBearing m;
	m.range_m = range;
	m.cov = Eigen::Vector2d(0.01, 3e-4).asDiagonal();
	g.addObservation(pose, 1, m, Pose2::Zero(), "measurement");
	return g;
}

TEST(CeresFullChecks, APoseOnALandmarkItMeasuredMetresAwayIsDegenerate)
{
	const Pose2 robot(2, 1, 0.3);
	// The case: 1e-9 m apart, measured at 3.5 m.
	EXPECT_EQ(countDegeneratePoses(onePoseOneLandmark(robot, robot.head<2>() + Eigen::Vector2d(1e-9, 0), 3.5), 0.05), 1u);
	// At the measured range: not degenerate.
	EXPECT_EQ(countDegeneratePoses(onePoseOneLandmark(robot, robot.head<2>() + Eigen::Vector2d(0, 3.5), 3.5), 0.05), 0u);
	// Close, and measured close within 5 range sigmas (0.1 m here): a robot
	// passing a feature, not a collapse; beyond 5 sigmas it is one.
	const Eigen::Vector2d near = robot.head<2>() + Eigen::Vector2d(0.03, 0);
	EXPECT_EQ(countDegeneratePoses(onePoseOneLandmark(robot, near, 0.08), 0.05), 0u);
	EXPECT_EQ(countDegeneratePoses(onePoseOneLandmark(robot, near, 0.52), 0.05), 0u);
	EXPECT_EQ(countDegeneratePoses(onePoseOneLandmark(robot, near, 0.54), 0.05), 1u);
	// Just outside the distance: not degenerate.
	EXPECT_EQ(countDegeneratePoses(onePoseOneLandmark(robot, robot.head<2>() + Eigen::Vector2d(0.051, 0), 3.5), 0.05), 0u);
}

TEST(CeresFullChecks, ACollapsedPoseMakesTheMarginalCovariancesFail)
{
	// The limit of the failure: 1e-9 m apart, the bearing term's
	// derivatives are ~1e9 times the others' (whether Ceres' rank test then
	// fails depends on the problem's size); exactly on the landmark they are
	// 0 / 0, and the covariances cannot be computed at all.
	const Pose2 robot(2, 1, 0.3);
	FullSlamGraph g = onePoseOneLandmark(robot, robot.head<2>(), 3.5);
	EXPECT_EQ(countDegeneratePoses(g, 0.05), 1u);
	EXPECT_THROW(marginalCovariances(g.problem(), {g.landmarkBlock(1), g.poseBlock(1)}, 1), NumericalError);
}

TEST(CeresFullChecks, ChiSquarePerDofAboveTheThresholdOrADegeneratePoseIsImplausible)
{
	EXPECT_TRUE(checkSolution(1100, 1000, 0, 3).plausible);
	EXPECT_NEAR(checkSolution(1100, 1000, 0, 3).chi2PerDof(), 1.1, 1e-12);
	const auto high = checkSolution(7000, 1000, 0, 3);
	EXPECT_FALSE(high.plausible);
	EXPECT_NE(high.warning(3).find("chi2 / dof = 7"), std::string::npos) << high.warning(3);
	const auto collapsed = checkSolution(1000, 1000, 2, 3);
	EXPECT_FALSE(collapsed.plausible);
	EXPECT_NE(collapsed.warning(3).find("2 pose(s) on a landmark"), std::string::npos) << collapsed.warning(3);
	EXPECT_EQ(collapsed.warning(3).find('\n'), std::string::npos);	 // one line
	// No redundancy: chi2 / dof undefined, nothing to judge by.
	EXPECT_TRUE(std::isnan(checkSolution(0, 0, 0, 3).chi2PerDof()));
	EXPECT_TRUE(checkSolution(0, 0, 0, 3).plausible);
	EXPECT_TRUE(checkSolution(1, 1, 0, 3).warning(3).empty());
}

}  // namespace
