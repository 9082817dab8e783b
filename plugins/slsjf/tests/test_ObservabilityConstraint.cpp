// The observability-constrained Jacobians of SLSJF's fusions
// (ObservabilityConstraint.h): the rigid motions are the null space of a
// local map's relative observation at the point it is linearised at, and
// the projection makes them the null space at any other chosen point while
// leaving a Jacobian that already has it unchanged.

#include "ObservabilityConstraint.h"

#include <esif/models/LocalMapObservation.h>

#include <Eigen/LU>
#include <gtest/gtest.h>

namespace
{
using namespace esif;
using namespace esif::slsjf;

/// A map seen from start pose s: [d h / d start, d h / d (end, features)]
/// and the variables' values in that order.
struct Linearised
{
	Eigen::MatrixXd J;
	std::vector<Eigen::VectorXd> points;
};

Linearised mapJacobian(const Pose2& s, const Pose2& e, const std::vector<Eigen::Vector2d>& f)
{
	const LocalMapPrediction p = predictLocalMap(s, e, f);
	Linearised out;
	out.J.resize(p.h.size(), 3 + p.d_state.cols());
	out.J << p.d_start, p.d_state;
	out.points = {s, e};
	for (const auto& x : f) out.points.emplace_back(x);
	return out;
}

TEST(ObservabilityConstraint, RigidMotionsAreTheNullSpaceOfARelativeObservationWhereItIsLinearised)
{
	const auto l = mapJacobian(Pose2(40, -25, 0.7), Pose2(44, -22, 1.1), {{41, -20}, {47, -26}, {38, -24}});
	const Eigen::MatrixXd N = rigidMotionDirections(l.points);
	EXPECT_LT((l.J * N).norm(), 1e-9 * l.J.norm() * N.norm());
}

TEST(ObservabilityConstraint, TheProjectionSharesTheNullSpaceOfAnotherPointAndChangesLittle)
{
	const auto current = mapJacobian(Pose2(40, -25, 0.7), Pose2(44, -22, 1.1), {{41, -20}, {47, -26}});
	// First estimates half a metre and a few degrees away.
	const std::vector<Eigen::VectorXd> first = {Pose2(40.4, -25.3, 0.66), Pose2(44.5, -21.6, 1.05),
												 Eigen::Vector2d(41.3, -19.6), Eigen::Vector2d(47.5, -25.8)};
	const Eigen::MatrixXd N_first = rigidMotionDirections(first);
	ASSERT_GT((current.J * N_first).norm(), 1e-3);	// the two null spaces differ
	const Eigen::MatrixXd J = constrainToNullSpace(current.J, N_first);
	EXPECT_LT((J * N_first).norm(), 1e-9 * J.norm());
	// The smallest change: orthogonal to the removed part.
	EXPECT_LT(((current.J - J) * (Eigen::MatrixXd::Identity(J.cols(), J.cols()) -
								  N_first * (N_first.transpose() * N_first).inverse() * N_first.transpose()))
				  .norm(),
			  1e-9 * J.norm());
	EXPECT_LT((current.J - J).norm(), 0.2 * current.J.norm());
}

TEST(ObservabilityConstraint, AJacobianThatAlreadyHasTheNullSpaceIsUnchanged)
{
	const auto l = mapJacobian(Pose2(-3, 8, -2.9), Pose2(0, 9, 2.8), {{-1, 10}});
	const Eigen::MatrixXd J = constrainToNullSpace(l.J, rigidMotionDirections(l.points));
	EXPECT_LT((J - l.J).norm(), 1e-9 * l.J.norm());
}

}  // namespace
