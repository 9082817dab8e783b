/// \file test_BoundedAssociation.cpp
/// JCBB's effort bound (SearchBounds): on clustered features the noise
/// cannot separate (pairs 0.2 m apart), JCBB branches on every
/// candidate of every observation; the association measures that ambiguity
/// before searching and falls back to nearest neighbour with the joint
/// compatibility test beyond the bounds. Asserted on the effort counters
/// (JCBB's node count, the hypothesis count), not on time.

#include <esif/association/Chi2.h>
#include <esif/association/DataAssociation.h>
#include <esif/association/PointSetAssociation.h>
#include <esif/ekf/LandmarkEkf.h>

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

namespace
{
using namespace esif;

constexpr double kGate = 0.99;
constexpr double kDeg = M_PI / 180.0;

/// `pairs` clusters of two features 0.2 m apart (across the line of sight),
/// at 2.5-4.5 m and bearings spread over +-75 deg, seen from the origin.
std::vector<Eigen::Vector2d> clusteredFeatures(int pairs)
{
	std::vector<Eigen::Vector2d> out;
	for (int p = 0; p < pairs; ++p)
	{
		const double range = 2.5 + 2.0 * (p % 3) / 2.0, bearing = (-75.0 + 150.0 * p / std::max(1, pairs - 1)) * kDeg;
		const Eigen::Vector2d centre(range * std::cos(bearing), range * std::sin(bearing));
		const Eigen::Vector2d across(-std::sin(bearing), std::cos(bearing));
		out.push_back(centre - 0.1 * across);
		out.push_back(centre + 0.1 * across);
	}
	return out;
}

Eigen::Vector2d rangeBearing(const Eigen::Vector2d& p) { return {p.norm(), std::atan2(p.y(), p.x())}; }

/// Range-bearing association problem: every feature predicted with 0.15 m
/// of (independent) position uncertainty plus the sensor noise (0.1 m, 1
/// deg), and observed once with that noise (fixed seed). A pair 0.2 m apart
/// at 3 m is 0.067 rad, about 1.3 sigma of bearing: both members pass the
/// 99% gate for either observation.
AssociationInput clusteredProblem(int pairs, unsigned seed)
{
	const auto features = clusteredFeatures(pairs);
	const auto n = static_cast<Eigen::Index>(features.size());
	AssociationInput in;
	in.observations.resize(n, 2);
	in.predictions.resize(n, 2);
	in.covariance = Eigen::MatrixXd::Zero(2 * n, 2 * n);
	std::mt19937 rng(seed);
	std::normal_distribution<double> unit;
	for (Eigen::Index j = 0; j < n; ++j)
	{
		const Eigen::Vector2d z = rangeBearing(features[j]);
		in.predictions.row(j) = z.transpose();
		const double sr2 = 0.15 * 0.15 + 0.1 * 0.1, sb2 = std::pow(0.15 / z(0), 2) + std::pow(1 * kDeg, 2);
		in.covariance.block<2, 2>(2 * j, 2 * j) = Eigen::Vector2d(sr2, sb2).asDiagonal();
		in.observations.row(j) << z(0) + std::sqrt(sr2) * unit(rng), z(1) + std::sqrt(sb2) * unit(rng);
	}
	return in;
}

std::size_t pairCount(const std::vector<int>& candidate_of)
{
	return static_cast<std::size_t>(std::count_if(candidate_of.begin(), candidate_of.end(), [](int c) { return c >= 0; }));
}

TEST(BoundedAssociation, ClusteredScanFallsBackWithoutSearching)
{
	// 12 pairs in view: 24 observations with 2 compatible candidates each,
	// 3^24 = 2.8e11 hypotheses for JCBB to branch over.
	const auto in = clusteredProblem(12, 1);
	const auto r = associate(in, AssociationMethod::Jcbb, kGate);
	std::cout << "12 clustered pairs: hypotheses " << r.effort.hypotheses << ", most candidates "
			  << r.effort.max_candidates << ", fell back " << r.fell_back << ", JCBB nodes " << r.jcbb_nodes << ", pairs "
			  << pairCount(r.candidate_of) << " of 24, dropped by the joint test " << r.pairs_dropped << "\n";
	EXPECT_GT(r.effort.hypotheses, SearchBounds{}.max_hypotheses);
	EXPECT_TRUE(r.fell_back);
	EXPECT_EQ(r.jcbb_nodes, 0u);  // the exponential search was never entered
	// The fallback's effort: one joint test per pair at most.
	EXPECT_LE(r.pairs_dropped, 24u);
	// Nearest neighbour stays inside each cluster (the clusters are metres
	// apart): an observation goes to its own feature or to the other one of
	// its pair, never further.
	for (int i = 0; i < 24; ++i)
		if (r.candidate_of[i] >= 0) { EXPECT_EQ(r.candidate_of[i] / 2, i / 2) << i; }
	// The noise that makes the pairs ambiguous is the noise of correct
	// pairs: almost all observations are associated (the joint test may
	// drop a few), none left new.
	EXPECT_GE(pairCount(r.candidate_of), 20u);
}

TEST(BoundedAssociation, WithinTheBoundsJcbbRunsAndItsEffortIsBoundedByTheHypothesisCount)
{
	// Growing clusters below the bound: JCBB runs, and its node count
	// stays within (observations x hypotheses), the justification of
	// measuring the effort by the hypothesis count before the search.
	double previous_nodes = 0;
	for (int pairs = 1; pairs <= 4; ++pairs)
	{
		const auto in = clusteredProblem(pairs, 2);
		const auto r = associate(in, AssociationMethod::Jcbb, kGate);
		const double M = static_cast<double>(in.observations.rows());
		std::cout << pairs << " clustered pairs: hypotheses " << r.effort.hypotheses << ", JCBB nodes " << r.jcbb_nodes
				  << "\n";
		EXPECT_FALSE(r.fell_back) << pairs;
		EXPECT_LE(static_cast<double>(r.jcbb_nodes), M * r.effort.hypotheses) << pairs;
		EXPECT_GT(static_cast<double>(r.jcbb_nodes), previous_nodes) << pairs;  // it does grow with the clusters
		previous_nodes = static_cast<double>(r.jcbb_nodes);
	}
}

TEST(BoundedAssociation, TooManyCandidatesForOneObservationFallsBack)
{
	// Seven features within 0.1 m of one another: one observation has 7
	// compatible candidates, more than jcbb_max_candidates (6).
	AssociationInput in;
	const int n = 7;
	in.predictions.resize(n, 2);
	in.covariance = Eigen::MatrixXd::Zero(2 * n, 2 * n);
	for (int j = 0; j < n; ++j)
	{
		in.predictions.row(j) << 3.0 + 0.01 * j, 0.005 * j;
		in.covariance.block<2, 2>(2 * j, 2 * j) = Eigen::Vector2d(0.04, 0.004).asDiagonal();
	}
	in.observations.resize(1, 2);
	in.observations << 3.03, 0.015;
	const auto r = associate(in, AssociationMethod::Jcbb, kGate);
	EXPECT_EQ(r.effort.max_candidates, 7);
	EXPECT_EQ(r.effort.hypotheses, 8);	// within the hypothesis bound: the candidate bound decides
	EXPECT_TRUE(r.fell_back);
	EXPECT_EQ(r.jcbb_nodes, 0u);
	EXPECT_GE(r.candidate_of[0], 0);
	// Raising the bound lets JCBB run on the same problem.
	SearchBounds wide;
	wide.max_candidates = 7;
	const auto w = associate(in, AssociationMethod::Jcbb, kGate, wide);
	EXPECT_FALSE(w.fell_back);
	EXPECT_GT(w.jcbb_nodes, 0u);
}

TEST(BoundedAssociation, FallbackRepairDropsThePairTheJointTestBlames)
{
	// Six landmarks ahead (bearing 0, 10-60 m) whose predicted bearings share
	// one error (sigma 0.05 rad, the robot's heading) beside their own; six
	// observations 1 sigma of that heading off, and a seventh 0.3 m beside
	// the sixth landmark on the other side: the nearest pair of all on its
	// own, yet against the heading the other five fix. A search bound of one
	// hypothesis forces the fallback; its repair must drop the seventh, not
	// the five (as dropping by individual distance did).
	AssociationInput in;
	const int n = 6;
	in.predictions.resize(n, 2);
	Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * n, 1);
	for (int j = 0; j < n; ++j)
	{
		in.predictions.row(j) << 10.0 * (j + 1), 0;
		J(2 * j + 1, 0) = 1;  // every bearing moves with the heading
	}
	Eigen::MatrixXd own = Eigen::MatrixXd::Zero(2 * n, 2 * n);
	for (int j = 0; j < n; ++j) own.block<2, 2>(2 * j, 2 * j) = Eigen::Vector2d(0.01, std::pow(0.1 / (10.0 * (j + 1)), 2)).asDiagonal();
	in.covariance = 0.05 * 0.05 * J * J.transpose() + own;
	in.observations.resize(n + 1, 2);
	for (int j = 0; j < n; ++j) in.observations.row(j) << 10.0 * (j + 1), 0.05;
	in.observations.row(n) << 60, -0.005;
	SearchBounds none;
	none.max_hypotheses = 1;
	const auto r = associate(in, AssociationMethod::Jcbb, kGate, none);
	ASSERT_TRUE(r.fell_back);
	for (int j = 0; j < 5; ++j) EXPECT_EQ(r.candidate_of[j], j) << "observation " << j;
	EXPECT_NE(r.candidate_of[n], n - 1);
}

