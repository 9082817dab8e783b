// Unit tests of D-SLAM's building blocks (book: Wang, Huang, Dissanayake,
// "SLAM: Exactly Sparse Information Filters", Ch. 3), the plugin's own and
// those in the framework's relative/ room (1, 2, 7):
//   1. RelativeGeometry: T1 (eq. 3.4/3.7), T2 = H_map = G (eq. 3.8/3.13/3.40)
//      and its Jacobian, z_rob (eq. 3.3/3.6) and its inverse (eq. 3.18), new
//      feature placement (eq. 3.14);
//   2. ReferencePair: the choice of f1, f2;
//   3. KidnappedRobot: eq. (3.17)-(3.18) against a case worked out by hand;
//   4. CovarianceIntersection: eq. (3.20)-(3.21) and the robot-marginal
//      replacement;
//   5. LocalSlam: dropping / re-initialising features, reordering;
//   6. AdmissibleChain: the virtual observation (Sec. 3.4.1);
//   7. FeatureMap: anchor + relative update against a dense weighted least
//      squares solution, and withdrawal of the last update.
//
// The reference values are computed here independently of the code under
// test: the geometry by hand-written atan2/hypot helpers, Jacobians by
// central differences (NumericJacobian.h) or written out by hand.

#include "AdmissibleChain.h"
#include "CovarianceIntersection.h"
#include "KidnappedRobot.h"
#include "KidnappedTestCase.h"
#include "LocalSlam.h"

#include <array>
#include <cmath>
#include <ostream>
#include <random>
#include <vector>

#include <NumericJacobian.h>
#include <esif/core/Errors.h>
#include <esif/relative/FeatureMap.h>
#include <esif/relative/ReferencePair.h>
#include <esif/relative/RelativeGeometry.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

namespace esif
{
// Readable names for the parameterised map tests' failure messages.
inline void PrintTo(RecoveryMethod m, std::ostream* os) { *os << recoveryMethodName(m); }
}  // namespace esif

namespace
{
using namespace esif;
using namespace esif::dslam;
using namespace esif::relative;

constexpr double kDeg = M_PI / 180;

// ---------------------------------------------------------------------------
// Independent reference geometry (no plugin or framework code).

/// Angle wrapped to [-pi, pi] (std::remainder), enough for comparisons.
double wrap(double a) { return std::remainder(a, 2 * M_PI); }

Eigen::Matrix2d rot(double a)
{
	Eigen::Matrix2d R;
	R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
	return R;
}

/// Point p (given in the parent frame) expressed in `frame`.
Eigen::Vector2d toFrame(const Pose2& frame, const Eigen::Vector2d& p)
{
	return rot(frame.z()).transpose() * (p - frame.head<2>());
}

/// Point p (given in `frame`) expressed in the parent frame.
Eigen::Vector2d fromFrame(const Pose2& frame, const Eigen::Vector2d& p) { return frame.head<2>() + rot(frame.z()) * p; }

/// Sensor pose in the parent frame of the robot.
Pose2 sensorPose(const Pose2& robot, const Pose2& sensor)
{
	Pose2 s;
	s.head<2>() = fromFrame(robot, sensor.head<2>());
	s.z() = robot.z() + sensor.z();
	return s;
}

/// Eq. (1.6) by hand: (range, bearing) of f from the sensor on the robot.
Eigen::Vector2d rangeBearing(const Pose2& robot, const Pose2& sensor, const Eigen::Vector2d& f)
{
	const Pose2 s = sensorPose(robot, sensor);
	const Eigen::Vector2d d = f - s.head<2>();
	return {std::hypot(d.x(), d.y()), wrap(std::atan2(d.y(), d.x()) - s.z())};
}

/// Inverse of rangeBearing(): the feature from a measurement.
Eigen::Vector2d featureAt(const Pose2& robot, const Pose2& sensor, const Eigen::Vector2d& z)
{
	const Pose2 s = sensorPose(robot, sensor);
	return s.head<2>() + z(0) * Eigen::Vector2d(std::cos(s.z() + z(1)), std::sin(s.z() + z(1)));
}

/// Eq. (3.8)/(3.13) by hand: [d12, a312, d13, a412, d14, ...].
Eigen::VectorXd zMap(const Eigen::VectorXd& xy)
{
	const int m = static_cast<int>(xy.size() / 2);
	const Eigen::Vector2d f1 = xy.head<2>(), b = xy.segment<2>(2) - f1;
	Eigen::VectorXd z(2 * m - 3);
	z(0) = std::hypot(b.x(), b.y());
	for (int i = 2; i < m; ++i)
	{
		const Eigen::Vector2d v = xy.segment<2>(2 * i) - f1;
		z(2 * i - 3) = wrap(std::atan2(v.y(), v.x()) - std::atan2(b.y(), b.x()));
		z(2 * i - 2) = std::hypot(v.x(), v.y());
	}
	return z;
}

std::vector<int> angleRows(int m)
{
	std::vector<int> rows;
	for (int r = 1; r < 2 * m - 3; r += 2) rows.push_back(r);
	return rows;
}

Eigen::VectorXd stack(const std::vector<Eigen::Vector2d>& points)
{
	Eigen::VectorXd xy(2 * points.size());
	for (std::size_t i = 0; i < points.size(); ++i) xy.segment<2>(2 * i) = points[i];
	return xy;
}

/// A random symmetric positive definite matrix with eigenvalues in
/// [floor, floor + scale * n] (roughly), from a fixed-seed generator.
Eigen::MatrixXd randomSpd(int n, double scale, double floor, std::mt19937& rng)
{
	std::uniform_real_distribution<double> u(-1, 1);
	Eigen::MatrixXd A(n, n);
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j) A(i, j) = u(rng);
	return scale * A * A.transpose() + floor * Eigen::MatrixXd::Identity(n, n);
}

double relError(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).norm() / b.norm(); }

// ===========================================================================
// 1. RelativeGeometry

TEST(DslamUnitsRelativeGeometry, JacobianMatchesCentralDifferencesAtRandomConfigurations)
{
	// Tolerance: central differences with h = 1e-6 on points within 8 m of
	// the origin, every point at least 1 m from f1: truncation error
	// ~ h^2 |f'''| / 6 < 1e-12 (|f'''| ~ 2 / d^3 <= 2), round-off
	// ~ eps |f| / h ~ 1e-16 * 25 / 1e-6 ~ 3e-9. 1e-7 on every entry is well
	// above both and far below the O(1 / d) >= 0.04 of any wrong entry.
	std::mt19937 rng(20240611);
	std::uniform_real_distribution<double> u(-8, 8);
	for (int m : {2, 3, 6})
		for (int trial = 0; trial < 20; ++trial)
		{
			std::vector<Eigen::Vector2d> p(m);
			p[0] = {u(rng), u(rng)};
			for (int i = 1; i < m; ++i)
				do p[i] = {u(rng), u(rng)};
				while ((p[i] - p[0]).norm() < 1.0);	 // non-degenerate: no point at f1
			const Eigen::VectorXd xy = stack(p);
			const ValueJacobian g = relativeGeometry(xy);
			ASSERT_EQ(g.value.size(), 2 * m - 3);
			ASSERT_EQ(g.jacobian.rows(), 2 * m - 3);
			ASSERT_EQ(g.jacobian.cols(), 2 * m);
			// The value is eq. (3.8) (exact arithmetic up to a few ulps).
			EXPECT_LT(relativeDifference(g.value, zMap(xy)).cwiseAbs().maxCoeff(), 1e-12) << "m=" << m;
			const Eigen::MatrixXd num = test::numericJacobian(
				[](const Eigen::VectorXd& x) -> Eigen::VectorXd { return relativeGeometry(x).value; }, xy, 1e-6,
				angleRows(m));
			EXPECT_LT((g.jacobian - num).cwiseAbs().maxCoeff(), 1e-7) << "m=" << m << " trial " << trial;
		}
}

TEST(DslamUnitsRelativeGeometry, PointsInRobotFrameCarryCovarianceThroughT1)
{
	// A sensor mounted off-centre and yawed, three features, and a full
	// (virtual-observation-like) covariance of the stacked (r, theta).
	const Pose2 sensor(0.35, -0.2, 0.6);
	const Eigen::VectorXd z = (Eigen::VectorXd(6) << 3.0, 0.4, 5.0, -1.2, 2.2, 2.9).finished();
	std::mt19937 rng(7);
	const Eigen::MatrixXd R = randomSpd(6, 1e-3, 1e-4, rng);
	const PointSet p = pointsInRobotFrame(z, R, sensor);

	// Eq. (3.7) with the mounting: each point is the measurement seen from
	// the sensor pose, expressed in the robot frame. Exact up to round-off.
	for (int i = 0; i < 3; ++i)
		EXPECT_LT((p.point(i) - featureAt(Pose2::Zero(), sensor, z.segment<2>(2 * i))).norm(), 1e-12) << i;

	// cov = J R J^T with J the numeric Jacobian of T1 (of our own T1, the
	// function above): entries of J are ~1-5 with error ~ eps * 5 / h
	// ~ 5e-10, so J R J^T agrees to ~1e-9 relative; 1e-8 leaves margin.
	const auto t1 = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd
	{
		Eigen::VectorXd out(6);
		for (int i = 0; i < 3; ++i) out.segment<2>(2 * i) = featureAt(Pose2::Zero(), sensor, v.segment<2>(2 * i));
		return out;
	};
	const Eigen::MatrixXd J = test::numericJacobian(t1, z);
	EXPECT_LT(relError(p.cov, J * R * J.transpose()), 1e-8);
	EXPECT_LT((p.cov - p.cov.transpose()).norm(), 1e-15 * p.cov.norm() + 1e-300);
}

