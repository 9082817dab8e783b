/// \file test_LocalMapModels.cpp
/// The local-map observation model (book eq. 5.7, 5.8): points and poses
/// moved between a frame and its parent, and a whole local map predicted
/// from its start pose, against central finite differences at random poses
/// and at headings next to +-pi, where the heading difference wraps.
///
/// Tolerance of every Jacobian check: central differences with h = 1e-6 on
/// coordinates up to ~70 m have a truncation error of h^2 |f'''| / 6 ~ 1e-11
/// and a round-off error of ~2 eps |f| / (2h) ~ 2.2e-16 * 70 / 1e-6 ~ 2e-8;
/// kJacobianTol = 2e-7 is ten times that, while a wrong or missing term is of
/// the order of a coordinate (metres) or of 1.

#include <NumericJacobian.h>

#include <esif/models/LocalMapObservation.h>
#include <esif/models/Se2.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace
{
using namespace esif;

constexpr double kJacobianTol = 2e-7;
/// Values computed two ways agree to round-off: a few ulps of a 70 m
/// coordinate (1.4e-14), with margin.
constexpr double kRoundOff = 1e-12;

/// Random poses in a 100 m square with any heading, plus headings next to
/// and exactly at +-pi.
std::vector<Pose2> testPoses()
{
	std::mt19937 rng(20240611);
	std::uniform_real_distribution<double> xy(-50, 50), phi(-M_PI, M_PI);
	std::vector<Pose2> out;
	for (int i = 0; i < 30; ++i) out.emplace_back(xy(rng), xy(rng), phi(rng));
	for (const double near_pi : {M_PI, -M_PI, M_PI - 1e-9, -M_PI + 1e-9, M_PI - 1e-3, -M_PI + 1e-3})
		out.emplace_back(xy(rng), xy(rng), near_pi);
	return out;
}

/// Pairs (frame, pose) whose heading difference lies within 1e-8 of +-pi, so
/// that a finite-difference step crosses the wrap of the output heading.
std::vector<std::pair<Pose2, Pose2>> wrappingPairs()
{
	std::vector<std::pair<Pose2, Pose2>> out;
	for (const double frame_phi : {0.3, -2.9, M_PI - 1e-9, -M_PI + 1e-9})
		for (const double offset : {M_PI - 1e-8, -M_PI + 1e-8, M_PI + 1e-8})
			out.push_back({Pose2(3.0, -4.0, frame_phi), Pose2(-7.5, 12.0, wrapAngle(frame_phi + offset))});
	return out;
}

Eigen::VectorXd pose3(const Eigen::VectorXd& v) { return v.head<3>(); }

double maxAbs(const Eigen::MatrixXd& m) { return m.size() ? m.cwiseAbs().maxCoeff() : 0.0; }

TEST(LocalMapModels, PointInFrameJacobians)
{
	std::mt19937 rng(7);
	std::uniform_real_distribution<double> xy(-20, 20);
	for (const Pose2& frame : testPoses())
	{
		const Eigen::Vector2d p(xy(rng), xy(rng));
		const PointInFrame a = pointInFrame(frame, p);
		// Value: the point's x, y in the frame, as Se2's inverseCompose gives it.
		EXPECT_LT((a.value - inverseCompose(frame, Pose2(p.x(), p.y(), 0)).head<2>()).norm(), kRoundOff);
		const auto d_frame = test::numericJacobian(
			[&](const Eigen::VectorXd& f) -> Eigen::VectorXd { return pointInFrame(pose3(f), p).value; }, frame);
		const auto d_point = test::numericJacobian(
			[&](const Eigen::VectorXd& q) -> Eigen::VectorXd { return pointInFrame(frame, q).value; }, p);
		EXPECT_LT(maxAbs(a.d_frame - d_frame), kJacobianTol) << "frame " << frame.transpose();
		EXPECT_LT(maxAbs(a.d_point - d_point), kJacobianTol) << "frame " << frame.transpose();
	}
}

TEST(LocalMapModels, PointFromFrameJacobiansAndRoundTrip)
{
	std::mt19937 rng(8);
	std::uniform_real_distribution<double> xy(-20, 20);
	for (const Pose2& frame : testPoses())
	{
		const Eigen::Vector2d local(xy(rng), xy(rng));
		const PointFromFrame a = pointFromFrame(frame, local);
		EXPECT_LT((a.value - transformPoint(frame, local)).norm(), kRoundOff);
		const auto d_frame = test::numericJacobian(
			[&](const Eigen::VectorXd& f) -> Eigen::VectorXd { return pointFromFrame(pose3(f), local).value; }, frame);
		const auto d_point = test::numericJacobian(
			[&](const Eigen::VectorXd& q) -> Eigen::VectorXd { return pointFromFrame(frame, q).value; }, local);
		EXPECT_LT(maxAbs(a.d_frame - d_frame), kJacobianTol) << "frame " << frame.transpose();
		EXPECT_LT(maxAbs(a.d_point - d_point), kJacobianTol) << "frame " << frame.transpose();

		// Round trips both ways; the two d_point are inverse rotations.
		const Eigen::Vector2d world(xy(rng), xy(rng));
		EXPECT_LT((pointFromFrame(frame, pointInFrame(frame, world).value).value - world).norm(), kRoundOff);
		EXPECT_LT((pointInFrame(frame, a.value).value - local).norm(), kRoundOff);
		EXPECT_LT(maxAbs(a.d_point * pointInFrame(frame, world).d_point - Eigen::Matrix2d::Identity()), 1e-15);
	}
}

void checkPoseInFrame(const Pose2& frame, const Pose2& pose)
{
	SCOPED_TRACE(::testing::Message() << "frame " << frame.transpose() << ", pose " << pose.transpose());
	const PoseInFrame a = poseInFrame(frame, pose);
	const Pose2 expected = inverseCompose(frame, pose);
	EXPECT_LT((a.value.head<2>() - expected.head<2>()).norm(), kRoundOff);
	EXPECT_LT(std::abs(wrapAngle(a.value.z() - expected.z())), kRoundOff);
	// The heading is wrapped to (-pi, pi].
	EXPECT_GT(a.value.z(), -M_PI);
	EXPECT_LE(a.value.z(), M_PI);
	// compose(frame, pose in frame) gives the pose back.
	const Pose2 back = compose(frame, a.value);
	EXPECT_LT((back.head<2>() - pose.head<2>()).norm(), kRoundOff);
	EXPECT_LT(std::abs(wrapAngle(back.z() - pose.z())), kRoundOff);

	const auto d_frame = test::numericJacobian(
		[&](const Eigen::VectorXd& f) -> Eigen::VectorXd { return poseInFrame(pose3(f), pose).value; }, frame, 1e-6,
		{2});
	const auto d_pose = test::numericJacobian(
		[&](const Eigen::VectorXd& q) -> Eigen::VectorXd { return poseInFrame(frame, pose3(q)).value; }, pose, 1e-6,
		{2});
	EXPECT_LT(maxAbs(a.d_frame - d_frame), kJacobianTol);
	EXPECT_LT(maxAbs(a.d_pose - d_pose), kJacobianTol);
}

TEST(LocalMapModels, PoseInFrameJacobiansAtRandomPosesAndAcrossTheWrap)
{
	const auto poses = testPoses();
	for (std::size_t i = 0; i < poses.size(); ++i) checkPoseInFrame(poses[i], poses[(i * 7 + 3) % poses.size()]);
	for (const auto& [frame, pose] : wrappingPairs()) checkPoseInFrame(frame, pose);
}

TEST(LocalMapModels, PredictLocalMapIsEq58WithItsJacobians)
{
	std::mt19937 rng(9);
	std::uniform_real_distribution<double> xy(-30, 30);
	auto pairs = wrappingPairs();
	const auto poses = testPoses();
	for (std::size_t i = 0; i + 1 < poses.size(); i += 2) pairs.push_back({poses[i], poses[i + 1]});
	for (const auto& [start, end] : pairs)
	{
		SCOPED_TRACE(::testing::Message() << "start " << start.transpose() << ", end " << end.transpose());
		std::vector<Eigen::Vector2d> features;
		for (int j = 0; j < 4; ++j) features.emplace_back(xy(rng), xy(rng));
		const LocalMapPrediction pred = predictLocalMap(start, end, features);
		const Eigen::Index n = 3 + 2 * static_cast<Eigen::Index>(features.size());
		ASSERT_EQ(pred.h.size(), n);
		ASSERT_EQ(pred.d_start.rows(), n);
		ASSERT_EQ(pred.d_start.cols(), 3);
		ASSERT_EQ(pred.d_state.rows(), n);
		ASSERT_EQ(pred.d_state.cols(), n);

		// h = [end in the start frame; each feature in the start frame] (eq. 5.8).
		const Pose2 e = inverseCompose(start, end);
		EXPECT_LT((pred.h.head<2>() - e.head<2>()).norm(), kRoundOff);
		EXPECT_LT(std::abs(wrapAngle(pred.h(2) - e.z())), kRoundOff);
		for (std::size_t j = 0; j < features.size(); ++j)
			EXPECT_LT(
				(pred.h.segment<2>(3 + 2 * j) - inverseCompose(start, Pose2(features[j].x(), features[j].y(), 0)).head<2>())
					.norm(),
				kRoundOff);

		Eigen::VectorXd state(n);
		state.head<3>() = end;
		for (std::size_t j = 0; j < features.size(); ++j) state.segment<2>(3 + 2 * j) = features[j];
		const auto unpack = [&](const Eigen::VectorXd& x) {
			std::vector<Eigen::Vector2d> f;
			for (std::size_t j = 0; j < features.size(); ++j) f.emplace_back(x.segment<2>(3 + 2 * j));
			return f;
		};
		const auto d_start = test::numericJacobian(
			[&](const Eigen::VectorXd& s) -> Eigen::VectorXd { return predictLocalMap(pose3(s), end, features).h; },
			start, 1e-6, {2});
		const auto d_state = test::numericJacobian(
			[&](const Eigen::VectorXd& x) -> Eigen::VectorXd { return predictLocalMap(start, pose3(x), unpack(x)).h; },
			state, 1e-6, {2});
		EXPECT_LT(maxAbs(pred.d_start - d_start), kJacobianTol);
		EXPECT_LT(maxAbs(pred.d_state - d_state), kJacobianTol);
	}
}

TEST(LocalMapModels, PredictLocalMapWithoutFeaturesIsThePoseOnly)
{
	const LocalMapPrediction pred = predictLocalMap(Pose2(1, 2, 3), Pose2(-1, 0.5, -3), {});
	ASSERT_EQ(pred.h.size(), 3);
	EXPECT_NEAR(pred.h(2), -6 + 2 * M_PI, kRoundOff);  // -3 - 3, wrapped into (-pi, pi]
}

}  // namespace
