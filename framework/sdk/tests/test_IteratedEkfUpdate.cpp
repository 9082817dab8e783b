// The iterated EKF update (EkfSlamCore, IteratedUpdate) and what it is for:
// the ID gate of LandmarkEkf must not reject the valid re-observations of a
// loop closed after a long stretch of dead reckoning (configs/sim/long_gap.ini),
// while a misread ID among correct measurements is still rejected.

#include <esif/ekf/EkfSlamCore.h>
#include <esif/ekf/LandmarkEkf.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

namespace
{
using namespace esif;

const Pose2 kSensor(0.2, 0.05, 0.1);
constexpr double kDeg = M_PI / 180.0;
/// The book's sensor noise (Sec. 1.3.3): 0.1 m range, 1 deg bearing.
const Eigen::Matrix2d kR = Eigen::Vector2d(0.01, std::pow(1 * kDeg, 2)).asDiagonal();

/// A robot with a large, correlated uncertainty (a long drive by odometry)
/// and three landmarks mapped on the way.
EkfSlamCore uncertainCore()
{
	EkfSlamCore core;
	core.addLandmark({4.0, 0.3}, kR, kSensor);
	OdometryIncrement u;
	u.delta = {0.5, 0.0, 0.0};
	u.cov = Eigen::Vector3d(0.02, 0.02, std::pow(0.5 * kDeg, 2)).asDiagonal();
	for (int k = 0; k < 10; ++k) core.predict(u);
	core.addLandmark({3.0, -0.6}, kR, kSensor);
	core.addLandmark({2.5, 0.9}, kR, kSensor);
	return core;
}

/// The scan's MAP estimate, min (x - x0)' P0^-1 (x - x0) + sum r' R^-1 r,
/// by dense Gauss-Newton in the information form: the reference the
/// iterated EKF (its covariance form) must reach.
Eigen::VectorXd denseMap(const EkfSlamCore& prior, const std::vector<EkfSlamCore::Match>& matches)
{
	const Eigen::VectorXd x0 = prior.state();
	const Eigen::MatrixXd P0inv = Eigen::MatrixXd(prior.covariance()).inverse();  // small n: reference only
	Eigen::VectorXd x = x0;
	for (int it = 0; it < 50; ++it)
	{
		Eigen::MatrixXd A = P0inv;
		Eigen::VectorXd dx0 = x - x0;
		dx0(2) = wrapAngle(dx0(2));
		Eigen::VectorXd g = P0inv * dx0;
		for (const auto& m : matches)
		{
			const std::size_t il = 3 + 2 * m.landmark;
			const auto h = predictRangeBearing(x.head<3>(), kSensor, x.segment<2>(il));
			Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, x.size());
			H.leftCols<3>() = h.d_robot;
			H.middleCols<2>(il) = h.d_landmark;
			Eigen::Vector2d r = m.z - h.z;
			r(1) = wrapAngle(r(1));
			A += H.transpose() * m.R.inverse() * H;
			g -= H.transpose() * m.R.inverse() * r;
		}
		const Eigen::VectorXd step = -A.ldlt().solve(g);
		x += step;
		if (step.cwiseAbs().maxCoeff() < 1e-12) break;
	}
	return x;
}

TEST(IteratedEkfUpdate, ReachesTheMapEstimateOfTheScan)
{
	const EkfSlamCore prior = uncertainCore();
	// The robot is 2.5 m and 6 deg from where the prior puts it: landmark 0
	// (4 m ahead when mapped) is re-observed far from its prediction.
	const Pose2 truth = prior.robot() + Pose2(-1.0, 0.6, 2 * kDeg);
	std::vector<EkfSlamCore::Match> matches;
	for (std::size_t i = 0; i < 3; ++i)
		matches.push_back({i, predictRangeBearing(truth, kSensor, prior.landmark(i)).z, kR});

	EkfSlamCore plain = prior, iterated = prior;
	const auto plain_out = plain.update(matches, kSensor);
	const auto out = iterated.update(matches, kSensor, {200, 1.0, 1e-10});
	const Eigen::VectorXd map = denseMap(prior, matches);
	std::cout << "linearisation error " << out.linearisation_error_d2 << " sigma^2, " << out.linearisations
			  << " linearisations; robot: plain EKF " << plain.robot().transpose() << ", iterated "
			  << iterated.robot().transpose() << ", MAP " << map.head<3>().transpose() << "\n";
	EXPECT_EQ(plain_out.linearisations, 1);
	EXPECT_GT(out.linearisation_error_d2, 1.0);
	EXPECT_GT(out.linearisations, 2);
	// Gauss-Newton in covariance form and in information form reach the
	// same minimum: equal to far below the noise (1e-6 m against 0.1 m).
	EXPECT_LT((Eigen::VectorXd(iterated.state()) - map).cwiseAbs().maxCoeff(), 1e-6);
	// The plain update does not: its single linear step misses the MAP by
	// more than a sensor sigma.
	EXPECT_GT((plain.robot() - map.head<3>()).head<2>().norm(), 0.1);
	const Eigen::MatrixXd P = iterated.covariance();
	EXPECT_EQ((P - P.transpose()).cwiseAbs().maxCoeff(), 0.0);
	EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(P).info(), Eigen::Success);
}

