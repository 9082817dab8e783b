#include <esif/core/Errors.h>
#include <esif/ekf/EkfSlamCore.h>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <algorithm>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace esif
{
namespace
{
/// The planar cross-product matrix J = [0 -1; 1 0] times v: d(R(phi) v)/dphi.
Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }
}  // namespace

EkfSlamCore::EkfSlamCore(JacobianPoints points) : points_(points)
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
	const Pose2 delta = u.delta;
	const auto J = composeJacobians(robot(), delta);
	x_.head<3>() = compose(robot(), delta);

	// d_a = [I, J (p_{k+1|k} - p_{k|k}); 0, 1]; FEJ (JacobianPoints) takes
	// the position difference from the prior p_{k|k-1} instead.
	Eigen::Matrix3d F = J.d_a;
	if (useFirstEstimates())
		F.topRightCorner<2, 1>() = perp(x_.head<2>() - robot_prior_.head<2>());
	robot_prior_ = robot();

	// Eq. (1.8) with the Jacobian blkdiag(F, I): only robot rows/cols change.
	const std::size_t m = n_ - 3;
	Eigen::Matrix3d Prr = P_.topLeftCorner<3, 3>();
	P_.topLeftCorner<3, 3>() = F * Prr * F.transpose() + J.d_b * u.cov * J.d_b.transpose();
	if (m > 0)
	{
		const Eigen::MatrixXd Prm = F * P_.block(0, 3, 3, m);
		P_.block(0, 3, 3, m) = Prm;
		P_.block(3, 0, m, 3) = Prm.transpose();
	}
	P_.topLeftCorner<3, 3>() = 0.5 * (P_.topLeftCorner<3, 3>() + P_.topLeftCorner<3, 3>().transpose()).eval();
}

RangeBearingPrediction EkfSlamCore::predictMeasurement(std::size_t i, const Pose2& sensor_on_robot) const
{
	return measurementModel(i, sensor_on_robot, x_, useFirstEstimates());
}

