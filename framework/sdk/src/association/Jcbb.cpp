/// \file Jcbb.cpp
/// Joint Compatibility Branch and Bound; see Jcbb.h.

#include "Jcbb.h"

#include <esif/association/Chi2.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <limits>

namespace esif::jcbb
{
JointInnovation jointInnovation(const Eigen::MatrixXd& z, const Eigen::MatrixXd& y, const Eigen::MatrixXd& S,
								const std::vector<int>& candidate_of, const Eigen::MatrixXd* Sz)
{
	JointInnovation out;
	auto& cand = out.candidates;
	for (std::size_t i = 0; i < candidate_of.size(); ++i)
		if (candidate_of[i] >= 0) out.observations.push_back(static_cast<Eigen::Index>(i)), cand.push_back(candidate_of[i]);
	const auto k = static_cast<Eigen::Index>(cand.size());
	out.nu.resize(2 * k);
	out.S.resize(2 * k, 2 * k);
	for (Eigen::Index a = 0; a < k; ++a)
	{
		out.nu.segment<2>(2 * a) = (z.row(out.observations[a]) - y.row(cand[a])).transpose();
		for (Eigen::Index b = 0; b < k; ++b)
		{
			out.S.block<2, 2>(2 * a, 2 * b) = S.block<2, 2>(2 * cand[a], 2 * cand[b]);
			if (Sz) out.S.block<2, 2>(2 * a, 2 * b) += Sz->block<2, 2>(2 * out.observations[a], 2 * out.observations[b]);
		}
	}
	return out;
}

double jointDistance2(const Eigen::MatrixXd& z, const Eigen::MatrixXd& y, const Eigen::MatrixXd& S,
					  const std::vector<int>& candidate_of, const Eigen::MatrixXd* Sz)
{
	const JointInnovation j = jointInnovation(z, y, S, candidate_of, Sz);
	if (j.observations.empty()) return 0;
	const Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (j.S + j.S.transpose()));
	if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
	return j.nu.dot(llt.solve(j.nu));
}

JointVerdict jointVerdict(const Eigen::VectorXd& nu, const Eigen::MatrixXd& S, double bound)
{
	JointVerdict v;
	if (nu.size() == 0) return v;
	const Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (S + S.transpose()));
	if (llt.info() != Eigen::Success)
	{
		v.distance2 = std::numeric_limits<double>::infinity();
		v.passes = false;
		return v;
	}
	const Eigen::VectorXd x = llt.solve(nu);
	v.distance2 = nu.dot(x);
	v.passes = v.distance2 <= bound;
	if (v.passes) return v;
	const Eigen::MatrixXd S_inv = llt.solve(Eigen::MatrixXd::Identity(S.rows(), S.cols()));
	double largest_share = -1;
	for (Eigen::Index a = 0; a < nu.size() / 2; ++a)
	{
		const Eigen::Vector2d xa = x.segment<2>(2 * a);
		const double share = xa.dot(S_inv.block<2, 2>(2 * a, 2 * a).ldlt().solve(xa));
		if (share > largest_share) largest_share = share, v.blamed = a;
	}
	return v;
}

namespace
{
class Search
{
   public:
	explicit Search(const Problem& p) : p_(p), current_(p.z.rows(), -1), used_(p.y.rows(), false)
	{
		const double gate = chi2Quantile(p.quantile, 2);
		const auto M = p.z.rows();
		compatible_.resize(M);
		for (Eigen::Index i = 0; i < M; ++i)
		{
			for (Eigen::Index j = 0; j < p.y.rows(); ++j)
				if (p.d2(i, j) <= gate) compatible_[i].push_back(static_cast<int>(j));
			// Closest first: the first maximal hypothesis found is a good bound.
			std::sort(compatible_[i].begin(), compatible_[i].end(),
					  [&](int a, int b) { return p.d2(i, a) < p.d2(i, b); });
		}
		// later_[i]: observations after i with a compatible candidate, what
		// the pairs can still grow by past i.
		later_.assign(M, 0);
		for (Eigen::Index i = M - 2; i >= 0; --i) later_[i] = later_[i + 1] + (compatible_[i + 1].empty() ? 0 : 1);
		best_.candidate_of.assign(M, -1);
	}

	Hypothesis run()
	{
		branch(0, 0);
		best_.nodes = nodes_;
		return best_;
	}

   private:
	void branch(Eigen::Index i, int pairs)
	{
		if (i == static_cast<Eigen::Index>(current_.size()))
		{
			record(pairs);
			return;
		}
		const int after = later_[i];
		// Pair observation i: ties with the best count are explored too, for the closer one.
		if (pairs + 1 + after >= best_pairs_)
			for (const int c : compatible_[i])
			{
				if (used_[c]) continue;
				current_[i] = c;
				++nodes_;
				if (jointDistance2(p_.z, p_.y, p_.S, current_, p_.Sz) <= chi2Quantile(p_.quantile, 2 * (pairs + 1)))
				{
					used_[c] = true;
					branch(i + 1, pairs + 1);
					used_[c] = false;
				}
				current_[i] = -1;
			}
		// Leave it unpaired.
		if (pairs + after >= best_pairs_)
		{
			++nodes_;
			branch(i + 1, pairs);
		}
	}

	void record(int pairs)
	{
		if (pairs == 0 || pairs < best_pairs_) return;
		const double d2 = jointDistance2(p_.z, p_.y, p_.S, current_, p_.Sz);
		if (pairs > best_pairs_ || d2 < best_d2_)
		{
			best_pairs_ = pairs;
			best_d2_ = d2;
			best_.candidate_of = current_;
		}
	}

	const Problem& p_;
	std::vector<std::vector<int>> compatible_;
	std::vector<int> later_;
	std::vector<int> current_;
	std::vector<bool> used_;
	Hypothesis best_;
	int best_pairs_ = 0;
	double best_d2_ = std::numeric_limits<double>::infinity();
	std::size_t nodes_ = 0;
};
}  // namespace

Hypothesis search(const Problem& problem) { return Search(problem).run(); }

}  // namespace esif::jcbb
