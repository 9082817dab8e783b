// Odometry from velocity commands (VelocityOdometry.h): exact arcs, and each
// term of the velocity-model covariance against what it stands for: the
// constant speed and turn-rate errors against finite differences of the
// integration, the random walks against their closed forms on a straight
// drive and a turn in place.

#include <NumericJacobian.h>

#include <esif/core/Errors.h>
#include <esif/models/VelocityOdometry.h>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>

namespace
{
using namespace esif;

/// A drive with curves, a stop and a reverse turn: 7.5 s of commands.
std::vector<VelocitySegment> wiggle()
{
	return {{1.5, 0.2, 0.0}, {2.0, 0.15, 0.4}, {0.5, 0.0, 0.0}, {1.0, 0.1, -0.6}, {2.5, 0.25, 0.1}};
}

/// Only the one noise term `set` turns on (and a negligible floor).
VelocityNoise only(void (*set)(VelocityNoise&))
{
	VelocityNoise n{1e-12, 0, 0, 0, 0, 0};
	set(n);
	return n;
}

TEST(VelocityOdometry, ArcsAreExact)
{
	// An eighth of a circle of radius 2 m: 0.5 m/s for pi s at 0.25 rad/s.
	const Pose2 end = integrateVelocity({{M_PI, 0.5, 0.25}});
	EXPECT_NEAR(end.x(), 2.0 * std::sin(M_PI / 4), 1e-12);
	EXPECT_NEAR(end.y(), 2.0 * (1 - std::cos(M_PI / 4)), 1e-12);
	EXPECT_NEAR(end.z(), M_PI / 4, 1e-12);
	// Sub-steps do not change the mean: the same arc in 1000 pieces.
	const auto inc = velocityOdometry({{M_PI, 0.5, 0.25}}, VelocityNoise{}, M_PI / 1000);
	EXPECT_NEAR(inc.delta.x(), end.x(), 1e-12);
	EXPECT_NEAR(inc.delta.y(), end.y(), 1e-12);
	EXPECT_NEAR(inc.delta(2), end.z(), 1e-12);
	// Standing still: no motion; the floor and the random walks (the white
	// noise is on the speed whatever is commanded), no constant-error term.
	const VelocityNoise n;
	const auto still = velocityOdometry({{2.0, 0, 0}}, n);
	EXPECT_EQ(still.delta.x(), 0.0);
	EXPECT_NEAR(still.cov(0, 0), n.floor_m * n.floor_m + n.speed_psd * 2.0, 1e-15);
	EXPECT_NEAR(still.cov(1, 1), n.floor_m * n.floor_m, 1e-15);
	EXPECT_NEAR(still.cov(2, 2), n.turn_psd * 2.0, 1e-15);
}

/// The constant-error terms are (b * mean)^2 J J^T with J the derivative of
/// the end pose by a constant speed (turn-rate) offset: checked against
/// central differences of the integration with the offset added.
TEST(VelocityOdometry, ConstantErrorTermsMatchFiniteDifferences)
{
	const auto segments = wiggle();
	double duration = 0, distance = 0, turn = 0;
	for (const auto& s : segments)
	{
		duration += s.duration_s;
		distance += s.duration_s * s.v_mps;
		turn += s.duration_s * s.w_radps;
	}
	const auto offset = [&](int which) {
		return [&, which](const Eigen::VectorXd& e) -> Eigen::VectorXd {
			auto shifted = segments;
			for (auto& s : shifted) (which == 0 ? s.v_mps : s.w_radps) += e(0);
			return integrateVelocity(shifted);
		};
	};
	const Eigen::Vector3d j_v = test::numericJacobian(offset(0), Eigen::VectorXd::Zero(1), 1e-6, {2});
	const Eigen::Vector3d j_w = test::numericJacobian(offset(1), Eigen::VectorXd::Zero(1), 1e-6, {2});

	const auto speed = velocityOdometry(segments, only([](VelocityNoise& n) { n.speed_scale = 0.1; }), 1e-3);
	const Eigen::Matrix3d expected_v = std::pow(0.1 * distance / duration, 2) * j_v * j_v.transpose();
	EXPECT_LT((speed.cov - expected_v).cwiseAbs().maxCoeff(), 1e-4 * expected_v.cwiseAbs().maxCoeff())
		<< speed.cov << "\nvs\n"
		<< expected_v;
	const auto rate = velocityOdometry(segments, only([](VelocityNoise& n) { n.turn_scale = 0.2; }), 1e-3);
	const Eigen::Matrix3d expected_w = std::pow(0.2 * turn / duration, 2) * j_w * j_w.transpose();
	EXPECT_LT((rate.cov - expected_w).cwiseAbs().maxCoeff(), 1e-4 * expected_w.cwiseAbs().maxCoeff())
		<< rate.cov << "\nvs\n"
		<< expected_w;
}

/// White noise on the speed of a straight drive is a random walk along it
/// (variance q T); on the turn rate of a turn in place, in heading (r T),
/// with r = r0 + r1 |w|; a turn-rate random walk on a straight drive of
/// length L gives the lateral variance r0 * v^2 T^3 / 3.
TEST(VelocityOdometry, RandomWalksHaveTheirClosedForms)
{
	const auto straight = velocityOdometry({{4.0, 0.5, 0.0}}, only([](VelocityNoise& n) { n.speed_psd = 1e-4; }));
	EXPECT_NEAR(straight.cov(0, 0), 1e-4 * 4.0, 1e-12);
	EXPECT_NEAR(straight.cov(1, 1), 0.0, 1e-12);
	const auto spin = velocityOdometry(
		{{3.0, 0.0, 0.5}}, only([](VelocityNoise& n) {
			n.turn_psd = 2e-4;
			n.turn_psd_per_rate = 0.01;
		}));
	EXPECT_NEAR(spin.cov(2, 2), (2e-4 + 0.01 * 0.5) * 3.0, 1e-12);
	const auto lateral =
		velocityOdometry({{4.0, 0.5, 0.0}}, only([](VelocityNoise& n) { n.turn_psd = 1e-3; }), 1e-3);
	EXPECT_NEAR(lateral.cov(1, 1), 1e-3 * 0.25 * 64.0 / 3.0, 1e-6);
	EXPECT_NEAR(lateral.cov(1, 2), 1e-3 * 0.5 * 16.0 / 2.0, 1e-6);
	EXPECT_NEAR(lateral.cov(2, 2), 1e-3 * 4.0, 1e-12);
}

TEST(VelocityOdometry, TheCovarianceIsSymmetricPositiveDefiniteAndGrowsWithTime)
{
	const VelocityNoise noise;
	double previous_trace = 0;
	for (const double seconds : {0.001, 0.25, 1.0, 10.0, 78.0})
	{
		const auto inc = velocityOdometry({{seconds, 0.08, 0.2}}, noise);
		EXPECT_EQ((inc.cov - inc.cov.transpose()).norm(), 0.0);
		EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inc.cov).eigenvalues().minCoeff(), 0.0) << seconds;
		EXPECT_GT(inc.cov.trace(), previous_trace) << seconds;
		previous_trace = inc.cov.trace();
	}
}

TEST(VelocityOdometry, BadParametersNameTheFlag)
{
	VelocityNoise n;
	n.turn_scale = -1;
	try
	{
		n.validate("import mrclam");
		FAIL();
	}
	catch (const ConfigError& e)
	{
		EXPECT_STREQ(e.what(), "import mrclam: --odometry-turn-scale = -1: must be in [0, 1000]");
	}
	n = VelocityNoise{};
	n.floor_m = 0;
	EXPECT_THROW(n.validate("x"), ConfigError);
	n.floor_m = std::nan("");
	EXPECT_THROW(n.validate("x"), ConfigError);
	// A subnormal floor passes "> 0" but squares to zero: a singular covariance.
	n.floor_m = 1e-320;
	EXPECT_THROW(n.validate("x"), ConfigError);
	n = VelocityNoise{};
	// Without white turn-rate noise a straight step has no heading variance at all.
	n.turn_psd = 0;
	EXPECT_THROW(n.validate("x"), ConfigError);
	n.turn_psd = kMinTurnPsd;
	n.floor_m = kMinOdometryFloor_m;
	EXPECT_NO_THROW(n.validate("x"));
}

}  // namespace
