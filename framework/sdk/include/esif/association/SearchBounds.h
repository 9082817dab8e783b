#pragma once
/// \file SearchBounds.h
/// How ambiguous a scan (or a map) may be before JCBB's exhaustive search is
/// skipped. MRPT's JCBB (Neira & Tardos 2001) has no effort limit: its bound
/// keeps every branch that could still reach the best number of pairs, so
/// an observation with n individually compatible candidates multiplies the
/// search by up to n + 1 (each candidate, or none). Between features closer
/// than the noise can separate (e.g. pairs 0.2 m apart) that is 3^k nodes
/// for k such observations: minutes inside one step. The ambiguity is
/// measured before the search, from the individual-compatibility matrix:
///   hypotheses = prod over observations with n_i >= 1 of (n_i + 1),
/// the number of ways the observations can be paired or left unpaired.
/// Observations with a single candidate count too: the bound prunes them
/// only while the joint test keeps passing, and where it fails (a local map
/// among clustered features, configs/sim/clusters.ini) JCBB searched 776,000
/// nodes for 46 such observations and 5 ambiguous ones, 0.4 s at every
/// step. Observations with no candidate are never handed to MRPT (see
/// PointSetAssociation.cpp). Beyond either limit the search is not started: the
/// association falls back to MRPT's nearest neighbour verified by the joint
/// compatibility test (pairs dropped, worst first, until it passes), whose
/// cost is polynomial, and the fallback is counted.

#include <esif/config/ParamBinder.h>

#include <cstddef>

namespace esif
{
struct SearchBounds
{
	/// Largest number of individually compatible candidates of one observation.
	int max_candidates = 6;
	/// Largest number of joint hypotheses of the ambiguous observations (see above).
	double max_hypotheses = 20000;

	/// Keys jcbb_max_candidates and jcbb_max_hypotheses, in the caller's section.
	void declare(ParamBinder& b);
};

/// The ambiguity of one association problem, from its individual compatibility.
struct SearchEffort
{
	int max_candidates = 0;	 ///< most compatible candidates of one observation
	double hypotheses = 1;	///< prod over n_i >= 1 of (n_i + 1); may be +inf
	/// Whether JCBB may search exhaustively within `bounds`.
	bool within(const SearchBounds& bounds) const
	{
		return max_candidates <= bounds.max_candidates && hypotheses <= bounds.max_hypotheses;
	}
};

/// Ambiguity of a problem with `compatible_counts[i]` individually
/// compatible candidates for observation i.
template <typename Counts>
SearchEffort searchEffort(const Counts& compatible_counts)
{
	SearchEffort e;
	for (const auto n : compatible_counts)
	{
		const int k = static_cast<int>(n);
		e.max_candidates = k > e.max_candidates ? k : e.max_candidates;
		if (k >= 1) e.hypotheses *= static_cast<double>(k + 1);
	}
	return e;
}

}  // namespace esif
