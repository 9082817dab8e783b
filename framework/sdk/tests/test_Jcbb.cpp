// JCBB (src/association/Jcbb.h) through associate(): the hypothesis with
// the most jointly compatible pairs and, among those, the smallest joint
// Mahalanobis distance, checked against brute-force enumeration of every
// hypothesis on random problems; and the case MRPT 2.5's search got wrong.

#include <esif/association/Chi2.h>
#include <esif/association/DataAssociation.h>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <random>

namespace
{
using namespace esif;

double jointDistance2(const AssociationInput& in, const std::vector<int>& candidate_of)
{
	std::vector<int> obs, cand;
	for (std::size_t i = 0; i < candidate_of.size(); ++i)
		if (candidate_of[i] >= 0) obs.push_back(static_cast<int>(i)), cand.push_back(candidate_of[i]);
	const auto k = static_cast<Eigen::Index>(obs.size());
	Eigen::VectorXd nu(2 * k);
	Eigen::MatrixXd S(2 * k, 2 * k);
	for (Eigen::Index a = 0; a < k; ++a)
	{
		nu.segment<2>(2 * a) = (in.observations.row(obs[a]) - in.predictions.row(cand[a])).transpose();
		for (Eigen::Index b = 0; b < k; ++b) S.block<2, 2>(2 * a, 2 * b) = in.covariance.block<2, 2>(2 * cand[a], 2 * cand[b]);
	}
	return k == 0 ? 0 : nu.dot(Eigen::LLT<Eigen::MatrixXd>(S).solve(nu));
}

/// Every hypothesis (each observation paired with an unused individually
/// compatible candidate, or not) whose pairs are jointly compatible at `q`
/// as they are added in observation order (Neira & Tardos' definition, on
/// which their branch and bound prunes): the one with the most pairs, then
/// the smallest joint distance.
std::vector<int> bruteForce(const AssociationInput& in, double q)
{
	const Eigen::MatrixXd d2 = individualDistances2(in);
	const auto M = in.observations.rows(), N = in.predictions.rows();
	std::vector<int> current(M, -1), best(M, -1);
	int best_pairs = 0;
	double best_d2 = std::numeric_limits<double>::infinity();
	std::vector<bool> used(N, false);
	std::function<void(Eigen::Index, int)> visit = [&](Eigen::Index i, int pairs) {
		if (i == M)
		{
			if (pairs == 0) return;
			const double d = jointDistance2(in, current);
			if (pairs > best_pairs || (pairs == best_pairs && d < best_d2)) best_pairs = pairs, best_d2 = d, best = current;
			return;
		}
		visit(i + 1, pairs);
		for (Eigen::Index j = 0; j < N; ++j)
			if (!used[j] && d2(i, j) <= chi2Quantile(q, 2))
			{
				used[j] = true;
				current[i] = static_cast<int>(j);
				if (jointDistance2(in, current) <= chi2Quantile(q, 2 * (pairs + 1))) visit(i + 1, pairs + 1);
				current[i] = -1;
				used[j] = false;
			}
	};
	visit(0, 0);
	return best;
}

/// Landmarks in clusters 0.2 m apart seen through a shared robot error:
/// predictions correlated, several candidates per observation.
AssociationInput randomProblem(std::mt19937& rng, int observations, int landmarks)
{
	std::normal_distribution<double> n(0, 1);
	std::uniform_real_distribution<double> u(0, 1);
	AssociationInput in;
	in.predictions.resize(landmarks, 2);
	for (int j = 0; j < landmarks; ++j) in.predictions.row(j) << 3 + 0.2 * (j / 2) + 0.05 * n(rng), 0.04 * j;
	// Robot heading and position noise shared by every prediction, plus R.
	Eigen::MatrixXd H(2 * landmarks, 3);
	for (int j = 0; j < landmarks; ++j) H.block<2, 3>(2 * j, 0) << 1, 0, 0, 0, 1.0 / 3, -1;
	const Eigen::Matrix3d P = Eigen::Vector3d(0.01, 0.01, 0.002).asDiagonal();
	in.covariance = H * P * H.transpose();
	for (int j = 0; j < landmarks; ++j) in.covariance.block<2, 2>(2 * j, 2 * j) += Eigen::Vector2d(0.01, 1e-4).asDiagonal();
	in.observations.resize(observations, 2);
	const Eigen::Vector3d robot_error(0.1 * n(rng), 0.1 * n(rng), 0.04 * n(rng));
	for (int i = 0; i < observations; ++i)
	{
		const int j = static_cast<int>(u(rng) * landmarks);
		in.observations.row(i) = in.predictions.row(j) + (H.block<2, 3>(2 * j, 0) * robot_error).transpose() +
								 Eigen::RowVector2d(0.1 * n(rng), 0.01 * n(rng));
	}
	return in;
}

TEST(Jcbb, FindsTheMostPairsAndThenTheClosestHypothesisAsBruteForceDoes)
{
	std::mt19937 rng(7);
	int ties_broken = 0;
	for (int trial = 0; trial < 300; ++trial)
	{
		const AssociationInput in = randomProblem(rng, 1 + trial % 4, 3 + trial % 5);
		const auto r = associate(in, AssociationMethod::Jcbb, 0.99, SearchBounds{20, 1e12});
		ASSERT_FALSE(r.fell_back);
		const auto expected = bruteForce(in, 0.99);
		EXPECT_EQ(r.candidate_of, expected) << "trial " << trial;
		std::size_t compatible = 0;
		const Eigen::MatrixXd d2 = individualDistances2(in);
		for (Eigen::Index i = 0; i < d2.rows(); ++i) compatible += (d2.row(i).array() <= chi2Quantile(0.99, 2)).count() > 1;
		ties_broken += compatible > 0;
	}
	EXPECT_GT(ties_broken, 100) << "the problems must be ambiguous for the test to mean anything";
}

/// MRPT 2.5 returned candidate 0 here (the first compatible one): its bound
/// pruned every branch that could only tie with the first maximal hypothesis.
TEST(Jcbb, OneObservationTwoCompatibleLandmarksTakesTheCloser)
{
	AssociationInput in;
	in.observations.resize(1, 2);
	in.observations << 3.77, -0.012;
	in.predictions.resize(2, 2);
	in.predictions << 4.00, -0.30, 3.76, 0.017;
	in.covariance = Eigen::MatrixXd::Zero(4, 4);
	in.covariance.block<2, 2>(0, 0) << 0.0527, 0.0013, 0.0013, 0.1069;
	in.covariance.block<2, 2>(2, 2) << 0.0648, 0, 0, 0.0009;
	const Eigen::MatrixXd d2 = individualDistances2(in);
	ASSERT_LT(d2(0, 0), chi2Quantile(0.99, 2));
	ASSERT_LT(d2(0, 1), d2(0, 0));
	EXPECT_EQ(associate(in, AssociationMethod::Jcbb, 0.99).candidate_of, std::vector<int>{1});
}

}  // namespace