TEST(DslamUnitsRelativeGeometry, AngleEntriesWrapAcrossPi)
{
	// Baseline f1 -> f2 at +170 deg, f1 -> f3 at -170 deg: the raw difference
	// atan2(f3 - f1) - atan2(f2 - f1) = -340 deg; wrapped it is +20 deg.
	const Eigen::Vector2d f1(1, 2);
	const Eigen::Vector2d f2 = f1 + 4 * Eigen::Vector2d(std::cos(170 * kDeg), std::sin(170 * kDeg));
	const Eigen::Vector2d f3 = f1 + 3 * Eigen::Vector2d(std::cos(-170 * kDeg), std::sin(-170 * kDeg));
	const Eigen::VectorXd xy = stack({f1, f2, f3});
	const ValueJacobian g = relativeGeometry(xy);
	EXPECT_NEAR(g.value(0), 4.0, 1e-12);
	EXPECT_NEAR(g.value(1), 20 * kDeg, 1e-12);	// not -340 deg
	EXPECT_NEAR(g.value(2), 3.0, 1e-12);
	// The Jacobian is continuous across the wrap (tolerance as above).
	const Eigen::MatrixXd num = test::numericJacobian(
		[](const Eigen::VectorXd& x) -> Eigen::VectorXd { return relativeGeometry(x).value; }, xy, 1e-6, {1});
	EXPECT_LT((g.jacobian - num).cwiseAbs().maxCoeff(), 1e-7);

	// relativeDifference wraps the angle entries (odd indices) and only them:
	// 179 - (-179) deg = -2 deg, and distances of 7 m (> pi) stay as they are.
	const Eigen::Vector3d a(7.0, 179 * kDeg, 7.5), b(0.0, -179 * kDeg, 0.0);
	const Eigen::VectorXd d = relativeDifference(a, b);
	EXPECT_NEAR(d(0), 7.0, 1e-12);
	EXPECT_NEAR(d(1), -2 * kDeg, 1e-12);
	EXPECT_NEAR(d(2), 7.5, 1e-12);
	EXPECT_TRUE(isAngleEntry(1) && isAngleEntry(3) && !isAngleEntry(0) && !isAngleEntry(2));
}

TEST(DslamUnitsRelativeGeometry, RobotPoseRoundTripThroughZRob)
{
	// Eq. (3.3)/(3.6) then (3.18): the pose is recovered exactly (1e-12:
	// a dozen floating operations on O(10) numbers, errors ~1e-14).
	const Eigen::Vector2d f1(5, 2), f2(1, 4);
	for (const Pose2& robot : {Pose2(3, -1, 40 * kDeg), Pose2(-2, 4, 179.5 * kDeg), Pose2(0.5, 0.5, -179.5 * kDeg),
							   Pose2(8, 9, -95 * kDeg)})
	{
		const Eigen::Vector2d l1 = toFrame(robot, f1), l2 = toFrame(robot, f2);
		const Eigen::Vector3d z_rob = robotRelativeToPair(l1, l2);
		// d_1r is the distance robot - f1 (eq. 3.3, second row).
		EXPECT_NEAR(z_rob(1), (f1 - robot.head<2>()).norm(), 1e-12);
		const Pose2 back = robotFromPair(f1, f2, z_rob);
		EXPECT_LT((back.head<2>() - robot.head<2>()).norm(), 1e-12) << robot.transpose();
		EXPECT_LT(std::abs(wrap(back.z() - robot.z())), 1e-12) << robot.transpose();
	}
}

TEST(DslamUnitsRelativeGeometry, NewFeatureFromPairAndFrameInvariance)
{
	// Four map features seen from two different robot poses: z_map is the
	// same in the map frame and in both robot frames (distances and angles
	// among features do not depend on the frame), and eq. (3.14) puts f3
	// and f4 back at their map positions from (d_1i, a_i12).
	const std::vector<Eigen::Vector2d> map = {{5, 2}, {1, 4}, {6, -3}, {-2, -1}};
	const Eigen::VectorXd z_in_map = relativeGeometry(stack(map)).value;
	for (const Pose2& robot : {Pose2(3, -1, 40 * kDeg), Pose2(-4, 7, -170 * kDeg)})
	{
		std::vector<Eigen::Vector2d> local;
		for (const auto& f : map) local.push_back(toFrame(robot, f));
		const Eigen::VectorXd z = relativeGeometry(stack(local)).value;
		EXPECT_LT(relativeDifference(z, z_in_map).cwiseAbs().maxCoeff(), 1e-12) << robot.transpose();
		EXPECT_LT((featureFromPair(map[0], map[1], z(2), z(1)) - map[2]).norm(), 1e-12);
		EXPECT_LT((featureFromPair(map[0], map[1], z(4), z(3)) - map[3]).norm(), 1e-12);
	}
}

// ===========================================================================
// 2. ReferencePair

TEST(DslamUnitsReferencePair, PicksTheWidestWellConditionedPair)
{
	// Baselines: A-B 3.16, A-C 5.00, B-C 6.71 (the widest), B-D 3.51,
	// C-D 4.99; A-D 0.36 is below min_separation. B at -45 deg and C at
	// 104 deg subtend 149 deg at the robot: well conditioned.
	const std::vector<ReferenceCandidate> c = {
		{{3, 1}, 5}, {{2, -2}, 2}, {{-1, 4}, 9}, {{3.2, 1.3}, 0}};
	const auto p = chooseReferencePair(c, ReferenceRules{});
	ASSERT_TRUE(p.has_value());
	EXPECT_EQ(*p, std::make_pair(1, 2));  // B (order 2) is f1, C (order 9) is f2
}

TEST(DslamUnitsReferencePair, RejectsCloseAndCollinearPairs)
{
	const ReferenceRules rules;	 // 0.5 m, 5 deg
	// 0.36 m apart (and 6.5 deg apart at the robot): too close ...
	EXPECT_FALSE(chooseReferencePair({{{3, 1}, 0}, {{2.8, 1.3}, 1}}, rules).has_value());
	// ... but fine when the separation rule allows it.
	EXPECT_TRUE(chooseReferencePair({{{3, 1}, 0}, {{2.8, 1.3}, 1}}, {ReferencePolicy::Widest, 0.3, rules.min_angle_rad})
					.has_value());
	// 3 m apart but nearly in line with the robot on the same side (1.1 deg).
	EXPECT_FALSE(chooseReferencePair({{{2, 0}, 0}, {{5, 0.1}, 1}}, rules).has_value());
	// 6 m apart but on opposite sides, nearly in line (178.6 deg > 175 deg).
	EXPECT_FALSE(chooseReferencePair({{{2, 0.1}, 0}, {{-4, -0.1}, 1}}, rules).has_value());
	// With a third feature the widest (collinear) pair is skipped for the
	// widest well-conditioned one: (-4, -0.1) - (0, 3), 5.0 m.
	const auto p = chooseReferencePair({{{2, 0.1}, 0}, {{-4, -0.1}, 1}, {{0, 3}, 2}}, rules);
	ASSERT_TRUE(p.has_value());
	EXPECT_EQ(*p, std::make_pair(1, 2));

	// The angle limits themselves, 1 mrad on either side of each.
	const auto at = [](double angle) -> std::vector<ReferenceCandidate>
	{ return {{{2, 0}, 0}, {3 * Eigen::Vector2d(std::cos(angle), std::sin(angle)), 1}}; };
	EXPECT_TRUE(chooseReferencePair(at(rules.min_angle_rad + 1e-3), rules).has_value());
	EXPECT_FALSE(chooseReferencePair(at(rules.min_angle_rad - 1e-3), rules).has_value());
	EXPECT_TRUE(chooseReferencePair(at(M_PI - rules.min_angle_rad - 1e-3), rules).has_value());
	EXPECT_FALSE(chooseReferencePair(at(M_PI - rules.min_angle_rad + 1e-3), rules).has_value());
}

TEST(DslamUnitsReferencePair, FirstMappedPolicyPicksTheTwoEarliest)
{
	ReferenceRules rules;
	rules.policy = ReferencePolicy::FirstMapped;
	// Orders 7, 3, 12, 5, all pairs well conditioned: the earliest two are
	// index 1 (order 3, f1) and index 3 (order 5, f2), though not the widest.
	const std::vector<ReferenceCandidate> c = {{{6, 0}, 7}, {{2, 1}, 3}, {{-6, 3}, 12}, {{1, 2.5}, 5}};
	const auto p = chooseReferencePair(c, rules);
	ASSERT_TRUE(p.has_value());
	EXPECT_EQ(*p, std::make_pair(1, 3));
	// The simplest case: two features mapped first and second.
	const auto q = chooseReferencePair({{{3, 0}, 1}, {{0, 3}, 0}}, rules);
	ASSERT_TRUE(q.has_value());
	EXPECT_EQ(*q, std::make_pair(1, 0));
	// The earliest pair is ill-conditioned (collinear with the robot): the
	// next earliest well-conditioned pair, orders 0 and 2.
	const auto r = chooseReferencePair({{{2, 0}, 0}, {{5, 0.1}, 1}, {{0, 3}, 2}}, rules);
	ASSERT_TRUE(r.has_value());
	EXPECT_EQ(*r, std::make_pair(0, 2));
}

TEST(DslamUnitsReferencePair, NoneWithFewerThanTwoCandidates)
{
	for (auto policy : {ReferencePolicy::Widest, ReferencePolicy::FirstMapped})
	{
		ReferenceRules rules;
		rules.policy = policy;
		EXPECT_FALSE(chooseReferencePair({}, rules).has_value());
		EXPECT_FALSE(chooseReferencePair({{{3, 1}, 0}}, rules).has_value());
	}
}