TEST(BoundedAssociation, NearestNeighbourIsNeverCountedAsAFallback)
{
	const auto r = associate(clusteredProblem(12, 3), AssociationMethod::NearestNeighbor, kGate);
	EXPECT_FALSE(r.fell_back);
	EXPECT_EQ(r.pairs_dropped, 0u);
}

TEST(BoundedAssociation, ClusteredPointSetsFallBack)
{
	// The same clusters as Cartesian point sets (local map against global
	// map): 0.2 m apart with 0.1 m per side.
	const auto features = clusteredFeatures(12);
	const auto n = static_cast<Eigen::Index>(features.size());
	PointSets s;
	s.candidates.resize(n, 2);
	s.observed.resize(n, 2);
	s.candidates_cov = 0.01 * Eigen::MatrixXd::Identity(2 * n, 2 * n);
	s.observed_cov = 0.01 * Eigen::MatrixXd::Identity(2 * n, 2 * n);
	std::mt19937 rng(4);
	std::normal_distribution<double> noise(0, 0.1);
	for (Eigen::Index j = 0; j < n; ++j)
	{
		s.candidates.row(j) = features[j].transpose();
		s.observed.row(j) << features[j].x() + noise(rng), features[j].y() + noise(rng);
	}
	const auto r = associatePointSets(s, AssociationMethod::Jcbb, kGate, kGate);
	std::cout << "12 clustered point pairs: hypotheses " << r.effort.hypotheses << ", fell back " << r.fell_back
			  << ", JCBB nodes " << r.jcbb_nodes << ", pairs " << pairCount(r.candidate_of) << "\n";
	EXPECT_TRUE(r.fell_back);
	EXPECT_EQ(r.jcbb_nodes, 0u);
	for (int i = 0; i < n; ++i)
		if (r.candidate_of[i] >= 0) { EXPECT_EQ(r.candidate_of[i] / 2, i / 2) << i; }
	EXPECT_GE(pairCount(r.candidate_of), 20u);
}

