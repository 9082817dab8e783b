#pragma once
/// \file SparseTestProblem.h
/// Random SLAM-like problems for the sparse information core: a chain of
/// poses with odometry-like links, point features observed from a few
/// nearby poses, occasional loop closures to old features, an anchor prior
/// on the first pose. Jacobians, covariances and innovations are random
/// (well conditioned), so the tests exercise the algebra, not a model.

#include <esif/sparse/SparseInformationCore.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

namespace esif::test
{
/// One measurement of a problem step.
struct TestMeasurement
{
	std::vector<VarId> vars;
	Eigen::MatrixXd J, R;
	Eigen::VectorXd innovation;
};

/// Variables added by a step (in order) and its measurements.
struct TestStep
{
	std::vector<std::pair<VarKind, Eigen::VectorXd>> new_vars;
	std::vector<TestMeasurement> measurements;
	Eigen::Vector2d robot = Eigen::Vector2d::Zero();  ///< reference point for reorderings
};

class SparseTestProblem
{
   public:
	/// `steps` steps; each adds a pose and, with probability 0.6, a point.
	SparseTestProblem(int steps, unsigned seed, double loop_probability = 0.05) : rng_(seed)
	{
		for (int k = 0; k < steps; ++k) steps_.push_back(makeStep(k, loop_probability));
	}

	const std::vector<TestStep>& steps() const { return steps_; }

	/// Applies step k to `core`: variables, then measurements; sets the reference point.
	static void apply(const TestStep& step, SparseInformationCore& core)
	{
		for (const auto& [kind, x0] : step.new_vars)
		{
			if (kind == VarKind::Pose2)
				core.addPose(x0);
			else
				core.addPoint(x0);
		}
		for (const auto& m : step.measurements) core.addMeasurement(m.vars, m.J, m.R, m.innovation);
		core.setReferencePoint(step.robot);
	}

   private:
	Eigen::MatrixXd randomMatrix(int rows, int cols, double scale)
	{
		std::normal_distribution<double> n(0.0, scale);
		Eigen::MatrixXd M(rows, cols);
		for (int i = 0; i < rows; ++i)
			for (int j = 0; j < cols; ++j) M(i, j) = n(rng_);
		return M;
	}

	/// Random SPD covariance with standard deviations around `sigma`.
	Eigen::MatrixXd randomCovariance(int m, double sigma)
	{
		const Eigen::MatrixXd A = randomMatrix(m, m, 0.3 * sigma);
		return A * A.transpose() + sigma * sigma * Eigen::MatrixXd::Identity(m, m);
	}

	/// Near-identity Jacobian block (a well-conditioned linearised model).
	Eigen::MatrixXd jacobianBlock(int rows, int cols, double sign)
	{
		Eigen::MatrixXd J = randomMatrix(rows, cols, 0.2);
		for (int i = 0; i < std::min(rows, cols); ++i) J(i, i) += sign;
		return J;
	}

	TestMeasurement relative(VarId a, int da, VarId b, int db, int rows, double sigma)
	{
		TestMeasurement m;
		m.vars = {a, b};
		m.J.resize(rows, da + db);
		m.J << jacobianBlock(rows, da, -1.0), jacobianBlock(rows, db, 1.0);
		m.R = randomCovariance(rows, sigma);
		m.innovation = randomMatrix(rows, 1, sigma);
		return m;
	}

	TestStep makeStep(int k, double loop_probability)
	{
		std::uniform_real_distribution<double> u(0.0, 1.0);
		TestStep s;
		// The robot drifts along a slow spiral so distances vary.
		const double t = 0.2 * k;
		s.robot = Eigen::Vector2d(t * std::cos(0.05 * k), t * std::sin(0.05 * k));
		const VarId pose{next_var_++};
		s.new_vars.push_back({VarKind::Pose2, Eigen::Vector3d(s.robot.x(), s.robot.y(), 0.01 * k)});
		if (k == 0)
		{
			TestMeasurement prior;  // anchor: direct observation of the first pose
			prior.vars = {pose};
			prior.J = Eigen::Matrix3d::Identity();
			prior.R = randomCovariance(3, 0.01);
			prior.innovation = randomMatrix(3, 1, 0.01);
			s.measurements.push_back(prior);
		}
		else
			s.measurements.push_back(relative(last_pose_, 3, pose, 3, 3, 0.05));
		if (u(rng_) < 0.6)
		{
			const VarId point{next_var_++};
			s.new_vars.push_back({VarKind::Point2, s.robot + randomMatrix(2, 1, 1.0)});
			points_.push_back(point);
			s.measurements.push_back(relative(pose, 3, point, 2, 2, 0.1));
		}
		// Recent points seen again; now and then a point from long ago (a loop).
		const int recent = std::min<int>(4, static_cast<int>(points_.size()) - 1);
		for (int j = 1; j <= recent; ++j)
			if (u(rng_) < 0.5) s.measurements.push_back(relative(pose, 3, points_[points_.size() - 1 - j], 2, 2, 0.1));
		if (points_.size() > 20 && u(rng_) < loop_probability)
		{
			std::uniform_int_distribution<std::size_t> old(0, points_.size() / 2);
			s.measurements.push_back(relative(pose, 3, points_[old(rng_)], 2, 2, 0.1));
		}
		last_pose_ = pose;
		return s;
	}

	std::mt19937 rng_;
	std::vector<TestStep> steps_;
	std::vector<VarId> points_;
	VarId last_pose_;
	int next_var_ = 0;
};

/// Relative difference |a - b| / max(|b|, tiny), Frobenius norms.
inline double relativeDifference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b)
{
	return (a - b).norm() / std::max(b.norm(), 1e-300);
}

}  // namespace esif::test