TEST(DslamUnitsReferencePair, F1IsTheOneMappedEarlier)
{
	// Only one pair; whichever index comes first, f1 is the smaller order.
	const auto p = chooseReferencePair({{{0, 3}, 9}, {{3, 0}, 4}}, ReferenceRules{});
	ASSERT_TRUE(p.has_value());
	EXPECT_EQ(*p, std::make_pair(1, 0));
	const auto q = chooseReferencePair({{{3, 0}, 4}, {{0, 3}, 9}}, ReferenceRules{});
	ASSERT_TRUE(q.has_value());
	EXPECT_EQ(*q, std::make_pair(0, 1));
}

// ===========================================================================
// 3. Kidnapped robot, eq. (3.17)-(3.18)

using esif::dslam::cases::kSigmaF;
using esif::dslam::cases::kSigmaR;
using esif::dslam::cases::kSigmaT;
using esif::dslam::cases::twoFeatureCase;

TEST(DslamUnitsKidnappedRobot, HandComputedTwoFeatureCovariance)
{
	const KidnappedInput in = twoFeatureCase();
	const GaussianState s = solveKidnappedRobot(in);
	ASSERT_EQ(s.mean.size(), 7);
	// Exact measurements, linearised at the truth: the mean is the truth.
	// (Solving a 7x7 system of condition ~1e4: round-off ~1e-12.)
	EXPECT_LT(s.mean.head<3>().norm(), 1e-9);
	EXPECT_LT((s.mean.tail<4>() - in.features).norm(), 1e-9);

	// By hand. h = (r, atan2(dy, dx) - phi) with (dx, dy) = f - robot; at the
	// truth the Jacobians (rows r, theta; robot columns x, y, phi) are
	//   f1, (dx, dy) = (2, 0): H_r = [-1 0 0; 0 -1/2 -1], H_f1 = [1 0; 0 1/2]
	//   f2, (dx, dy) = (0, 2): H_r = [0 -1 0; 1/2 0 -1], H_f2 = [0 1; -1/2 0]
	// The robot has no prior, so its posterior information is that of
	// z = H_r x_r + (H_f x_f + w) with the features and noise marginalised:
	// S_i = sf^2 H_fi H_fi^T + R = diag(sf^2 + sr^2, sf^2 / 4 + st^2) for
	// both features (H_fi H_fi^T = diag(1, 1/4)). With a = 1/(sf^2 + sr^2),
	// b = 1/(sf^2/4 + st^2):
	//   Lambda_r = sum_i H_ri^T S_i^-1 H_ri
	//            = [ a + b/4   0        -b/2 ]
	//              [ 0         a + b/4   b/2 ]
	//              [ -b/2      b/2       2b  ]
	// Inverting by blocks, c = a + b/4, h = b/2, q = 2b - 2h^2/c:
	//   P_phiphi = 1/q,  P_(x,y),phi = (h, -h) / (c q),
	//   P_(x,y),(x,y) = I/c + [h^2 -h^2; -h^2 h^2] / (c^2 q).
	const double sf2 = kSigmaF * kSigmaF, sr2 = kSigmaR * kSigmaR, st2 = kSigmaT * kSigmaT;
	const double a = 1 / (sf2 + sr2), b = 1 / (sf2 / 4 + st2);
	const double c = a + b / 4, h = b / 2, q = 2 * b - 2 * h * h / c;
	Eigen::Matrix3d expected;
	expected << 1 / c + h * h / (c * c * q), -h * h / (c * c * q), h / (c * q),  //
		-h * h / (c * c * q), 1 / c + h * h / (c * c * q), -h / (c * q),  //
		h / (c * q), -h / (c * q), 1 / q;
	// Both sides are inverses of well-conditioned matrices (condition < 1e4):
	// they agree to ~1e-12 relative; 1e-9 leaves margin.
	EXPECT_LT(relError(s.cov.topLeftCorner<3, 3>(), expected), 1e-9);
	// Sanity of the hand algebra: expected is indeed Lambda_r^-1.
	Eigen::Matrix3d lambda;
	lambda << c, 0, -h, 0, c, h, -h, h, 2 * b;
	EXPECT_LT((lambda * expected - Eigen::Matrix3d::Identity()).norm(), 1e-12);
	// The covariance is symmetric positive definite.
	EXPECT_LT((s.cov - s.cov.transpose()).norm(), 1e-15 * s.cov.norm());
	EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(s.cov).eigenvalues().minCoeff(), 0.0);
}

TEST(DslamUnitsKidnappedRobot, SmallPerturbationConvergesInOneStep)
{
	KidnappedInput in = twoFeatureCase();
	in.initial_robot = Pose2(0.01, -0.01, 0.5 * kDeg);	// 1 cm / 0.5 deg off
	const GaussianState s = solveKidnappedRobot(in);
	// One linearised (Gauss-Newton) step leaves an error of second order in
	// the ~2 cm initial error at 2 m range: ~ (0.02)^2 / 2 = 2e-4 < 1e-3. A
	// step that did not move the robot would leave 0.01 m / 0.0087 rad.
	EXPECT_LT(s.mean.head<2>().norm(), 1e-3);
	EXPECT_LT(std::abs(s.mean(2)), 1e-3);
	EXPECT_LT((s.mean.tail<4>() - in.features).norm(), 1e-3);
}

TEST(DslamUnitsKidnappedRobot, GaussNewtonConvergesFromAFarStart)
{
	// The loop-closure case in miniature: eq. (3.18) starts the robot 1.5 m
	// and 30 deg off (its reference pair pairs an old feature with one
	// mapped metres off). With exact measurements the solution is the
	// truth (robot at the origin, features at the map's values).
	KidnappedInput in = twoFeatureCase();
	in.initial_robot = Pose2(1.0, -1.1, 30 * kDeg);
	const GaussianState one = solveKidnappedRobot(in);
	// The book's single step lands far off: its Jacobians are taken 30 deg
	// away, so the error left is of the order of the start's (measured:
	// about 0.5 m).
	EXPECT_GT(one.mean.head<2>().norm(), 0.1);
	in.iterations = 20;
	const GaussianState gn = solveKidnappedRobot(in);
	// Converged: the stopping rule is a step below 1 mm and 1e-6 rad, and
	// Gauss-Newton converges quadratically on this zero-residual problem,
	// so the last step's error is far below that.
	EXPECT_LT(gn.mean.head<2>().norm(), 1e-6);
	EXPECT_LT(std::abs(gn.mean(2)), 1e-6);
	EXPECT_LT((gn.mean.tail<4>() - in.features).norm(), 1e-6);
	// The covariance is the one at the truth (the hand-computed case above)
	// up to where the last step was linearised: the stopping rule leaves
	// that within 1 mm of the solution, which changes the Jacobians by at
	// most 1 mm / 2 m range = 5e-4 relative (measured: 3e-7).
	in.initial_robot = Pose2::Zero();
	in.iterations = 1;
	EXPECT_LT((gn.cov - solveKidnappedRobot(in).cov).norm(), 5e-4 * gn.cov.norm());
}

TEST(DslamUnitsKidnappedRobot, FitChi2IsTheNormalisedResidualsAndDeparture)
{
	KidnappedInput in = twoFeatureCase();
	// Exact measurements at the truth: zero cost, 2 m1 - 3 = 1 dof.
	GaussianState truth{Eigen::VectorXd::Zero(7), Eigen::MatrixXd::Identity(7, 7)};
	truth.mean.tail<4>() = in.features;
	EXPECT_LT(kidnappedFitChi2(in, truth), 1e-20);
	EXPECT_EQ(kidnappedFitDof(in), 1);
	// Move f1 by 2 sigma_f along x at the solution: its measurement is then
	// 2 sigma_f longer than predicted... the departure costs 4, the range
	// residual (2 sigma_f / sigma_r)^2, the bearing none (f1 stays on the
	// x axis).
	GaussianState moved = truth;
	moved.mean(3) += 2 * cases::kSigmaF;
	const double expected = 4.0 + std::pow(2 * cases::kSigmaF / cases::kSigmaR, 2);
	EXPECT_NEAR(kidnappedFitChi2(in, moved), expected, 1e-9 * expected);
}

TEST(DslamUnitsKidnappedRobot, FewerThanTwoFeaturesThrow)
{
	KidnappedInput in = twoFeatureCase();
	in.z_loc.pop_back();
	in.features.conservativeResize(2);
	in.features_cov = in.features_cov.topLeftCorner(2, 2).eval();
	EXPECT_THROW(solveKidnappedRobot(in), NumericalError);
	in.z_loc.clear();
	in.features.resize(0);
	in.features_cov.resize(0, 0);
	EXPECT_THROW(solveKidnappedRobot(in), NumericalError);
}

// ===========================================================================
// 4. Covariance intersection, eq. (3.20)-(3.21)

GaussianState state3(const Eigen::Vector3d& x, const Eigen::Vector3d& diag)
{
	return {x, diag.asDiagonal().toDenseMatrix()};
}