/// The scan's posterior cost (x - x0)' P0^-1 (x - x0) + sum r' R^-1 r,
/// densely (small n: reference only).
double denseScanCost(const EkfSlamCore& prior, const std::vector<EkfSlamCore::Match>& matches, const Eigen::VectorXd& x)
{
	Eigen::VectorXd dx = x - prior.state();
	dx(2) = wrapAngle(dx(2));
	double cost = dx.dot(Eigen::MatrixXd(prior.covariance()).ldlt().solve(dx));
	for (const auto& m : matches)
	{
		Eigen::Vector2d r = m.z - predictRangeBearing(x.head<3>(), kSensor, x.segment<2>(3 + 2 * m.landmark)).z;
		r(1) = wrapAngle(r(1));
		cost += r.dot(m.R.inverse() * r);
	}
	return cost;
}

TEST(IteratedEkfUpdate, NeverTakesAnIterateThatRaisesTheScanCost)
{
	// Gauss-Newton has no step control: from a poor linearisation an
	// iterate can land uphill (on clusters.ini, noise seed 4, such updates
	// left the EKF 2.0 m off with mean landmark NEES 160; 0.34 m without).
	// Robots far off their prior, in heading above all, make such steps;
	// the update must end no higher than where it started iterating.
	std::mt19937 rng(7);
	std::normal_distribution<double> gauss;
	int uphill = 0, iterated_updates = 0;
	for (int trial = 0; trial < 200; ++trial)
	{
		const EkfSlamCore prior = uncertainCore();
		const Pose2 truth =
			prior.robot() + Pose2(1.5 * gauss(rng), 1.5 * gauss(rng), 25 * kDeg * gauss(rng));
		std::vector<EkfSlamCore::Match> matches;
		for (std::size_t i = 0; i < 3; ++i)
			matches.push_back({i, predictRangeBearing(truth, kSensor, prior.landmark(i)).z, kR});
		EkfSlamCore plain = prior, iterated = prior;
		plain.update(matches, kSensor);
		const auto out = iterated.update(matches, kSensor, {10, 1.0, 1e-10});
		if (out.linearisations > 1) ++iterated_updates;
		if (out.stopped_uphill) ++uphill;
		EXPECT_LE(denseScanCost(prior, matches, iterated.state()),
				  denseScanCost(prior, matches, plain.state()) * (1 + 1e-9) + 1e-9)
			<< "trial " << trial;
	}
	std::cout << iterated_updates << " of 200 updates iterated, " << uphill << " stopped at an uphill iterate\n";
	// The guard is exercised, not only the easy cases (measured: 77 of the 193 iterated).
	EXPECT_GT(uphill, 0);
}

TEST(IteratedEkfUpdate, AWellLinearisedUpdateIsNotIterated)
{
	const EkfSlamCore prior = uncertainCore();
	std::vector<EkfSlamCore::Match> matches;
	for (std::size_t i = 0; i < 3; ++i)
		matches.push_back({i, prior.predictMeasurement(i, kSensor).z + Eigen::Vector2d(0.05, 0.5 * kDeg), kR});
	EkfSlamCore plain = prior, gated = prior;
	plain.update(matches, kSensor);
	const auto out = gated.update(matches, kSensor, {10, 1.0, 1e-6});
	// Innovations of half a sigma: the linear model misses by far less than
	// the noise, and the update is the plain EKF's, bit for bit.
	EXPECT_LT(out.linearisation_error_d2, 1e-2);
	EXPECT_EQ(out.linearisations, 1);
	EXPECT_EQ(Eigen::VectorXd(gated.state()), Eigen::VectorXd(plain.state()));
	EXPECT_EQ(Eigen::MatrixXd(gated.covariance()), Eigen::MatrixXd(plain.covariance()));
}

/// configs/sim/long_gap.ini in miniature. Landmark 0 is mapped from the
/// start pose; the robot then drives a loop without landmarks and returns
/// to the start, its odometry 3.4 m off (2.1 sigma of the 1.6 m
/// dead-reckoning sigma per axis; heading sigma 0.04 rad: as on long_gap
/// after a 28 m crossing). Back at the start it maps landmarks 1-4 (about
/// 3 m away) for six scans, then sees landmark 0 again (4.6 m away,
/// predicted at 3.8 m and 47 deg off): the loop closure. Measurements are
/// exact; the filter is told the book's sensor sigmas (0.1 m, 1 deg).
class LoopAfterDeadReckoning : public ::testing::Test
{
   protected:
	const std::map<LandmarkId, Eigen::Vector2d> world = {
		{0, {4.8, 0.4}}, {1, {2.0, -2.0}}, {2, {3.0, -1.2}}, {3, {2.5, 2.0}}, {4, {1.0, 3.0}}};
	const Pose2 start = Pose2::Zero();	// the true pose throughout

