// The full-SLAM terms and graph on hand-made cases: residuals against the
// framework's range-bearing model and against finite differences, the
// square-root information, the J^T J non-zero count against the evaluated
// Jacobian, and the marginal covariances against a dense inverse.

#include "FullSlamGraph.h"
#include "MarginalCovariances.h"
#include "Residuals.h"

#include <NumericJacobian.h>

#include <esif/core/Errors.h>
#include <esif/models/RangeBearingModel.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <gtest/gtest.h>

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
		if (k > 0) pose = g.addPose(pose, odo, compose(g.pose(pose), toPose2(odo.delta)), "odometry");
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

}  // namespace