TEST(DslamUnitsCovarianceIntersection, SymmetricHandCase)
{
	// P1 = diag(1, 4, 1), P2 = diag(4, 1, 1):
	//   tr P_CI(w) = 1 / (w + (1 - w)/4) + 1 / (w/4 + 1 - w) + 1,
	// symmetric under w <-> 1 - w and convex, so w = 1/2. There
	//   P_CI = (0.5 P1^-1 + 0.5 P2^-1)^-1 = (diag(1/2 + 1/8, 1/8 + 1/2, 1))^-1
	//        = diag(1.6, 1.6, 1),
	//   x_CI = P_CI (0.5 P1^-1 x1 + 0.5 P2^-1 x2)
	//        = (1.6 (0.5 * 1 + 0.125 * 3), 1.6 (0.125 * 2 - 0.5 * 2), 0.5 * 0.1 + 0.5 * 0.3)
	//        = (1.4, -1.2, 0.2) for x1 = (1, 2, 0.1), x2 = (3, -2, 0.3).
	const CiResult ci = covarianceIntersection(state3({1, 2, 0.1}, {1, 4, 1}), state3({3, -2, 0.3}, {4, 1, 1}));
	// Brent stops within ~2^-19 of the minimiser; 1e-4 is the brief's bound.
	EXPECT_NEAR(ci.omega, 0.5, 1e-4);
	// An error dw in omega moves P_CI's diagonal by ~1.9 dw and x_CI by
	// ~3 dw; with dw ~ 2e-6, 1e-5 bounds both.
	EXPECT_LT((ci.fused.cov - Eigen::Vector3d(1.6, 1.6, 1.0).asDiagonal().toDenseMatrix()).norm(), 1e-5);
	EXPECT_LT((ci.fused.mean - Eigen::Vector3d(1.4, -1.2, 0.2)).norm(), 1e-5);
}

TEST(DslamUnitsCovarianceIntersection, MuchBetterEstimateWins)
{
	// P1 = 0.01 I << P2: d tr P_CI / dw < 0 on all of [0, 1], so w = 1 and
	// the result is (x1, P1). With w = 1 - dw, P_CI ~ P1 + dw (P1 - P1 P2^-1 P1):
	// relative error ~ dw < 1e-4; the mean moves by ~ dw P1 P2^-1 |x2 - x1|
	// < 1e-5.
	const GaussianState a = state3({1, 1, 0.2}, {0.01, 0.01, 0.01});
	const GaussianState b = state3({2, 3, -0.4}, {1, 2, 0.5});
	const CiResult ci = covarianceIntersection(a, b);
	EXPECT_NEAR(ci.omega, 1.0, 1e-4);
	EXPECT_LT(relError(ci.fused.cov, a.cov), 1e-4);
	EXPECT_LT((ci.fused.mean - a.mean).norm(), 1e-5);
	// Symmetric in the arguments: the good estimate second gives w = 0.
	const CiResult swapped = covarianceIntersection(b, a);
	EXPECT_NEAR(swapped.omega, 0.0, 1e-4);
	EXPECT_LT((swapped.fused.mean - a.mean).norm(), 1e-5);
}

TEST(DslamUnitsCovarianceIntersection, HeadingsWrapAcrossPi)
{
	// Headings +179 and -179 deg are 2 deg apart; with the symmetric
	// covariances above (w = 1/2, equal heading variances) the fused
	// heading is 180 deg, whereas averaging raw angles would give 0.
	// Error: 2 dw * 1 deg with dw < 1e-4: under 1e-5 rad.
	const CiResult ci =
		covarianceIntersection(state3({1, 2, 179 * kDeg}, {1, 4, 1}), state3({3, -2, -179 * kDeg}, {4, 1, 1}));
	EXPECT_LT(std::abs(wrap(ci.fused.mean(2) - M_PI)), 1e-5);
	EXPECT_LE(std::abs(ci.fused.mean(2)), M_PI);  // and reported wrapped
}

/// A 3 + 4 state (robot and two features) with a random SPD covariance.
GaussianState randomJointState(std::mt19937& rng)
{
	std::uniform_real_distribution<double> u(-3, 3);
	GaussianState s;
	s.mean.resize(7);
	for (int i = 0; i < 7; ++i) s.mean(i) = u(rng);
	s.cov = randomSpd(7, 0.1, 0.05, rng);
	return s;
}

Eigen::MatrixXd conditionalFeatures(const Eigen::MatrixXd& P)
{
	return P.bottomRightCorner(4, 4) -
		P.bottomLeftCorner(4, 3) * P.topLeftCorner<3, 3>().partialPivLu().solve(P.topRightCorner(3, 4));
}

TEST(DslamUnitsCovarianceIntersection, WithRobotMarginalSameMarginalIsIdentity)
{
	// Cancellation in P_ff - K P_rf + K P_rr K^T costs ~ eps * cond(P_rr)
	// (< 1e3 here): 1e-10 relative is comfortably above it.
	std::mt19937 rng(11);
	for (int trial = 0; trial < 5; ++trial)
	{
		const GaussianState s = randomJointState(rng);
		const GaussianState t = withLeadingMarginal(s, robotMarginal(s));
		EXPECT_LT((t.mean - s.mean).norm(), 1e-12);
		EXPECT_LT(relError(t.cov, s.cov), 1e-10);
	}
}

TEST(DslamUnitsCovarianceIntersection, WithRobotMarginalMovesFeaturesKeepsConditional)
{
	std::mt19937 rng(12);
	for (int trial = 0; trial < 5; ++trial)
	{
		GaussianState s = randomJointState(rng);
		s.mean(2) = 3.1;  // heading near +pi ...
		GaussianState robot{s.mean.head<3>(), 0.5 * s.cov.topLeftCorner<3, 3>()};
		robot.mean += Eigen::Vector3d(0.2, -0.1, 0);
		robot.mean(2) = -3.1;  // ... moved across it: dr_phi = 2 pi - 6.2 = +0.0832, not -6.2
		const Eigen::Vector3d dr(0.2, -0.1, 2 * M_PI - 6.2);
		const GaussianState t = withLeadingMarginal(s, robot);

		// Features move by P_fr P_rr^-1 dr (computed here by LU, not LLT).
		const Eigen::MatrixXd K =
			s.cov.bottomLeftCorner(4, 3) * s.cov.topLeftCorner<3, 3>().partialPivLu().inverse();
		EXPECT_LT((t.mean.tail<4>() - (s.mean.tail<4>() + K * dr)).norm(), 1e-10);
		EXPECT_LT((t.mean.head<2>() - robot.mean.head<2>()).norm(), 1e-12);
		EXPECT_LT(std::abs(wrap(t.mean(2) - robot.mean(2))), 1e-12);
		EXPECT_LT(relError(t.cov.topLeftCorner<3, 3>(), robot.cov), 1e-12);

		// Symmetric positive definite.
		EXPECT_LT((t.cov - t.cov.transpose()).norm(), 1e-15 * t.cov.norm());
		EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(t.cov).eigenvalues().minCoeff(), 0.0);
		// The conditional of the features given the robot is unchanged.
		EXPECT_LT(relError(conditionalFeatures(t.cov), conditionalFeatures(s.cov)), 1e-10);
	}
}

TEST(DslamUnitsCovarianceIntersection, WithLeadingMarginalOfRobotAndFeatureKeepsTheRestsConditional)
{
	// The joint fusion with features held out of view: the robot and the
	// first feature (5 entries) replaced, the other feature following its
	// conditional on them. Same tolerances as the robot-only case above.
	std::mt19937 rng(13);
	for (int trial = 0; trial < 5; ++trial)
	{
		const GaussianState s = randomJointState(rng);
		GaussianState lead{s.mean.head<5>(), 0.6 * s.cov.topLeftCorner<5, 5>()};
		const Eigen::VectorXd dl = (Eigen::VectorXd(5) << 0.2, -0.1, 0.05, 0.3, -0.2).finished();
		lead.mean += dl;
		const GaussianState t = withLeadingMarginal(s, lead);

		const Eigen::MatrixXd K = s.cov.bottomLeftCorner(2, 5) * s.cov.topLeftCorner<5, 5>().partialPivLu().inverse();
		EXPECT_LT((t.mean.tail<2>() - (s.mean.tail<2>() + K * dl)).norm(), 1e-10);
		EXPECT_LT((t.mean.head<5>() - lead.mean).norm(), 1e-12);
		EXPECT_LT(relError(t.cov.topLeftCorner<5, 5>(), lead.cov), 1e-12);
		const auto conditional = [](const Eigen::MatrixXd& P) -> Eigen::MatrixXd {
			return P.bottomRightCorner(2, 2) -
				P.bottomLeftCorner(2, 5) * P.topLeftCorner<5, 5>().partialPivLu().solve(P.topRightCorner(5, 2));
		};
		EXPECT_LT(relError(conditional(t.cov), conditional(s.cov)), 1e-10);
		EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(t.cov).eigenvalues().minCoeff(), 0.0);
	}
}

// ===========================================================================
// 5. LocalSlam

const Pose2 kSensor(0.2, 0.05, 0.1);

IdentifiedMeasurement measure(LandmarkId id, const Pose2& robot, const Eigen::Vector2d& f, const Eigen::Matrix2d& R)
{
	return {id, rangeBearing(robot, kSensor, f), R};
}

OdometryIncrement odometry(double dx, double dy, double dphi, const Eigen::Matrix3d& cov)
{
	OdometryIncrement u;
	u.delta = Pose2(dx, dy, dphi);
	u.cov = cov;
	return u;
}