	StepInput scan(std::size_t index, const std::vector<std::pair<LandmarkId, LandmarkId>>& seen) const
	{
		// seen: (ID reported, landmark truly measured)
		StepInput s;
		s.index = index;
		s.scan = Scan{kSensor, 0, 0, {}};
		for (const auto& [id, truly] : seen)
		{
			const auto z = predictRangeBearing(start, kSensor, world.at(truly)).z;
			s.scan->measurements.push_back({z(0), z(1), kR, id});
		}
		return s;
	}

	StepInput deadReckoning(std::size_t index) const
	{
		StepInput s;
		s.index = index;
		s.odometry = OdometryIncrement{};
		s.odometry->delta = {1.8, 2.9, 0.0};  // the robot really came back to where it started
		s.odometry->cov = Eigen::Vector3d(1.6 * 1.6, 1.6 * 1.6, 0.04 * 0.04).asDiagonal();
		return s;
	}

	/// Runs the loop; returns the kinds of the measurements of each closing scan.
	std::vector<StepReport> run(LandmarkEkf& ekf, std::size_t closing_scans) const
	{
		std::size_t k = 0;
		ekf.processStep(scan(k++, {{0, 0}}));
		ekf.processStep(scan(k++, {{0, 0}}));
		ekf.processStep(deadReckoning(k++));
		for (int i = 0; i < 6; ++i) ekf.processStep(scan(k++, {{1, 1}, {2, 2}, {3, 3}, {4, 4}}));
		std::vector<StepReport> closing;
		for (std::size_t i = 0; i < closing_scans; ++i)
			closing.push_back(ekf.processStep(scan(k++, {{0, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 4}})));
		return closing;
	}

	static std::size_t rejected(const std::vector<StepReport>& reports)
	{
		std::size_t n = 0;
		for (const auto& r : reports)
			for (const auto& a : r.associations) n += a.kind == Association::Kind::Rejected;
		return n;
	}
};

TEST_F(LoopAfterDeadReckoning, TheClosingScansPassTheIdGate)
{
	EkfAssociationParams params;
	params.association = EkfAssociation::KnownIds;
	LandmarkEkf iterated(params);
	const auto closing = run(iterated, 10);
	const Pose2 robot = iterated.core().robot();
	const Eigen::Matrix3d P = iterated.core().robotCov();
	Eigen::Vector3d e = robot - start;
	e(2) = wrapAngle(e(2));
	const double nees = e.dot(P.ldlt().solve(e));
	std::cout << "iterated update: " << rejected(closing) << " of " << 5 * closing.size()
			  << " closing measurements rejected, " << iterated.iteratedUpdates() << " updates iterated; robot error "
			  << e.transpose() << ", NEES " << nees << "\n";
	EXPECT_EQ(rejected(closing), 0u);
	EXPECT_GE(iterated.iteratedUpdates(), 1u);
	// After the closure the robot is where it is, within its own 95%
	// ellipse (chi-square 3 dof: 7.81).
	EXPECT_LT(nees, 7.81);

	// The plain EKF update of the same scans: linearised 3.4 m from the
	// truth, the first closing update overshoots and leaves P too small,
	// and the gate turns the loop's later sightings of landmark 0 away.
	params.update_iterations = 1;
	LandmarkEkf plain(params);
	const auto plain_closing = run(plain, 10);
	Eigen::Vector3d e_plain = plain.core().robot() - start;
	e_plain(2) = wrapAngle(e_plain(2));
	std::cout << "plain update: " << rejected(plain_closing) << " rejected; robot error " << e_plain.transpose()
			  << ", NEES " << e_plain.dot(plain.core().robotCov().ldlt().solve(e_plain)) << "\n";
	EXPECT_GT(rejected(plain_closing), 0u);
}

TEST_F(LoopAfterDeadReckoning, AMisreadAmongCorrectMeasurementsIsStillRejected)
{
	EkfAssociationParams params;
	params.association = EkfAssociation::KnownIds;
	LandmarkEkf ekf(params);
	run(ekf, 3);
	// Landmark 3 read as landmark 4 (1.6 m from it), beside three correct ones.
	const auto report = ekf.processStep(scan(100, {{0, 0}, {1, 1}, {2, 2}, {4, 3}}));
	ASSERT_EQ(report.associations.size(), 4u);
	for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(report.associations[i].kind, Association::Kind::Matched) << i;
	EXPECT_EQ(report.associations[3].kind, Association::Kind::Rejected);
	EXPECT_EQ(ekf.idGateRejections(), 1u);
}

}  // namespace
