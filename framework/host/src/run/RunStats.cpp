#include <esif/eval/SuspectResult.h>
#include <esif/run/RunStats.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>
#include <sys/resource.h>

namespace esif
{
void flagSuspectResult(Stats& stats)
{
	if (const auto reason = markSuspect(stats))
		std::cerr << "esif: warning: suspect result: " << *reason
				  << " (stats.json suspect = 1; the outputs are written, look before using them)\n";
}

double nearestRankPercentile(std::vector<double> values, double p)
{
	if (values.empty()) return 0;
	std::sort(values.begin(), values.end());
	const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(values.size())));
	return values[std::min(values.size() - 1, rank == 0 ? 0 : rank - 1)];
}

double peakRssMb()
{
	rusage usage{};
	getrusage(RUSAGE_SELF, &usage);
	return usage.ru_maxrss / 1024.0;  // ru_maxrss is in KiB on Linux
}

void setTimeStats(Stats& s, const std::string& key, const std::vector<double>& us)
{
	s.set(key + "_mean", StatValue(us.empty() ? 0.0 : std::accumulate(us.begin(), us.end(), 0.0) / us.size()));
	s.set(key + "_p50", StatValue(nearestRankPercentile(us, 0.50)));
	s.set(key + "_p99", StatValue(nearestRankPercentile(us, 0.99)));
	s.set(key + "_max", StatValue(us.empty() ? 0.0 : *std::max_element(us.begin(), us.end())));
}

void setCostStats(Stats& s, const CostFigures& cost)
{
	s.set("state_dim", StatValue(static_cast<long long>(cost.state_dim)));
	s.set("poses_in_state", StatValue(static_cast<long long>(cost.poses_in_state)));
	if (cost.info_nnz)
		s.set("info_nnz", StatValue(static_cast<long long>(*cost.info_nnz)));
	else
		s.set("info_nnz", StatValue(nullptr));
}

void setAssociationStats(Stats& s, const AssociationAudit& audit)
{
	s.set("da_new", StatValue(static_cast<long long>(audit.newCount())));
	s.set("da_matched", StatValue(static_cast<long long>(audit.matchedCount())));
	s.set("da_rejected", StatValue(static_cast<long long>(audit.rejectedCount())));
	if (audit.hasTruth())
		s.set("da_wrong", StatValue(static_cast<long long>(audit.wrongCount())));
	else
		s.set("da_wrong", StatValue(nullptr));
	const auto tracked = [&](std::size_t n) {
		return audit.tracksGivenIds() ? StatValue(static_cast<long long>(n)) : StatValue(nullptr);
	};
	s.set("da_id_given", tracked(audit.givenIdCount()));
	s.set("da_id_rejected", tracked(audit.givenIdRejectedCount()));
}

void setAccuracyStats(Stats& s, const std::optional<Accuracy>& accuracy)
{
	const Accuracy acc = accuracy.value_or(Accuracy{});
	s.set("landmark_rmse_m", acc.landmark_rmse_m);
	s.set("ate_rmse_m", acc.ate_rmse_m);
	s.set("landmark_nees_mean", acc.landmark_nees_mean);
	s.set("pose_nees_mean", acc.pose_nees_mean);
	s.set("landmark_consistent_fraction", acc.landmark_consistent_fraction);
	s.set("pose_consistent_fraction", acc.pose_consistent_fraction);
	s.set("landmarks_evaluated", StatValue(static_cast<long long>(acc.landmarks_evaluated)));
}

std::optional<StateNees> finalStateNees(
	const FilterPlugin& plugin, const StateReference& reference,
	const std::optional<std::map<LandmarkId, LandmarkId>>& filter_to_reference, const std::string& what)
{
	const auto state = plugin.stateInformation();
	if (!state) return std::nullopt;
	try
	{
		return stateNees(*state, reference, filter_to_reference, what);
	}
	catch (const NumericalError& e)
	{
		std::cerr << "esif: warning: " << e.what() << "; state_nees left null\n";
		return std::nullopt;
	}
}

void setStateNeesStats(Stats& s, const std::optional<StateNees>& nees, const std::string& reference)
{
	if (!nees)
	{
		for (const char* key : {"state_nees", "state_nees_dof", "state_nees_lower95", "state_nees_upper95",
								"state_nees_consistent", "state_nees_poses", "state_nees_reference"})
			s.set(key, StatValue(nullptr));
		return;
	}
	s.set("state_nees", StatValue(nees->nees));
	s.set("state_nees_dof", StatValue(static_cast<long long>(nees->dof)));
	s.set("state_nees_lower95", StatValue(nees->lower95));
	s.set("state_nees_upper95", StatValue(nees->upper95));
	s.set("state_nees_consistent", StatValue(nees->consistent() ? 1LL : 0LL));
	s.set("state_nees_poses", StatValue(static_cast<long long>(nees->poses_compared)));
	s.set("state_nees_reference", StatValue(reference));
}

void setPluginCounters(Stats& s, const CostFigures& cost)
{
	for (const auto& [name, value] : cost.counters) s.set("plugin_" + name, StatValue(value));
}

void setLocalMapJoinStats(
	Stats& s, std::size_t local_maps, const std::vector<double>& join_us, const std::vector<LocalMapFusionCost>& costs)
{
	s.set("local_maps", StatValue(static_cast<long long>(local_maps)));
	std::vector<double> total_us = join_us, association_us;
	for (const auto& c : costs)
	{
		if (join_us.empty()) total_us.push_back(c.total_s * 1e6);
		association_us.push_back(c.association_s * 1e6);
	}
	setTimeStats(s, "join_us", total_us);
	if (association_us.empty())
		s.set("join_association_us_mean", StatValue(nullptr));
	else
		s.set(
			"join_association_us_mean",
			StatValue(std::accumulate(association_us.begin(), association_us.end(), 0.0) / association_us.size()));
}

}  // namespace esif