TEST(DslamUnitsLocalSlam, ObserveDropsUnseenAndReinitialisesReturningFeatures)
{
	const Eigen::Matrix2d R = Eigen::Vector2d(0.01, 1e-4).asDiagonal();
	const Eigen::Matrix3d Q = Eigen::Vector3d(1e-3, 1e-3, 1e-4).asDiagonal();
	const std::vector<Eigen::Vector2d> F = {{3, 1}, {2, -2}, {4, 3}};
	LocalSlam ls;
	Pose2 truth = Pose2::Zero();
	ls.addFeatures({measure(1, truth, F[0], R), measure(2, truth, F[1], R), measure(3, truth, F[2], R)}, kSensor);
	ASSERT_EQ(ls.order(), (std::vector<LandmarkId>{1, 2, 3}));
	const Eigen::Vector2d old2 = ls.state().segment<2>(5);

	// Step: feature 2 is out of view and must be dropped.
	ls.predict(odometry(0.5, 0.1, 0.05, Q));
	truth = Pose2(0.5, 0.1, 0.05);
	ls.observe({measure(1, truth, F[0], R), measure(3, truth, F[2], R)}, kSensor);
	EXPECT_EQ(ls.order(), (std::vector<LandmarkId>{1, 3}));
	EXPECT_FALSE(ls.holds(2));
	EXPECT_EQ(ls.state().size(), 7);
	EXPECT_EQ(ls.covariance().rows(), 7);

	// Next step: 2 comes back, measured 0.5 m away from where it was (a
	// returning feature is initialised from its measurement, never from
	// its old value).
	ls.predict(odometry(0.4, -0.1, -0.02, Q));
	truth = Pose2(0.9, 0.0, 0.03);
	const Eigen::Vector2d moved2 = F[1] + Eigen::Vector2d(0.3, -0.4);
	const IdentifiedMeasurement z2 = measure(2, truth, moved2, R);
	ls.observe({measure(1, truth, F[0], R), z2, measure(3, truth, F[2], R)}, kSensor);
	ASSERT_EQ(ls.order(), (std::vector<LandmarkId>{1, 3, 2}));
	ASSERT_TRUE(ls.holds(2));

	// Its estimate is the inverse measurement from the current (updated)
	// robot pose: a handful of floating operations, 1e-12.
	const Pose2 robot = ls.robot();
	const Eigen::Vector2d est2 = ls.state().segment<2>(7);
	EXPECT_LT((est2 - featureAt(robot, kSensor, z2.z)).norm(), 1e-12);
	EXPECT_GT((est2 - old2).norm(), 0.4);

	// And its covariance is that of a fresh initialisation: G_r P_r,: for
	// the cross terms and G_r P_rr G_r^T + G_z R G_z^T for its own block,
	// with numeric Jacobians of the inverse measurement (relative error
	// ~1e-9, hence 1e-7 on the products).
	const Eigen::MatrixXd P = ls.covariance();
	const Eigen::MatrixXd Gr = test::numericJacobian(
		[&](const Eigen::VectorXd& x) -> Eigen::VectorXd { return featureAt(x, kSensor, z2.z); }, robot);
	const Eigen::MatrixXd Gz = test::numericJacobian(
		[&](const Eigen::VectorXd& z) -> Eigen::VectorXd { return featureAt(robot, kSensor, z); }, z2.z);
	const Eigen::MatrixXd Prr = P.topLeftCorner<3, 3>();
	EXPECT_LT(relError(P.block(7, 7, 2, 2), Gr * Prr * Gr.transpose() + Gz * R * Gz.transpose()), 1e-7);
	EXPECT_LT(relError(P.block(7, 0, 2, 7), Gr * P.topLeftCorner(3, 7)), 1e-7);
}

TEST(DslamUnitsLocalSlam, HoldsAFeatureOutOfViewForHoldStepsThenDropsIt)
{
	const Eigen::Matrix2d R = Eigen::Vector2d(0.01, 1e-4).asDiagonal();
	const Eigen::Matrix3d Q = Eigen::Vector3d(1e-3, 1e-3, 1e-4).asDiagonal();
	const std::vector<Eigen::Vector2d> F = {{3, 1}, {2, -2}};
	LocalSlam ls(3);
	Pose2 truth = Pose2::Zero();
	ls.addFeatures({measure(1, truth, F[0], R), measure(2, truth, F[1], R)}, kSensor);

	// Feature 2 unseen for 1, 2, 3 predictions: held, in its place.
	for (int k = 1; k <= 3; ++k)
	{
		ls.predict(odometry(0.2, 0, 0.01, Q));
		truth = Pose2(0.2 * k, 0, 0.01 * k);
		ls.observe({measure(1, truth, F[0], R)}, kSensor);
		EXPECT_TRUE(ls.holds(2)) << "after " << k << " steps out of view";
		EXPECT_EQ(ls.order(), (std::vector<LandmarkId>{1, 2}));
	}
	// The fourth step out of view drops it.
	ls.predict(odometry(0.2, 0, 0.01, Q));
	truth = Pose2(0.8, 0, 0.04);
	ls.observe({measure(1, truth, F[0], R)}, kSensor);
	EXPECT_FALSE(ls.holds(2));
	EXPECT_EQ(ls.state().size(), 5);

	// Seen again, it starts afresh and its clock with it.
	ls.predict(odometry(0.2, 0, 0.01, Q));
	truth = Pose2(1.0, 0, 0.05);
	ls.observe({measure(1, truth, F[0], R), measure(2, truth, F[1], R)}, kSensor);
	ASSERT_TRUE(ls.holds(2));
	for (int k = 1; k <= 3; ++k)
	{
		ls.predict(odometry(0.2, 0, 0.01, Q));
		ls.observe({measure(1, truth, F[0], R)}, kSensor);
	}
	EXPECT_TRUE(ls.holds(2));
}

TEST(DslamUnitsLocalSlam, HeldFeatureKeepsItsEstimateWhereTheBookReinitialisesIt)
{
	// The same two steps with hold 0 (the book) and hold 5: feature 2 is out
	// of view at step 1 and measured 0.5 m off its first estimate at step 2.
	// The book re-initialises it from that measurement; held, it is updated
	// by it: a Kalman update moves it only part of the way (its covariance
	// is comparable to R here), so it ends between the two.
	const Eigen::Matrix2d R = Eigen::Vector2d(0.01, 1e-4).asDiagonal();
	const Eigen::Matrix3d Q = Eigen::Vector3d(1e-3, 1e-3, 1e-4).asDiagonal();
	const std::vector<Eigen::Vector2d> F = {{3, 1}, {2, -2}};
	const auto run = [&](int hold)
	{
		LocalSlam ls(hold);
		ls.addFeatures({measure(1, Pose2::Zero(), F[0], R), measure(2, Pose2::Zero(), F[1], R)}, kSensor);
		ls.predict(odometry(0.2, 0, 0.01, Q));
		ls.observe({measure(1, Pose2(0.2, 0, 0.01), F[0], R)}, kSensor);
		ls.predict(odometry(0.2, 0, 0.01, Q));
		const Pose2 truth(0.4, 0, 0.02);
		ls.observe({measure(1, truth, F[0], R), measure(2, truth, F[1] + Eigen::Vector2d(0.3, -0.4), R)}, kSensor);
		return ls;
	};
	const LocalSlam book = run(0), held = run(5);
	ASSERT_EQ(book.order(), (std::vector<LandmarkId>{1, 2}));
	ASSERT_EQ(held.order(), (std::vector<LandmarkId>{1, 2}));
	const Eigen::Vector2d moved = F[1] + Eigen::Vector2d(0.3, -0.4);
	const double book_off = (book.state().segment<2>(5) - moved).norm();
	const double held_off = (held.state().segment<2>(5) - moved).norm();
	const double held_from_old = (held.state().segment<2>(5) - F[1]).norm();
	EXPECT_LT(book_off, 0.1);		  // at the measurement, up to the robot's correction
	EXPECT_GT(held_off, 0.1);		  // not at the measurement ...
	EXPECT_GT(held_from_old, 0.05);	  // ... nor where it was
}

TEST(DslamUnitsLocalSlam, BringToFrontKeepsTheOthersBehind)
{
	const Eigen::Matrix2d R = Eigen::Vector2d(0.02, 2e-4).asDiagonal();
	const std::vector<Eigen::Vector2d> F = {{3, 1}, {2, -2}, {4, 3}, {-1, 3}};
	LocalSlam ls;
	std::vector<IdentifiedMeasurement> scan;
	for (int i = 0; i < 4; ++i) scan.push_back(measure(i + 1, Pose2::Zero(), F[i], R));
	ls.addFeatures(scan, kSensor);
	const Eigen::VectorXd x = ls.state();
	const Eigen::MatrixXd P = ls.covariance();
	ls.bringToFront({3, 1});
	EXPECT_EQ(ls.order(), (std::vector<LandmarkId>{3, 1, 2, 4}));
	const std::vector<Eigen::Index> perm = {0, 1, 2, 7, 8, 3, 4, 5, 6, 9, 10};
	EXPECT_LT((ls.state() - x(perm)).norm(), 1e-15 * x.norm());
	EXPECT_LT((ls.covariance() - P(perm, perm)).norm(), 1e-15 * P.norm());
}

