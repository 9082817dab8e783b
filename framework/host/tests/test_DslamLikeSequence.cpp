// The benchmark's D-SLAM-like sequence: what a step sees and measures, that
// the first sweep maps everything and later sweeps revisit it, and that the
// core recovers it like the dense reference and the other methods.

#include <esif/sparsebench/DslamLikeSequence.h>
#include <esif/sparsebench/DslamSequenceFeeder.h>
#include <esif/sparsebench/SparseBenchmark.h>
#include <esif/core/Errors.h>
#include <esif/sparse/SparseInformationCore.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <set>

namespace
{
using namespace esif;

DslamSequenceOptions smallGrid(int features)
{
	DslamSequenceOptions o;
	o.features = features;
	return o;
}

TEST(DslamLikeSequence, StepsSeeFiveToFifteenFeaturesRelativeToAMappedOne)
{
	DslamLikeSequence seq(smallGrid(300));
	std::set<int> mapped;
	for (int k = 0; k < 2 * seq.mappingSteps(); ++k)
	{
		const DslamStep s = seq.next();
		const std::size_t seen = s.others.size() + 1;
		ASSERT_GE(seen, 5u) << "step " << k;
		ASSERT_LE(seen, 16u) << "step " << k;  // 15 in view, plus a reference from outside if none is mapped
		ASSERT_EQ(s.anchor, k == 0);
		if (!s.anchor)
		{
			ASSERT_TRUE(mapped.count(s.reference)) << "step " << k;
		}
		ASSERT_EQ(s.z.size(), static_cast<Eigen::Index>(2 * s.others.size()));
		for (std::size_t a = 0; a < s.others.size(); ++a)
		{
			const Eigen::Vector2d truth = seq.features()[s.others[a]] - seq.features()[s.reference];
			ASSERT_LT((s.z.segment<2>(2 * a) - truth).norm(), 10 * seq.options().sigma_m);
		}
		for (int f : s.new_features) EXPECT_TRUE(mapped.insert(f).second) << "feature " << f << " mapped twice";
		if (k + 1 == seq.mappingSteps())
		{
			EXPECT_EQ(mapped.size(), 300u) << "the first sweep maps every feature";
		}
	}
}

TEST(DslamLikeSequence, LaterSweepsRevisitOldFeatures)
{
	DslamLikeSequence seq(smallGrid(400));
	std::vector<int> last_seen(400, -1);
	int loops = 0;
	for (int k = 0; k < 2 * seq.mappingSteps(); ++k)
	{
		const DslamStep s = seq.next();
		std::vector<int> seen = s.others;
		seen.push_back(s.reference);
		for (int f : seen)
		{
			// Seen again long after it left the view: a loop closure.
			if (last_seen[f] >= 0 && k - last_seen[f] > 50) ++loops;
			last_seen[f] = k;
		}
	}
	EXPECT_GT(loops, 100);
}

TEST(DslamLikeSequence, CovarianceSharesTheReferenceNoise)
{
	DslamLikeSequence seq(smallGrid(100));
	DslamStep s = seq.next();
	const Eigen::MatrixXd R = seq.covariance(s);
	const double v = seq.options().sigma_m * seq.options().sigma_m;
	ASSERT_EQ(R.rows(), s.z.size());
	EXPECT_DOUBLE_EQ(R(0, 0), 2 * v);
	EXPECT_DOUBLE_EQ(R(0, 2), v);
	EXPECT_DOUBLE_EQ(R(0, 1), 0.0);
}

TEST(DslamLikeSequence, FedToTheCoreEveryMethodRecoversTheDenseEstimate)
{
	DslamLikeSequence seq(smallGrid(150));
	SparseRecoveryParams incremental, pcg, fresh;
	incremental.n0 = pcg.n0 = 40;
	pcg.recovery = RecoveryMethod::Pcg;
	pcg.pcg_relative_tolerance = 1e-15;
	fresh.recovery = RecoveryMethod::FreshCholesky;
	SparseInformationCore a(incremental), b(pcg), c(fresh);
	DslamSequenceFeeder fa, fb, fc;
	for (int k = 0; k < seq.mappingSteps() + 150; ++k)
	{
		const DslamStep s = seq.next();
		fa.apply(s, seq, a);
		fb.apply(s, seq, b);
		fc.apply(s, seq, c);
		a.recoverState();
		b.recoverState();
		c.recoverState();
	}
	EXPECT_EQ(fa.mappedFeatures(), 150);
	const Eigen::MatrixXd I = a.information().matrix().toDense();
	const Eigen::VectorXd x = I.llt().solve(a.information().vector());
	// cond(I) of this grid is about 1e4 (relative links over ~10 hops to the
	// one anchor), so 1e-9 bounds a backward-stable solve with margin.
	EXPECT_LT((a.state() - x).norm() / x.norm(), 1e-9);
	EXPECT_LT((b.state() - x).norm() / x.norm(), 1e-9);
	EXPECT_LT((c.state() - x).norm() / x.norm(), 1e-9);
	// The estimate is the map: features close to the truth (noise 5 cm).
	for (int f = 0; f < 150; ++f)
		EXPECT_LT((a.estimate(fa.variable(f)) - seq.features()[f]).norm(), 0.5) << "feature " << f;
	EXPECT_GT(a.counters().partial_refactorisations, 100u);
	EXPECT_LE(b.counters().pcg_iterations_max, 3u);
}

TEST(SparseBenchmark, RunsEveryMethodAndRejectsUnknownOnes)
{
	for (const auto& method : sparseBenchMethods())
	{
		const SparseBenchResult r = runSparseBenchmark(method, 60, 30, SparseRecoveryParams{});
		EXPECT_EQ(r.method, method);
		EXPECT_EQ(r.features, 60);
		EXPECT_EQ(r.steps, 30);
		EXPECT_GT(r.us_per_step, 0.0);
		EXPECT_GT(r.factor_nnz, 0u);
		if (method == "fresh_cholesky")
		{
			EXPECT_EQ(r.reorders, 30u);
		}
		if (method.rfind("pcg", 0) == 0)
		{
			EXPECT_GE(r.pcg_iterations_max, 1u);
		}
	}
	EXPECT_THROW(runSparseBenchmark("cholesky", 60, 30, SparseRecoveryParams{}), ConfigError);
}

}  // namespace
