#include <esif/core/Errors.h>
#include <esif/ekf/EkfSlamCore.h>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <stdexcept>
#include <string>

namespace esif
{
EkfSlamCore::EkfSlamCore()
{
	reserve(64);
	x_.setZero();
	P_.setZero();
}

void EkfSlamCore::reserve(std::size_t dim)
{
	if (dim <= static_cast<std::size_t>(x_.size())) return;
	// Doubling keeps the amortised cost of growing the map linear.
	const auto cap = std::max<std::size_t>(dim, 2 * static_cast<std::size_t>(x_.size()));
	Eigen::VectorXd x = Eigen::VectorXd::Zero(cap);
	Eigen::MatrixXd P = Eigen::MatrixXd::Zero(cap, cap);
	if (x_.size() > 0)
	{
		x.head(n_) = x_.head(n_);
		P.topLeftCorner(n_, n_) = P_.topLeftCorner(n_, n_);
	}
	x_.swap(x);
	P_.swap(P);
}

void EkfSlamCore::predict(const OdometryIncrement& u)
{
	const Pose2 delta = toPose2(u.delta);
	const auto J = composeJacobians(robot(), delta);
	x_.head<3>() = compose(robot(), delta);

	// Eq. (1.8) with the Jacobian F = blkdiag(d_a, I): only robot rows/cols change.
	const std::size_t m = n_ - 3;
	Eigen::Matrix3d Prr = P_.topLeftCorner<3, 3>();
	P_.topLeftCorner<3, 3>() = J.d_a * Prr * J.d_a.transpose() + J.d_b * u.cov * J.d_b.transpose();
	if (m > 0)
	{
		const Eigen::MatrixXd Prm = J.d_a * P_.block(0, 3, 3, m);
		P_.block(0, 3, 3, m) = Prm;
		P_.block(3, 0, m, 3) = Prm.transpose();
	}
	P_.topLeftCorner<3, 3>() = 0.5 * (P_.topLeftCorner<3, 3>() + P_.topLeftCorner<3, 3>().transpose()).eval();
}

RangeBearingPrediction EkfSlamCore::predictMeasurement(std::size_t i, const Pose2& sensor_on_robot) const
{
	return predictRangeBearing(robot(), sensor_on_robot, landmark(i));
}

Eigen::MatrixXd EkfSlamCore::predictionCovariance(
	const std::vector<std::size_t>& landmarks, const Pose2& sensor_on_robot) const
{
	const std::size_t k = landmarks.size();
	std::vector<RangeBearingPrediction> h(k);
	for (std::size_t a = 0; a < k; ++a) h[a] = predictMeasurement(landmarks[a], sensor_on_robot);

	// H P H^T block (a, b) = Hr_a Prr Hr_b^T + Hr_a Prb Hl_b^T + Hl_a Par Hr_b^T + Hl_a Pab Hl_b^T.
	Eigen::MatrixXd S(2 * k, 2 * k);
	const Eigen::Matrix3d Prr = P_.topLeftCorner<3, 3>();
	for (std::size_t a = 0; a < k; ++a)
	{
		const std::size_t ia = 3 + 2 * landmarks[a];
		for (std::size_t b = a; b < k; ++b)
		{
			const std::size_t ib = 3 + 2 * landmarks[b];
			const Eigen::Matrix2d block = h[a].d_robot * Prr * h[b].d_robot.transpose() +
				h[a].d_robot * P_.block<3, 2>(0, ib) * h[b].d_landmark.transpose() +
				h[a].d_landmark * P_.block<2, 3>(ia, 0) * h[b].d_robot.transpose() +
				h[a].d_landmark * P_.block<2, 2>(ia, ib) * h[b].d_landmark.transpose();
			S.block<2, 2>(2 * a, 2 * b) = block;
			S.block<2, 2>(2 * b, 2 * a) = block.transpose();
		}
	}
	return S;
}

void EkfSlamCore::update(const std::vector<Match>& matches, const Pose2& sensor_on_robot)
{
	if (matches.empty()) return;
	const std::size_t m = matches.size(), n = n_;
	const auto P = P_.topLeftCorner(n, n);

	// P H^T built from the 5 columns each measurement touches: O(n m).
	Eigen::MatrixXd PHt(n, 2 * m);
	std::vector<RangeBearingPrediction> h(m);
	Eigen::VectorXd innovation(2 * m);
	for (std::size_t j = 0; j < m; ++j)
	{
		const std::size_t il = 3 + 2 * matches[j].landmark;
		h[j] = predictMeasurement(matches[j].landmark, sensor_on_robot);
		PHt.middleCols<2>(2 * j).noalias() =
			P.leftCols<3>() * h[j].d_robot.transpose() + P.middleCols<2>(il) * h[j].d_landmark.transpose();
		innovation.segment<2>(2 * j) = matches[j].z - h[j].z;
		innovation(2 * j + 1) = wrapAngle(innovation(2 * j + 1));
	}

	// Eq. (1.10): S = H P H^T + R, read off the rows of P H^T.
	Eigen::MatrixXd S(2 * m, 2 * m);
	for (std::size_t j = 0; j < m; ++j)
	{
		const std::size_t il = 3 + 2 * matches[j].landmark;
		S.middleRows<2>(2 * j).noalias() =
			h[j].d_robot * PHt.topRows<3>() + h[j].d_landmark * PHt.middleRows<2>(il);
	}
	S = 0.5 * (S + S.transpose()).eval();
	for (std::size_t j = 0; j < m; ++j) S.block<2, 2>(2 * j, 2 * j) += matches[j].R;

	const Eigen::LLT<Eigen::MatrixXd> llt(S);
	if (llt.info() != Eigen::Success)
		throw NumericalError("EKF update: innovation covariance is not positive definite");

	// Eq. (1.9) with K = P H^T S^-1 = W L^-1, W = P H^T L^-T (S = L L^T):
	// x += W L^-1 nu and P -= W W^T, the latter as one symmetric rank update.
	const Eigen::MatrixXd Wt = llt.matrixL().solve(PHt.transpose());
	const Eigen::VectorXd v = llt.matrixL().solve(innovation);
	x_.head(n).noalias() += Wt.transpose() * v;
	x_(2) = wrapAngle(x_(2));
	auto Pn = P_.topLeftCorner(n, n);
	Pn.selfadjointView<Eigen::Lower>().rankUpdate(Wt.transpose(), -1.0);
	symmetrise();

	if (!x_.head(n).allFinite() || !(P_(0, 0) >= 0 && P_(1, 1) >= 0 && P_(2, 2) >= 0))
		throw NumericalError("EKF update produced a non-finite state or negative variance");
}

std::size_t EkfSlamCore::addLandmark(const Eigen::Vector2d& z, const Eigen::Matrix2d& R, const Pose2& sensor_on_robot)
{
	const auto init = landmarkFromRangeBearing(robot(), sensor_on_robot, z(0), z(1));
	const std::size_t i = n_;
	reserve(n_ + 2);
	x_.segment<2>(i) = init.position;

	// Cross-covariance with everything known so far: G_x P_r,: (O(n)).
	const Eigen::MatrixXd cross = init.d_robot * P_.topLeftCorner(3, n_);
	P_.block(i, 0, 2, n_) = cross;
	P_.block(0, i, n_, 2) = cross.transpose();
	P_.block<2, 2>(i, i) = init.d_robot * P_.topLeftCorner<3, 3>() * init.d_robot.transpose() +
		init.d_measurement * R * init.d_measurement.transpose();
	n_ += 2;
	return landmarkCount() - 1;
}

void EkfSlamCore::retainLandmarks(const std::vector<std::size_t>& keep)
{
	std::vector<Eigen::Index> rows = {0, 1, 2};
	for (std::size_t i : keep)
	{
		if (i >= landmarkCount()) throw std::invalid_argument("EkfSlamCore::retainLandmarks: no such landmark");
		rows.push_back(static_cast<Eigen::Index>(3 + 2 * i));
		rows.push_back(static_cast<Eigen::Index>(4 + 2 * i));
	}
	const Eigen::VectorXd x = x_(rows);
	const Eigen::MatrixXd P = P_(rows, rows);
	setState(x, P);
}

void EkfSlamCore::setState(const Eigen::VectorXd& x, const Eigen::MatrixXd& P)
{
	const auto n = static_cast<std::size_t>(x.size());
	if (n < 3 || (n - 3) % 2 != 0 || P.rows() != x.size() || P.cols() != x.size())
		throw std::invalid_argument("EkfSlamCore::setState: expected [robot(3); landmarks(2 each)] and a matching P");
	reserve(n);
	n_ = n;
	x_.head(n) = x;
	x_(2) = wrapAngle(x_(2));
	P_.topLeftCorner(n, n) = 0.5 * (P + P.transpose());
}

void EkfSlamCore::symmetrise()
{
	// rankUpdate wrote the lower triangle only; mirror it so the whole matrix
	// is exactly symmetric for the column reads of the next update.
	auto P = P_.topLeftCorner(n_, n_);
	P.triangularView<Eigen::StrictlyUpper>() = P.transpose();
}

}  // namespace esif