TEST(DslamUnitsLocalSlam, ArrangePermutesTheJointGaussian)
{
	const Eigen::Matrix2d R = Eigen::Vector2d(0.02, 2e-4).asDiagonal();
	const Eigen::Matrix3d Q = Eigen::Vector3d(2e-3, 1e-3, 3e-4).asDiagonal();
	const std::vector<Eigen::Vector2d> F = {{3, 1}, {2, -2}, {4, 3}, {-1, 3}};
	LocalSlam ls;
	std::vector<IdentifiedMeasurement> scan;
	for (int i = 0; i < 4; ++i) scan.push_back(measure(i + 1, Pose2::Zero(), F[i], R));
	ls.addFeatures(scan, kSensor);
	// A step with every feature in view correlates everything.
	ls.predict(odometry(0.5, 0.1, 0.05, Q));
	scan.clear();
	for (int i = 0; i < 4; ++i) scan.push_back(measure(i + 1, Pose2(0.52, 0.08, 0.06), F[i], R));
	ls.observe(scan, kSensor);
	ASSERT_EQ(ls.order(), (std::vector<LandmarkId>{1, 2, 3, 4}));
	const Eigen::VectorXd x = ls.state();
	const Eigen::MatrixXd P = ls.covariance();
	ASSERT_GT(P.block(3, 9, 2, 2).norm(), 1e-8);  // feature 1 - feature 4 correlated

	const auto rows = [](const std::vector<int>& features)
	{
		std::vector<Eigen::Index> r = {0, 1, 2};
		for (int f : features)
		{
			r.push_back(3 + 2 * f);
			r.push_back(4 + 2 * f);
		}
		return r;
	};
	// A pure permutation: the same joint Gaussian, rows and columns moved
	// together. Only copies (and symmetrising an exactly symmetric matrix):
	// exact, 1e-15 relative allows for nothing more than that.
	ls.arrange({3, 1, 4, 2});
	EXPECT_EQ(ls.order(), (std::vector<LandmarkId>{3, 1, 4, 2}));
	const auto perm = rows({2, 0, 3, 1});
	EXPECT_LT((ls.state() - x(perm)).norm(), 1e-15 * x.norm());
	EXPECT_LT((ls.covariance() - P(perm, perm)).norm(), 1e-15 * P.norm());

	// A subset in a new order: marginalisation = deleting rows and columns.
	ls.arrange({4, 3});
	EXPECT_EQ(ls.order(), (std::vector<LandmarkId>{4, 3}));
	EXPECT_FALSE(ls.holds(1));
	EXPECT_FALSE(ls.holds(2));
	const auto sub = rows({3, 2});
	EXPECT_LT((ls.state() - x(sub)).norm(), 1e-15 * x.norm());
	EXPECT_LT((ls.covariance() - P(sub, sub)).norm(), 1e-15 * P.norm());
}

// ===========================================================================
// 6. AdmissibleChain

struct ChainCase
{
	Pose2 sensor{0.3, 0.1, 0.2};
	std::vector<Eigen::Vector2d> features{{4, 1}, {2, -3}, {-1, 5}};
	std::vector<Eigen::Matrix2d> R{Eigen::Vector2d(0.01, 4e-4).asDiagonal(),
								   Eigen::Vector2d(0.02, 1e-4).asDiagonal(),
								   Eigen::Vector2d(0.005, 9e-4).asDiagonal()};
	Pose2 step{1.0, 0.2, 0.3};	///< odometry from the root

	std::vector<IdentifiedMeasurement> rootScan() const
	{
		std::vector<IdentifiedMeasurement> scan;
		for (std::size_t i = 0; i < features.size(); ++i)
			scan.push_back({static_cast<LandmarkId>(10 + i), rangeBearing(Pose2::Zero(), sensor, features[i]), R[i]});
		return scan;
	}
};

/// H P H^T for the virtual observation of `c`, computed independently: the
/// robot exactly at the root, features initialised from exact measurements
/// (covariance G_z R G_z^T each, independent, no robot cross terms since
/// the root is exact), the robot after the step with covariance Q (at the
/// root heading 0 the composition Jacobian with respect to the increment
/// is the identity) and uncorrelated with the features.
Eigen::MatrixXd virtualCovariance(const ChainCase& c, const Eigen::Matrix3d& Q)
{
	const int k = static_cast<int>(c.features.size());
	Eigen::MatrixXd P = Eigen::MatrixXd::Zero(3 + 2 * k, 3 + 2 * k);
	P.topLeftCorner<3, 3>() = Q;
	for (int i = 0; i < k; ++i)
	{
		const Eigen::Vector2d z = rangeBearing(Pose2::Zero(), c.sensor, c.features[i]);
		const Eigen::MatrixXd Gz = test::numericJacobian(
			[&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return featureAt(Pose2::Zero(), c.sensor, v); }, z);
		P.block(3 + 2 * i, 3 + 2 * i, 2, 2) = Gz * c.R[i] * Gz.transpose();
	}
	// H of all predicted measurements with respect to [robot; features].
	const auto h = [&](const Eigen::VectorXd& y) -> Eigen::VectorXd
	{
		Eigen::VectorXd out(2 * k);
		for (int i = 0; i < k; ++i) out.segment<2>(2 * i) = rangeBearing(y.head<3>(), c.sensor, y.segment<2>(3 + 2 * i));
		return out;
	};
	Eigen::VectorXd y(3 + 2 * k);
	y << c.step, stack(c.features);
	std::vector<int> bearings;
	for (int i = 0; i < k; ++i) bearings.push_back(2 * i + 1);
	const Eigen::MatrixXd H = test::numericJacobian(h, y, 1e-6, bearings);
	return H * P * H.transpose();
}

TEST(DslamUnitsAdmissibleChain, VirtualObservationAfterAZeroNoiseStep)
{
	const ChainCase c;
	AdmissibleChain chain;
	EXPECT_TRUE(chain.rootIsMapFrame());
	EXPECT_EQ(chain.scans(), 0);
	chain.restart(c.rootScan(), c.sensor);
	EXPECT_FALSE(chain.rootIsMapFrame());
	EXPECT_EQ(chain.scans(), 1);
	ASSERT_EQ(chain.ids(), (std::vector<LandmarkId>{10, 11, 12}));
	// Exact measurements from the exact root: the features are exact.
	EXPECT_LT((chain.features().xy - stack(c.features)).norm(), 1e-12);

	chain.predict(odometry(c.step.x(), c.step.y(), c.step.z(), Eigen::Matrix3d::Zero()));
	const VirtualObservation v = chain.virtualObservation(c.sensor);
	ASSERT_EQ(v.ids, chain.ids());
	ASSERT_EQ(v.range_bearing.size(), 6);
	// The geometric ranges and bearings from the new pose (1e-12: O(5 m)
	// values from a few operations).
	for (int i = 0; i < 3; ++i)
	{
		const Eigen::Vector2d g = rangeBearing(c.step, c.sensor, c.features[i]);
		EXPECT_NEAR(v.range_bearing(2 * i), g(0), 1e-12) << i;
		EXPECT_LT(std::abs(wrap(v.range_bearing(2 * i + 1) - g(1))), 1e-12) << i;
	}
	// Covariance H P H^T from numeric Jacobians (each ~1e-9 relative): 1e-7.
	const Eigen::MatrixXd expected = virtualCovariance(c, Eigen::Matrix3d::Zero());
	EXPECT_LT(relError(v.cov, expected), 1e-7);
	// Exactly symmetric (blocks mirrored).
	EXPECT_LT((v.cov - v.cov.transpose()).norm(), 1e-15 * v.cov.norm());
}

TEST(DslamUnitsAdmissibleChain, VirtualObservationAfterANoisyStep)
{
	// The same with odometry noise: the robot's uncertainty enters H P H^T.
	const ChainCase c;
	Eigen::Matrix3d Q;
	Q << 4e-3, 1e-3, 0, 1e-3, 2e-3, 2e-4, 0, 2e-4, 1e-3;
	AdmissibleChain chain;
	chain.restart(c.rootScan(), c.sensor);
	chain.predict(odometry(c.step.x(), c.step.y(), c.step.z(), Q));
	const VirtualObservation v = chain.virtualObservation(c.sensor);
	EXPECT_LT(relError(v.cov, virtualCovariance(c, Q)), 1e-7);
	// The noise matters: without it the covariance is clearly smaller.
	EXPECT_GT(relError(v.cov, virtualCovariance(c, Eigen::Matrix3d::Zero())), 1e-2);
}

TEST(DslamUnitsAdmissibleChain, RestartForgetsThePreviousChain)
{
	// A chain that has moved and absorbed a scan, restarted from its current
	// pose: the new root is that pose, exactly known, and only the root
	// scan's features are held, expressed in the new root frame.
	const ChainCase c;
	const Eigen::Matrix2d R = Eigen::Vector2d(0.01, 1e-4).asDiagonal();
	const Eigen::Matrix3d Q = Eigen::Vector3d(1e-3, 1e-3, 1e-4).asDiagonal();
	AdmissibleChain chain;
	chain.restart(c.rootScan(), c.sensor);
	chain.predict(odometry(c.step.x(), c.step.y(), c.step.z(), Q));
	chain.absorb({{99, rangeBearing(c.step, c.sensor, {3, 3}), R}}, c.sensor);
	ASSERT_EQ(chain.scans(), 2);
	ASSERT_EQ(chain.ids().size(), 4u);

	// Restart at the current pose with a scan of two features given in the
	// new root frame.
	const std::vector<Eigen::Vector2d> local = {{2, 1}, {1, -2}};
	chain.restart({{7, rangeBearing(Pose2::Zero(), c.sensor, local[0]), R},
				   {8, rangeBearing(Pose2::Zero(), c.sensor, local[1]), R}},
				  c.sensor);
	EXPECT_FALSE(chain.rootIsMapFrame());
	EXPECT_EQ(chain.scans(), 1);
	ASSERT_EQ(chain.ids(), (std::vector<LandmarkId>{7, 8}));
	const PointSet f = chain.features();
	EXPECT_LT((f.xy - stack(local)).norm(), 1e-12);
	// Exact root: no robot uncertainty in the features, only G_z R G_z^T
	// (numeric Jacobian, ~1e-9 relative).
	for (int i = 0; i < 2; ++i)
	{
		const Eigen::Vector2d z = rangeBearing(Pose2::Zero(), c.sensor, local[i]);
		const Eigen::MatrixXd Gz = test::numericJacobian(
			[&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return featureAt(Pose2::Zero(), c.sensor, v); }, z);
		EXPECT_LT(relError(f.cov.block(2 * i, 2 * i, 2, 2), Gz * R * Gz.transpose()), 1e-7) << i;
	}
	EXPECT_LT(f.cov.block(0, 2, 2, 2).norm(), 1e-15);
}

// ===========================================================================
// 7. FeatureMap

