#include <NumericJacobian.h>

#include <esif/models/Se2.h>

#include <gtest/gtest.h>
#include <cmath>

namespace
{
using namespace esif;

TEST(Se2, WrapAngleIsHalfOpen)
{
	EXPECT_DOUBLE_EQ(wrapAngle(M_PI), M_PI);
	EXPECT_DOUBLE_EQ(wrapAngle(-M_PI), M_PI);
	EXPECT_NEAR(wrapAngle(3 * M_PI + 0.1), -M_PI + 0.1, 1e-12);
	EXPECT_NEAR(wrapAngle(-0.3 - 4 * M_PI), -0.3, 1e-12);
}

TEST(Se2, ComposeThenInverseComposeIsIdentity)
{
	const Pose2 a(1.0, -2.0, 2.5), b(0.3, 0.7, -3.0);
	const Pose2 c = compose(a, b);
	const Pose2 back = inverseCompose(a, c);
	EXPECT_NEAR((back - b).head<2>().norm(), 0, 1e-12);
	EXPECT_NEAR(wrapAngle(back(2) - b(2)), 0, 1e-12);
}

TEST(Se2, ComposeJacobiansMatchFiniteDifferences)
{
	const Pose2 a(1.0, -2.0, 2.9), b(0.3, 0.7, 0.4);
	const auto J = composeJacobians(a, b);
	const auto num_a = test::numericJacobian(
		[&](const Eigen::VectorXd& x) -> Eigen::VectorXd { return compose(Pose2(x), b); }, a, 1e-6, {2});
	const auto num_b = test::numericJacobian(
		[&](const Eigen::VectorXd& x) -> Eigen::VectorXd { return compose(a, Pose2(x)); }, b, 1e-6, {2});
	// Central differences of smooth trigonometric functions with h = 1e-6
	// are accurate to ~1e-9; 1e-7 leaves room without hiding a wrong term.
	EXPECT_LT((J.d_a - num_a).cwiseAbs().maxCoeff(), 1e-7);
	EXPECT_LT((J.d_b - num_b).cwiseAbs().maxCoeff(), 1e-7);
}

TEST(Se2, TransformPointAgreesWithCompose)
{
	const Pose2 a(1.0, -2.0, 1.1);
	const Eigen::Vector2d p(0.5, 2.0);
	EXPECT_LT((transformPoint(a, p) - compose(a, Pose2(p.x(), p.y(), 0)).head<2>()).norm(), 1e-12);
}

}  // namespace