RangeBearingPrediction EkfSlamCore::measurementModel(
	std::size_t i, const Pose2& sensor_on_robot, const Eigen::VectorXd& at, bool first_estimates) const
{
	auto h = predictRangeBearing(at.head<3>(), sensor_on_robot, at.segment<2>(3 + 2 * i));
	if (first_estimates)
	{
		const auto fej = predictRangeBearing(robot_prior_, sensor_on_robot, first_estimates_[i]);
		h.d_robot = fej.d_robot;
		h.d_landmark = fej.d_landmark;
	}
	return h;
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

EkfSlamCore::Linearisation EkfSlamCore::linearise(const std::vector<Match>& matches, const Pose2& sensor_on_robot,
												 const Eigen::VectorXd& at, bool first_estimates) const
{
	const std::size_t m = matches.size(), n = n_;
	const auto P = P_.topLeftCorner(n, n);
	Linearisation lin{Eigen::MatrixXd(n, 2 * m), Eigen::MatrixXd(2 * m, 2 * m), Eigen::VectorXd(2 * m), {}, {},
					  std::vector<RangeBearingPrediction>(m)};
	auto& h = lin.h;

	// P H^T built from the 5 columns each measurement touches: O(n m).
	for (std::size_t j = 0; j < m; ++j)
	{
		const std::size_t il = 3 + 2 * matches[j].landmark;
		h[j] = measurementModel(matches[j].landmark, sensor_on_robot, at, first_estimates);
		lin.PHt.middleCols<2>(2 * j).noalias() =
			P.leftCols<3>() * h[j].d_robot.transpose() + P.middleCols<2>(il) * h[j].d_landmark.transpose();
		lin.innovation.segment<2>(2 * j) = matches[j].z - h[j].z;
		lin.innovation(2 * j + 1) = wrapAngle(lin.innovation(2 * j + 1));
		// Linearised at `at` rather than at the prior mean x0 (iterated EKF),
		// the innovation is z - h(at) - H (x0 - at); at x0 the term is zero.
		Eigen::Vector3d dr = x_.head<3>() - at.head<3>();
		dr(2) = wrapAngle(dr(2));
		lin.innovation.segment<2>(2 * j) -=
			h[j].d_robot * dr + h[j].d_landmark * (x_.segment<2>(il) - at.segment<2>(il));
	}

	// Eq. (1.10): S = H P H^T + R, read off the rows of P H^T.
	for (std::size_t j = 0; j < m; ++j)
	{
		const std::size_t il = 3 + 2 * matches[j].landmark;
		lin.S.middleRows<2>(2 * j).noalias() =
			h[j].d_robot * lin.PHt.topRows<3>() + h[j].d_landmark * lin.PHt.middleRows<2>(il);
	}
	lin.S = 0.5 * (lin.S + lin.S.transpose()).eval();
	for (std::size_t j = 0; j < m; ++j) lin.S.block<2, 2>(2 * j, 2 * j) += matches[j].R;

	lin.llt.compute(lin.S);
	if (lin.llt.info() != Eigen::Success)
		throw NumericalError("EKF update: innovation covariance is not positive definite");
	lin.Wt = lin.llt.matrixL().solve(lin.PHt.transpose());
	return lin;
}

UpdateOutcome EkfSlamCore::update(
	const std::vector<Match>& matches, const Pose2& sensor_on_robot, const IteratedUpdate& iterated)
{
	UpdateOutcome out;
	if (matches.empty()) return out;
	const std::size_t n = n_;

	// Eq. (1.9)-(1.10) linearised at the prior mean x0, then, if the model
	// is not linear at the scale of that correction, Gauss-Newton on the
	// scan's posterior (iterated EKF): each iteration relinearises h at the
	// last estimate x_i and sets x_{i+1} = x0 + K_i (z - h(x_i) - H_i (x0 - x_i)),
	// until one moves no state entry by more than the tolerance. Each costs
	// O(n m^2); P is updated once, with H at the last linearisation point,
	// or with FEJ (JacobianPoints) at the FEJ points, to keep the null space.
	// Gauss-Newton has no step control, and from a poor linearisation it can
	// step uphill: an iterate is only taken while it lowers the scan's
	// posterior cost (scanCost), else the last accepted one stands.
	const Eigen::VectorXd x0 = x_.head(n);
	Linearisation lin = linearise(matches, sensor_on_robot, x0, useFirstEstimates());
	Eigen::VectorXd x_next = stateAfter(lin);
	out.linearisations = 1;
	if (iterated.max_iterations > 1)
		out.linearisation_error_d2 = linearisationError(matches, sensor_on_robot, lin, x0, x_next);
	std::optional<Linearisation> at_fej_points;
	if (out.linearisation_error_d2 > iterated.min_linearisation_error_d2)
	{
		double cost = scanCost(matches, sensor_on_robot, lin, x_next);
		while (out.linearisations < iterated.max_iterations)
		{
			const Eigen::VectorXd x_i = x_next;
			Linearisation at_x_i = linearise(matches, sensor_on_robot, x_i, false);
			Eigen::VectorXd x_candidate = stateAfter(at_x_i);
			++out.linearisations;
			const double candidate_cost = scanCost(matches, sensor_on_robot, at_x_i, x_candidate);
			if (!(candidate_cost < cost))
			{
				out.stopped_uphill = true;
				break;
			}
			if (useFirstEstimates() && !at_fej_points) at_fej_points = std::move(lin);
			lin = std::move(at_x_i);
			x_next = std::move(x_candidate);
			cost = candidate_cost;
			Eigen::VectorXd step = x_next - x_i;
			step(2) = wrapAngle(step(2));
			if (step.lpNorm<Eigen::Infinity>() <= iterated.tolerance) break;
		}
	}

	// P -= W W^T (K S K^T of eq. 1.9) as one symmetric rank update.
	x_.head(n) = x_next;
	auto Pn = P_.topLeftCorner(n, n);
	Pn.selfadjointView<Eigen::Lower>().rankUpdate((at_fej_points ? at_fej_points->Wt : lin.Wt).transpose(), -1.0);
	symmetrise();

	if (!x_.head(n).allFinite() || !(P_(0, 0) >= 0 && P_(1, 1) >= 0 && P_(2, 2) >= 0))
		throw NumericalError("EKF update produced a non-finite state or negative variance");
	return out;
}

double EkfSlamCore::linearisationError(const std::vector<Match>& matches, const Pose2& sensor_on_robot,
									   const Linearisation& at_x0, const Eigen::VectorXd& x0,
									   const Eigen::VectorXd& x1) const
{
	Eigen::Vector3d dr = x1.head<3>() - x0.head<3>();
	dr(2) = wrapAngle(dr(2));
	double worst = 0;
	for (std::size_t j = 0; j < matches.size(); ++j)
	{
		const auto& match = matches[j];
		const std::size_t il = 3 + 2 * match.landmark;
		// The nonlinearity of h at the scale of the correction, whatever the
		// Jacobians of the update: with FEJ, those at the FEJ points would
		// add the distance of the landmarks from their first estimates and
		// iterate (and so relinearise away from the FEJ points) many updates
		// that are linear (measured: 12-30 updates per run on wrong_ids and
		// clutter instead of 1-7, landmark ANEES 6.1 and 14.8 instead of
		// 2.6 and 3.0 without iterating).
		const auto h0 = useFirstEstimates() ? measurementModel(match.landmark, sensor_on_robot, x0, false) : at_x0.h[j];
		const auto h1 = predictRangeBearing(x1.head<3>(), sensor_on_robot, x1.segment<2>(il));
		Eigen::Vector2d e = h1.z - h0.z - h0.d_robot * dr - h0.d_landmark * (x1.segment<2>(il) - x0.segment<2>(il));
		e(1) = wrapAngle(e(1));
		worst = std::max(worst, e.dot(match.R.ldlt().solve(e)));
	}
	return worst;
}

double EkfSlamCore::scanCost(const std::vector<Match>& matches, const Pose2& sensor_on_robot,
							 const Linearisation& lin, const Eigen::VectorXd& x) const
{
	// x - x0 = P H^T a with a = S^-1 innovation (stateAfter), so the prior
	// term (x - x0)^T P^-1 (x - x0) is a^T H P H^T a = a^T (S - R) a.
	const Eigen::VectorXd a = lin.llt.solve(lin.innovation);
	Eigen::MatrixXd HPHt = lin.S;
	for (std::size_t j = 0; j < matches.size(); ++j) HPHt.block<2, 2>(2 * j, 2 * j) -= matches[j].R;
	double cost = a.dot(HPHt * a);
	for (const Match& match : matches)
	{
		const std::size_t il = 3 + 2 * match.landmark;
		Eigen::Vector2d r = match.z - predictRangeBearing(x.head<3>(), sensor_on_robot, x.segment<2>(il)).z;
		r(1) = wrapAngle(r(1));
		cost += r.dot(match.R.ldlt().solve(r));
	}
	return cost;
}

Eigen::VectorXd EkfSlamCore::stateAfter(const Linearisation& lin) const
{
	// Eq. (1.9) with K = P H^T S^-1 = W L^-1, W = P H^T L^-T (S = L L^T).
	Eigen::VectorXd x = x_.head(n_);
	x.noalias() += lin.Wt.transpose() * lin.llt.matrixL().solve(lin.innovation);
	x(2) = wrapAngle(x(2));
	return x;
}

std::size_t EkfSlamCore::addLandmark(const Eigen::Vector2d& z, const Eigen::Matrix2d& R, const Pose2& sensor_on_robot)
{
	const auto init = landmarkFromRangeBearing(robot(), sensor_on_robot, z(0), z(1));
	const std::size_t i = n_;
	reserve(n_ + 2);
	x_.segment<2>(i) = init.position;
	first_estimates_.push_back(init.position);

	// G_x = [I, J (p_L - p_R)]; FEJ (JacobianPoints) takes it about the
	// robot's prior p_{k|k-1}, so that G_x maps the robot's rotation
	// direction [J p_{k|k-1}; 1] onto J p_L, the new landmark's.
	Eigen::Matrix<double, 2, 3> Gx = init.d_robot;
	if (useFirstEstimates()) Gx.col(2) = perp(init.position - robot_prior_.head<2>());

	// Cross-covariance with everything known so far: G_x P_r,: (O(n)).
	const Eigen::MatrixXd cross = Gx * P_.topLeftCorner(3, n_);
	P_.block(i, 0, 2, n_) = cross;
	P_.block(0, i, n_, 2) = cross.transpose();
	P_.block<2, 2>(i, i) = Gx * P_.topLeftCorner<3, 3>() * Gx.transpose() +
		init.d_measurement * R * init.d_measurement.transpose();
	n_ += 2;
	return landmarkCount() - 1;
}

void EkfSlamCore::retainLandmarks(const std::vector<std::size_t>& keep)
{
	std::vector<Eigen::Index> rows = {0, 1, 2};
	std::vector<Eigen::Vector2d> first_estimates;
	for (std::size_t i : keep)
	{
		if (i >= landmarkCount()) throw std::invalid_argument("EkfSlamCore::retainLandmarks: no such landmark");
		rows.push_back(static_cast<Eigen::Index>(3 + 2 * i));
		rows.push_back(static_cast<Eigen::Index>(4 + 2 * i));
		first_estimates.push_back(first_estimates_[i]);
	}
	const Eigen::VectorXd x = x_(rows);
	const Eigen::MatrixXd P = P_(rows, rows);
	replaceState(x, P);
	first_estimates_ = std::move(first_estimates);
}

double EkfSlamCore::coincidenceDistance2(std::size_t a, std::size_t b) const
{
	const auto ia = static_cast<Eigen::Index>(3 + 2 * a), ib = static_cast<Eigen::Index>(3 + 2 * b);
	const Eigen::Vector2d d = x_.segment<2>(ia) - x_.segment<2>(ib);
	const Eigen::Matrix2d S =
		P_.block<2, 2>(ia, ia) + P_.block<2, 2>(ib, ib) - P_.block<2, 2>(ia, ib) - P_.block<2, 2>(ib, ia);
	const Eigen::LLT<Eigen::Matrix2d> llt(S);
	if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
	return d.dot(llt.solve(d));
}

bool EkfSlamCore::mergeLandmarks(std::size_t keep, std::size_t drop)
{
	if (keep == drop || keep >= landmarkCount() || drop >= landmarkCount())
		throw std::invalid_argument("EkfSlamCore::mergeLandmarks: no such pair of landmarks");
	const auto n = static_cast<Eigen::Index>(n_);
	const auto ia = static_cast<Eigen::Index>(3 + 2 * keep), ib = static_cast<Eigen::Index>(3 + 2 * drop);
	// z = x_keep - x_drop = 0 observed without noise: H = [.. I .. -I ..],
	// S = H P H^T, K = P H^T S^-1 (eq. 1.9 with R = 0); P -= W W^T as in
	// update(), W = P H^T L^-T.
	const Eigen::MatrixXd PHt = P_.block(0, ia, n, 2) - P_.block(0, ib, n, 2);
	const Eigen::Matrix2d S = PHt.block<2, 2>(ia, 0) - PHt.block<2, 2>(ib, 0);
	const Eigen::LLT<Eigen::Matrix2d> llt(0.5 * (S + S.transpose()));
	if (llt.info() != Eigen::Success) return false;
	const Eigen::Vector2d innovation = x_.segment<2>(ib) - x_.segment<2>(ia);
	const Eigen::MatrixXd Wt = llt.matrixL().solve(PHt.transpose());	// L^-1 (P H^T)^T
	x_.head(n) += Wt.transpose() * llt.matrixL().solve(innovation);
	x_(2) = wrapAngle(x_(2));
	P_.topLeftCorner(n, n).selfadjointView<Eigen::Lower>().rankUpdate(Wt.transpose(), -1.0);
	symmetrise();
	std::vector<std::size_t> rest;
	for (std::size_t i = 0; i < landmarkCount(); ++i)
		if (i != drop) rest.push_back(i);
	retainLandmarks(rest);
	return true;
}

void EkfSlamCore::setState(const Eigen::VectorXd& x, const Eigen::MatrixXd& P)
{
	replaceState(x, P);
	robot_prior_ = robot();
	first_estimates_.clear();
	for (std::size_t i = 0; i < landmarkCount(); ++i) first_estimates_.push_back(landmark(i));
}

void EkfSlamCore::replaceState(const Eigen::VectorXd& x, const Eigen::MatrixXd& P)
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