/// The map case: anchor f1 = (2, 1), f2 = (5, 2) (map frame, correlated
/// covariance), then a scan from (1, -1, 0.3) that sees f1, f2 and the new
/// f3 ~ (4, 5), with points perturbed by a few cm so that its d12 disagrees
/// with the anchor and the update has something to reconcile.
struct MapCase
{
	std::vector<LandmarkId> anchor_ids{10, 20};
	PointSet anchor;
	std::vector<LandmarkId> scan_ids{10, 20, 30};
	PointSet scan;

	MapCase()
	{
		anchor.xy = (Eigen::VectorXd(4) << 2, 1, 5, 2).finished();
		anchor.cov = Eigen::Vector4d(0.01, 0.02, 0.015, 0.01).asDiagonal();
		anchor.cov(0, 2) = anchor.cov(2, 0) = 0.004;
		anchor.cov(1, 3) = anchor.cov(3, 1) = -0.003;
		const Pose2 robot(1, -1, 0.3);
		scan.xy = stack({toFrame(robot, {2, 1}), toFrame(robot, {5, 2}), toFrame(robot, {4, 5})});
		scan.xy += (Eigen::VectorXd(6) << 0.03, -0.02, -0.04, 0.05, 0.02, 0.01).finished();
		std::mt19937 rng(3);
		scan.cov = randomSpd(6, 2e-3, 1e-3, rng);
	}
};

/// Information matrix of the core as a dense matrix.
Eigen::MatrixXd denseInformation(const FeatureMap& map)
{
	return Eigen::MatrixXd(toEigenSparse(map.core().information().matrix()));
}

class DslamUnitsMapRecovery : public ::testing::TestWithParam<RecoveryMethod>
{
};

TEST_P(DslamUnitsMapRecovery, RelativeUpdateMatchesDenseLeastSquaresAndWithdraws)
{
	const MapCase c;
	SparseRecoveryParams params;
	params.recovery = GetParam();
	FeatureMap map(params);

	const MapUpdate a = map.updateAnchor(c.anchor_ids, c.anchor);
	EXPECT_EQ(a.new_features, c.anchor_ids);
	ASSERT_TRUE(map.supported(10) && map.supported(20));
	EXPECT_EQ(map.mappedOrder(10), 0);
	EXPECT_EQ(map.mappedOrder(20), 1);
	const Eigen::MatrixXd I_before = denseInformation(map);
	const Eigen::VectorXd i_before = map.core().information().vector();
	ASSERT_EQ(I_before.rows(), 4);

	const MapUpdate u = map.updateRelative(c.scan_ids, c.scan);
	EXPECT_EQ(u.new_features, (std::vector<LandmarkId>{30}));
	ASSERT_TRUE(map.contains(30));

	// Eq. (3.14) by hand: f3 from the map estimates of f1, f2 and the
	// scan's d13, a312. 1e-12: a few operations on O(5 m) numbers.
	const Eigen::Vector2d m1(2, 1), m2(5, 2);
	const Eigen::Vector2d l1 = c.scan.point(0), l2 = c.scan.point(1), l3 = c.scan.point(2);
	const double d13 = (l3 - l1).norm();
	const double a312 = std::atan2(l3.y() - l1.y(), l3.x() - l1.x()) - std::atan2(l2.y() - l1.y(), l2.x() - l1.x());
	const double a12 = std::atan2(m2.y() - m1.y(), m2.x() - m1.x());
	const Eigen::Vector2d f3_init = m1 + d13 * Eigen::Vector2d(std::cos(a12 + a312), std::sin(a12 + a312));
	EXPECT_LT((map.position(30) - f3_init).norm(), 1e-12);

	// Dense weighted least squares linearised at x0 = [f1, f2 (anchor), f3
	// (eq. 3.14)], the same point the EIF uses (one Gauss-Newton step):
	//   anchor:   z_a = x_12 + w_a,        cov P_a;
	//   relative: z_map = h(x) + w_map,    cov R_map = Jz P_scan Jz^T (eq. 3.9),
	// with h = eq. (3.13) written by hand above and H, Jz by central
	// differences.
	Eigen::VectorXd x0(6);
	x0 << m1, m2, f3_init;
	const Eigen::VectorXd z_map = zMap(c.scan.xy);
	const Eigen::MatrixXd Jz = test::numericJacobian(zMap, c.scan.xy, 1e-6, {1});
	const Eigen::MatrixXd R_map = Jz * c.scan.cov * Jz.transpose();
	const Eigen::MatrixXd H = test::numericJacobian(zMap, x0, 1e-6, {1});
	Eigen::VectorXd nu = z_map - zMap(x0);
	nu(1) = wrap(nu(1));
	Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4, 6);
	A.leftCols<4>().setIdentity();
	const Eigen::MatrixXd Wa = c.anchor.cov.inverse(), Wm = R_map.inverse();
	const Eigen::MatrixXd normal = A.transpose() * Wa * A + H.transpose() * Wm * H;
	const Eigen::VectorXd rhs = A.transpose() * Wa * (c.anchor.xy - x0.head<4>()) + H.transpose() * Wm * nu;
	const Eigen::VectorXd x_wls = x0 + normal.ldlt().solve(rhs);

	map.recover(Eigen::Vector2d(1, -1));
	Eigen::VectorXd x_map(6);
	x_map << map.position(10), map.position(20), map.position(30);
	// The update did move the estimate (d12 of the scan disagrees with the
	// anchor by ~5 cm) ...
	ASSERT_GT((x_wls - x0).norm(), 1e-3);
	// ... and agrees with the dense solution. Error budget: numeric H and
	// Jz carry ~1e-9 relative error, scaled by the ~0.05 m correction, plus
	// the solvers' round-off (condition ~1e4): ~1e-11 m. For PCG, its
	// stopping rule |I x - i| <= 1e-10 |i| with |i| ~ 1e3 |x| and the
	// smallest eigenvalue of I ~ 30 bounds the error by ~1e-8 m.
	const double tol = GetParam() == RecoveryMethod::Pcg ? 1e-7 : 1e-9;
	EXPECT_LT((x_map - x_wls).norm(), tol);
	// Covariance, eq. (3.25), against the dense inverse: both ~1e-9 relative.
	EXPECT_LT(relError(map.covariance(c.scan_ids), normal.inverse()), 1e-6);

	// Withdrawing the relative update restores the information matrix and
	// vector: I += C C^T then -= C C^T, round-off ~ eps |C C^T| ~ 1e-13 |I|;
	// f3's rows stay structurally present, with zero values.
	map.withdraw(u);
	const Eigen::MatrixXd I_after = denseInformation(map);
	ASSERT_EQ(I_after.rows(), 6);
	EXPECT_LT((I_after.topLeftCorner(4, 4) - I_before).norm(), 1e-12 * I_before.norm());
	EXPECT_LT(I_after.rightCols(2).norm(), 1e-12 * I_before.norm());
	EXPECT_LT(I_after.bottomRows(2).norm(), 1e-12 * I_before.norm());
	const Eigen::VectorXd i_after = map.core().information().vector();
	EXPECT_LT((i_after.head(4) - i_before).norm(), 1e-12 * I_before.norm() * x0.norm());
	EXPECT_LT(i_after.tail(2).norm(), 1e-12 * I_before.norm() * x0.norm());
	// f3 stays mapped but no longer supported; f1, f2 still are.
	EXPECT_TRUE(map.contains(30));
	EXPECT_FALSE(map.supported(30));
	EXPECT_TRUE(map.supported(10) && map.supported(20));
}

INSTANTIATE_TEST_SUITE_P(Recovery, DslamUnitsMapRecovery,
						 ::testing::Values(RecoveryMethod::IncrementalCholesky, RecoveryMethod::FreshCholesky,
										   RecoveryMethod::Pcg),
						 [](const ::testing::TestParamInfo<RecoveryMethod>& info)
						 { return std::string(recoveryMethodName(info.param)); });

/// Variance of the rigid rotation of the features `ids` about their
/// centroid, for the rotation generator v at `at` (stacked points):
/// theta = v^T dx / |v|^2, var = v^T P v / |v|^4.
double rotationVariance(FeatureMap& map, const std::vector<LandmarkId>& ids, const Eigen::VectorXd& at)
{
	const Eigen::Index n = at.size() / 2;
	Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
	for (Eigen::Index i = 0; i < n; ++i) centroid += at.segment<2>(2 * i) / static_cast<double>(n);
	Eigen::VectorXd v(at.size());
	for (Eigen::Index i = 0; i < n; ++i)
	{
		const Eigen::Vector2d p = at.segment<2>(2 * i) - centroid;
		v.segment<2>(2 * i) << -p.y(), p.x();
	}
	return v.dot(map.covariance(ids) * v) / std::pow(v.squaredNorm(), 2);
}

/// The map's rotation variance after 30 relative updates over the
/// anchor's alone. Four features anchored with an isotropic prior (sigma
/// 0.5 m each) at a shape 0.3 m off the truth, then updated from noisy
/// points (sigma 2 cm) of all four: the updates reshape the map, so with
/// Jacobians at the current estimate each is evaluated at a different
/// shape. Relative updates cannot see a rigid motion of the features.
double rotationVarianceRatio(bool share_points)
{
	const std::vector<LandmarkId> ids{1, 2, 3, 4};
	const Eigen::VectorXd truth = (Eigen::VectorXd(8) << 0, 0, 4, 0, 4, 3, 0, 3).finished();
	PointSet anchor;
	anchor.xy = truth + (Eigen::VectorXd(8) << 0.3, -0.2, -0.3, 0.1, 0.2, 0.3, -0.1, -0.3).finished();
	anchor.cov = 0.25 * Eigen::MatrixXd::Identity(8, 8);
	FeatureMap map(SparseRecoveryParams{});
	map.shareLinearisationPoints(share_points);
	map.updateAnchor(ids, anchor);
	map.recover(Eigen::Vector2d::Zero());
	// The rotation about the anchor's shape: the features' shared points.
	const double before = rotationVariance(map, ids, anchor.xy);
	std::mt19937 rng(7);
	std::normal_distribution<double> noise(0.0, 0.02);
	for (int k = 0; k < 30; ++k)
	{
		PointSet scan;
		scan.xy = truth;
		for (Eigen::Index i = 0; i < scan.xy.size(); ++i) scan.xy(i) += noise(rng);
		scan.cov = 0.02 * 0.02 * Eigen::MatrixXd::Identity(8, 8);
		map.updateRelative(ids, scan);
		map.recover(Eigen::Vector2d::Zero());
	}
	return rotationVariance(map, ids, anchor.xy) / before;
}

