// The whole-state NEES (eval/StateNees.h) on linear-Gaussian states where
// the answer is known: draws from N(x_ref, I^-1) give NEES ~ chi-square(dof),
// and marginalising a variable must equal the dense Schur complement.
#include <esif/core/Errors.h>
#include <esif/eval/StateNees.h>

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <random>

namespace esif
{
namespace
{
/// Landmarks 1, 2 and the pose after step 0: 7 scalars.
std::vector<StateVariable> toyVariables()
{
	return {StateVariable::landmarkOf(1), StateVariable::poseOf(0), StateVariable::landmarkOf(2)};
}

/// A fixed, well-conditioned but strongly correlated information matrix.
Eigen::MatrixXd toyInformation()
{
	std::mt19937 rng(7);
	std::normal_distribution<double> n01;
	Eigen::MatrixXd A(7, 7);
	for (int i = 0; i < 7; ++i)
		for (int j = 0; j < 7; ++j) A(i, j) = n01(rng);
	return A * A.transpose() + 0.5 * Eigen::MatrixXd::Identity(7, 7);
}

Eigen::VectorXd toyReferenceVector() { return (Eigen::VectorXd(7) << 10, -2, 1, 2, 0.3, -4, 6).finished(); }

StateReference toyReference(bool with_pose = true)
{
	const Eigen::VectorXd r = toyReferenceVector();
	StateReference ref;
	ref.landmarks[1] = r.segment<2>(0);
	ref.landmarks[2] = r.segment<2>(5);
	if (with_pose) ref.poses_by_step[0] = r.segment<3>(2);
	return ref;
}

StateInformation stateAt(const Eigen::VectorXd& x, const Eigen::MatrixXd& I)
{
	StateInformation s;
	s.variables = toyVariables();
	s.mean = x;
	s.information = I.sparseView();
	return s;
}
}  // namespace

TEST(StateNees, TheIntervalIsTheTwoSidedChiSquareQuantiles)
{
	// One landmark: 2 dof, where chi2inv(0.025, 2) = -2 ln(0.975) and
	// chi2inv(0.975, 2) = -2 ln(0.025) in closed form.
	StateInformation one;
	one.variables = {StateVariable::landmarkOf(1)};
	one.mean = Eigen::Vector2d(0.3, -0.4);
	one.information = Eigen::MatrixXd(Eigen::Matrix2d::Identity()).sparseView();
	StateReference reference;
	reference.landmarks[1] = Eigen::Vector2d::Zero();
	const auto n = stateNees(one, reference, std::nullopt, "one landmark");
	ASSERT_TRUE(n);
	EXPECT_EQ(n->dof, 2u);
	EXPECT_NEAR(n->nees, 0.25, 1e-12);
	EXPECT_NEAR(n->lower95, -2 * std::log(0.975), 1e-12);
	EXPECT_NEAR(n->upper95, -2 * std::log(0.025), 1e-12);
}

TEST(StateNees, DrawsFromTheStatedGaussianAreChiSquare)
{
	const Eigen::MatrixXd I = toyInformation();
	const Eigen::MatrixXd L = Eigen::MatrixXd(I.inverse()).llt().matrixL();  // 7x7: the test's own sampler
	std::mt19937 rng(42);
	std::normal_distribution<double> n01;
	const int draws = 4000;
	double sum = 0;
	int inside = 0;
	for (int d = 0; d < draws; ++d)
	{
		Eigen::VectorXd z(7);
		for (int i = 0; i < 7; ++i) z(i) = n01(rng);
		const auto nees = stateNees(stateAt(toyReferenceVector() + L * z, I), toyReference(), std::nullopt, "toy");
		ASSERT_TRUE(nees);
		EXPECT_EQ(nees->dof, 7u);
		EXPECT_EQ(nees->landmarks_compared, 2u);
		EXPECT_EQ(nees->poses_compared, 1u);
		sum += nees->nees;
		inside += nees->consistent() ? 1 : 0;
	}
	// Mean of chi-square(7): 7, standard error sqrt(2 * 7 / 4000) = 0.059; 5 sigma.
	EXPECT_NEAR(sum / draws, 7.0, 0.30);
	// 95% inside, standard error sqrt(0.95 * 0.05 / 4000) = 0.0034; 5 sigma.
	EXPECT_NEAR(static_cast<double>(inside) / draws, 0.95, 0.018);
}

TEST(StateNees, OverConfidenceIsCaught)
{
	// The same draws stated with 4x the information: NEES ~ 4 chi-square(7).
	const Eigen::MatrixXd I = toyInformation();
	const Eigen::MatrixXd L = Eigen::MatrixXd(I.inverse()).llt().matrixL();
	std::mt19937 rng(3);
	std::normal_distribution<double> n01;
	double sum = 0;
	for (int d = 0; d < 1000; ++d)
	{
		Eigen::VectorXd z(7);
		for (int i = 0; i < 7; ++i) z(i) = n01(rng);
		sum += stateNees(stateAt(toyReferenceVector() + L * z, 4 * I), toyReference(), std::nullopt, "toy")->nees;
	}
	EXPECT_NEAR(sum / 1000, 28.0, 1.5);	 // standard error 4 sqrt(14 / 1000) = 0.47
}

TEST(StateNees, AVariableWithoutReferenceIsMarginalisedNotDropped)
{
	const Eigen::MatrixXd I = toyInformation();
	Eigen::VectorXd x = toyReferenceVector();
	x += (Eigen::VectorXd(7) << 0.3, -0.2, 0.5, 0.1, 0.05, -0.4, 0.2).finished();
	const auto nees = stateNees(stateAt(x, I), toyReference(false), std::nullopt, "toy");
	ASSERT_TRUE(nees);
	EXPECT_EQ(nees->dof, 4u);
	EXPECT_EQ(nees->poses_compared, 0u);
	EXPECT_EQ(nees->variables_marginalised, 1u);
	// Dense: the marginal covariance of the landmarks is the sub-block of I^-1.
	const Eigen::MatrixXd P = I.inverse();
	Eigen::MatrixXd P_ll(4, 4);
	const int idx[4] = {0, 1, 5, 6};
	for (int i = 0; i < 4; ++i)
		for (int j = 0; j < 4; ++j) P_ll(i, j) = P(idx[i], idx[j]);
	Eigen::VectorXd e(4);
	for (int i = 0; i < 4; ++i) e(i) = x(idx[i]) - toyReferenceVector()(idx[i]);
	const double dense = e.dot(P_ll.ldlt().solve(e));
	EXPECT_NEAR(nees->nees, dense, 1e-9 * dense);
	// Dropping the pose instead (using I's landmark block) would be wrong here.
	Eigen::MatrixXd I_ll(4, 4);
	for (int i = 0; i < 4; ++i)
		for (int j = 0; j < 4; ++j) I_ll(i, j) = I(idx[i], idx[j]);
	EXPECT_GT(std::abs(e.dot(I_ll * e) - dense), 1e-3 * dense);
}

TEST(StateNees, HeadingErrorIsWrapped)
{
	const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(7, 7);
	Eigen::VectorXd x = toyReferenceVector();
	StateReference ref = toyReference();
	ref.poses_by_step[0](2) = M_PI - 0.05;
	x(4) = -M_PI + 0.05;  // 0.1 rad away across the cut
	EXPECT_NEAR(stateNees(stateAt(x, I), ref, std::nullopt, "toy")->nees, 0.01, 1e-12);
}

TEST(StateNees, LandmarksArePairedThroughTheMapping)
{
	const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(7, 7);
	StateReference ref = toyReference();
	ref.landmarks = {{10, ref.landmarks.at(1) + Eigen::Vector2d(1, 0)}, {20, ref.landmarks.at(2)}};
	const std::map<LandmarkId, LandmarkId> to_ref{{1, 10}, {2, 20}};
	const auto nees = stateNees(stateAt(toyReferenceVector(), I), ref, to_ref, "toy");
	EXPECT_NEAR(nees->nees, 1.0, 1e-12);
	EXPECT_EQ(nees->landmarks_compared, 2u);
	// Unmapped landmark 2: marginalised.
	const auto partial = stateNees(stateAt(toyReferenceVector(), I), ref, std::map<LandmarkId, LandmarkId>{{1, 10}}, "toy");
	EXPECT_EQ(partial->landmarks_compared, 1u);
	EXPECT_EQ(partial->variables_marginalised, 1u);
}

TEST(StateNees, PosesPairByLocalMapWhenTheyHaveNoStep)
{
	StateInformation s = stateAt(toyReferenceVector(), Eigen::MatrixXd::Identity(7, 7));
	s.variables[1] = StateVariable::poseOf(std::nullopt, 3);
	StateReference ref = toyReference(false);
	ref.poses_by_local_map[3] = toyReferenceVector().segment<3>(2) + Eigen::Vector3d(0, 2, 0);
	const auto nees = stateNees(s, ref, std::nullopt, "toy");
	EXPECT_EQ(nees->poses_compared, 1u);
	EXPECT_NEAR(nees->nees, 4.0, 1e-12);
}

TEST(StateNees, NothingComparableGivesNothing)
{
	StateReference empty;
	EXPECT_FALSE(stateNees(stateAt(toyReferenceVector(), toyInformation()), empty, std::nullopt, "toy"));
}

TEST(StateNees, SingularInformationOfTheMarginalisedPartIsAnErrorNamingTheRun)
{
	Eigen::MatrixXd I = Eigen::MatrixXd::Identity(7, 7);
	I(2, 2) = I(3, 3) = I(4, 4) = 0;  // the pose is not observed at all
	try
	{
		stateNees(stateAt(toyReferenceVector(), I), toyReference(false), std::nullopt, "run X");
		FAIL() << "no error";
	}
	catch (const NumericalError& e)
	{
		EXPECT_NE(std::string(e.what()).find("run X"), std::string::npos);
	}
}

TEST(StateNees, TruthAndRunReferencesPairPosesByStep)
{
	GroundTruth truth;
	truth.landmarks[4] = {1, 2};
	truth.path = {Pose2(0, 0, 0), Pose2(1, 0, 0.1)};
	const StateReference r = stateReferenceOf(truth);
	EXPECT_EQ(r.poses_by_step.size(), 2u);
	EXPECT_DOUBLE_EQ(r.poses_by_step.at(1)(2), 0.1);
	RunOutputs run;
	run.landmarks = {{4, {1, 2}, Eigen::Matrix2d::Identity()}};
	run.trajectory = {{0.0, {0, 0, 0}}, {1.0, {1, 0, 0.1}}};
	EXPECT_EQ(stateReferenceOf(run, 2).poses_by_step.size(), 2u);
	EXPECT_TRUE(stateReferenceOf(run, 3).poses_by_step.empty());  // rows cannot be paired with steps
	EXPECT_EQ(stateReferenceOf(run, 3).landmarks.size(), 1u);
}

}  // namespace esif