TEST(BoundedAssociation, LandmarkEkfCountsTheFallback)
{
	// The EKF maps 12 clustered pairs from one scan, then sees them again
	// from the same pose: JCBB would branch over 3^24 hypotheses.
	EkfAssociationParams params;
	params.association = EkfAssociation::Jcbb;
	LandmarkEkf ekf(params);
	const auto features = clusteredFeatures(12);
	std::mt19937 rng(5);
	std::normal_distribution<double> unit;
	auto scan = [&] {
		StepInput step;
		step.scan = Scan{};
		for (const auto& f : features)
		{
			RangeBearing m;
			const Eigen::Vector2d z = rangeBearing(f);
			m.cov = Eigen::Vector2d(0.1 * 0.1, std::pow(2 * kDeg, 2)).asDiagonal();
			m.range_m = z(0) + 0.1 * unit(rng);
			m.bearing_rad = z(1) + 2 * kDeg * unit(rng);
			step.scan->measurements.push_back(m);
		}
		return step;
	};
	ekf.processStep(scan());
	ASSERT_EQ(ekf.core().landmarkCount(), 24u);
	ekf.processStep(scan());
	EXPECT_EQ(ekf.jcbbFallbacks(), 1u);
	EXPECT_EQ(ekf.jcbbNodes(), 0u);
}

}  // namespace