TEST(DslamUnitsMap, SharedLinearisationPointsAddNoInformationOnTheUnobservedRotation)
{
	const double shared = rotationVarianceRatio(true);
	const double current = rotationVarianceRatio(false);
	std::cout << "rotation variance after / before 30 relative updates: shared points " << shared
			  << ", current estimate " << current << "\n";
	// With shared points every update's Jacobian annihilates the same
	// rotation v, and the anchor's information is isotropic, so I v = v /
	// sigma^2 and the variance stays sigma^2 / |v|^2 exactly (round-off of
	// an 8 x 8 solve: ~1e-12 relative).
	EXPECT_NEAR(shared, 1.0, 1e-9);
	// With Jacobians at the current estimate, taken at shapes up to 0.3 m
	// apart, the updates claim to know the rotation and the variance falls.
	EXPECT_LT(current, 0.9);
}

TEST(DslamUnitsMap, ANewFeatureIsLinearisedWithItsPairAfterTheMapMoved)
{
	// f1 = (0, 0) and f2 = (4, 0) anchored, then moved 30 m along x by a far
	// tighter prior (a loop closure translating the map): their shared
	// linearisation points stay where they were mapped. A noise-free scan
	// sees them and a new f3 at (2, 3) from the pair: f3 must land at
	// (32, 3) beside the moved pair. A translation lies in the null space of
	// every relative term (eq. 3.13), so the linearised update is exact here
	// up to the first anchor's pull on the pair (1e-8 of 30 m) and
	// round-off; 1e-4 m leaves room for both. Placed from the pair's
	// estimates but linearised against its old points, f3 was thrown tens of
	// metres off (the 10k city's D-SLAM divergence).
	FeatureMap map(SparseRecoveryParams{});
	map.shareLinearisationPoints(true);
	PointSet mapped;
	mapped.xy = (Eigen::VectorXd(4) << 0, 0, 4, 0).finished();
	mapped.cov = 1e-4 * Eigen::MatrixXd::Identity(4, 4);
	map.updateAnchor({1, 2}, mapped);
	mapped.xy += (Eigen::VectorXd(4) << 30, 0, 30, 0).finished();
	mapped.cov = 1e-12 * Eigen::MatrixXd::Identity(4, 4);
	map.updateAnchor({1, 2}, mapped);
	map.recover(Eigen::Vector2d::Zero());
	ASSERT_NEAR(map.position(1).x(), 30.0, 1e-6);

	PointSet scan;
	scan.xy = (Eigen::VectorXd(6) << 0, 0, 4, 0, 2, 3).finished();
	scan.cov = 1e-4 * Eigen::MatrixXd::Identity(6, 6);
	map.updateRelative({1, 2, 3}, scan);
	map.recover(Eigen::Vector2d::Zero());
	EXPECT_NEAR((map.position(3) - Eigen::Vector2d(32, 3)).norm(), 0.0, 1e-4);
	EXPECT_NEAR((map.position(2) - Eigen::Vector2d(34, 0)).norm(), 0.0, 1e-4);
}

/// Two sightings of f3 (range, bearing from the baseline in degrees) from
/// the pair f1 = (0, 0), f2 = (`base`, 0), anchored to 1 mm; each scan's
/// points with sigma `sd`.
struct TwoSightings
{
	double base;
	std::array<Eigen::Vector2d, 2> f3;
	double sd;

	PointSet scan(int k) const
	{
		const double t = f3[k].y() * M_PI / 180;
		PointSet p;
		p.xy = (Eigen::VectorXd(6) << 0, 0, base, 0, f3[k].x() * std::cos(t), f3[k].x() * std::sin(t)).finished();
		p.cov = sd * sd * Eigen::MatrixXd::Identity(6, 6);
		return p;
	}

	std::unique_ptr<FeatureMap> map() const
	{
		auto map = std::make_unique<FeatureMap>(SparseRecoveryParams{});
		map->keepRelativeTerms(true);
		map->shareLinearisationPoints(true);
		PointSet pair;
		pair.xy = (Eigen::VectorXd(4) << 0, 0, base, 0).finished();
		pair.cov = 1e-6 * Eigen::MatrixXd::Identity(4, 4);
		map->updateAnchor({1, 2}, pair);
		for (int k : {0, 1})
		{
			map->updateRelative({1, 2, 3}, scan(k));
			map->recover(Eigen::Vector2d::Zero());
		}
		return map;
	}
};

/// The sightings disagree by 5 m, with the pair 0.2 m apart (MRCLAM's
/// cylinders stand in such pairs): the bearing rows are far from linear.
const TwoSightings kFarApart{0.2, {Eigen::Vector2d(5, 90), Eigen::Vector2d(1, 0)}, 0.1};
/// The sightings 20 degrees apart 1 m from f1, with the pair 1 m apart.
const TwoSightings kClose{1.0, {Eigen::Vector2d(1, 90), Eigen::Vector2d(1, 70)}, 0.01};

TEST(DslamUnitsMap, CostIsTheWeightedSquaredResidualOfTheKeptUpdates)
{
	const auto map = kFarApart.map();
	// By hand: the anchor's residual weighed by 1e6, each scan's z_map
	// (d12, a312, d13) against h at the estimate, weighed by R_map^-1 (eq.
	// 3.9, with Jz by central differences).
	Eigen::VectorXd x(6);
	x << map->position(1), map->position(2), map->position(3);
	double expected = 1e6 * (x.head<4>() - (Eigen::VectorXd(4) << 0, 0, 0.2, 0).finished()).squaredNorm();
	for (int k : {0, 1})
	{
		const PointSet p = kFarApart.scan(k);
		const Eigen::MatrixXd Jz = test::numericJacobian(zMap, p.xy, 1e-6, {1});
		const Eigen::MatrixXd R_map = Jz * p.cov * Jz.transpose();
		Eigen::VectorXd nu = zMap(p.xy) - zMap(x);
		nu(1) = wrap(nu(1));
		expected += nu.dot(R_map.ldlt().solve(nu));
	}
	// Numeric Jz carries ~1e-9 relative error; 1e-6 relative leaves room.
	EXPECT_NEAR(map->cost(), expected, 1e-6 * expected);
}

TEST(DslamUnitsMap, ARelinearisationThatRaisesTheCostIsTakenBack)
{
	// Plain Gauss-Newton: the first pass lowers the cost, the second raises
	// it (8287 -> 4465 -> 51531 when written).
	const auto plain = kFarApart.map();
	std::vector<double> cost{plain->cost()};
	std::vector<Eigen::Vector2d> f3{plain->position(3)};
	for (int pass = 0; pass < 2; ++pass)
	{
		plain->relinearise();
		plain->recover(Eigen::Vector2d::Zero());
		cost.push_back(plain->cost());
		f3.push_back(plain->position(3));
	}
	std::cout << "plain Gauss-Newton: cost " << cost[0] << " -> " << cost[1] << " -> " << cost[2] << "\n";
	ASSERT_LT(cost[1], cost[0]) << "the case changed; it no longer tests a kept pass";
	ASSERT_GT(cost[2], cost[1]) << "the case no longer overshoots; it tests nothing";

	// Guarded: the first pass is kept (its two relative terms), the second
	// taken back, and the iteration stops there.
	const auto guarded = kFarApart.map();
	EXPECT_EQ(guarded->relineariseUntilSettled(0, 5, Eigen::Vector2d::Zero()), 2u);
	EXPECT_EQ(guarded->rejectedPasses(), 1u);
	// Back where the first pass left it: the same terms recovered again give
	// the same estimate up to round-off of a 6 x 6 solve (~1e-12 m).
	EXPECT_LT((guarded->position(3) - f3[1]).norm(), 1e-9);
	EXPECT_NEAR(guarded->cost(), cost[1], 1e-9 * cost[1]);
}

TEST(DslamUnitsMap, ARelinearisationThatLowersTheCostIsKeptToAStationaryPoint)
{
	const auto map = kClose.map();
	const double cost_before = map->cost();
	EXPECT_GT(map->relineariseUntilSettled(0, 10, Eigen::Vector2d::Zero()), 0u);
	EXPECT_EQ(map->rejectedPasses(), 0u);
	EXPECT_LT(map->cost(), cost_before);
	// A fixed point of Gauss-Newton is a stationary point of the cost
	// (J^T R^-1 r = 0): one more plain pass no longer moves f3. Converging
	// quadratically from ~1 cm in under ten passes leaves far less than
	// 1e-9 m.
	const Eigen::Vector2d settled = map->position(3);
	map->relinearise();
	map->recover(Eigen::Vector2d::Zero());
	EXPECT_LT((map->position(3) - settled).norm(), 1e-9);
}

TEST(DslamUnitsMap, RelativeUpdateNeedsSupportedReferencePair)
{
	const MapCase c;
	FeatureMap map(SparseRecoveryParams{});
	EXPECT_THROW(map.updateRelative(c.scan_ids, c.scan), std::logic_error);
}

}  // namespace
