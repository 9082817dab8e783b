#include <esif/core/Errors.h>
#include <esif/eval/AssociationAudit.h>

#include <algorithm>
#include <string>

namespace esif
{
void AssociationAudit::record(const StepReport& report, const std::vector<std::optional<LandmarkId>>& true_ids)
{
	for (std::size_t i = 0; i < report.associations.size(); ++i)
	{
		const auto& a = report.associations[i];
		const std::optional<LandmarkId> true_id = i < true_ids.size() ? true_ids[i] : std::nullopt;
		if (true_id)
		{
			++with_truth_;
			true_landmarks_.insert(*true_id);
		}
		switch (a.kind)
		{
			case Association::Kind::New: ++new_; break;
			case Association::Kind::Matched: ++matched_; break;
			case Association::Kind::Rejected: ++rejected_; continue;
		}
		++used_[a.id];
		if (true_id) ++votes_[a.id][*true_id];
	}
}

void AssociationAudit::recordGivenIds(const StepReport& report, const StepInput& step)
{
	tracks_given_ = true;
	if (!step.scan) return;
	const auto& measurements = step.scan->measurements;
	for (std::size_t i = 0; i < measurements.size() && i < report.associations.size(); ++i)
		if (measurements[i].id) countGivenId(report.associations[i]);
}

void AssociationAudit::recordGivenIds(const StepReport& report, const std::vector<bool>& given, std::size_t first)
{
	tracks_given_ = true;
	for (std::size_t i = 0; i < report.associations.size() && first + i < given.size(); ++i)
		if (given[first + i]) countGivenId(report.associations[i]);
}

void AssociationAudit::countGivenId(const Association& a)
{
	++given_ids_;
	given_ids_rejected_ += a.kind == Association::Kind::Rejected;
}

std::size_t AssociationAudit::usedOn(LandmarkId id) const
{
	const auto it = used_.find(id);
	return it == used_.end() ? 0 : it->second;
}

std::size_t AssociationAudit::votesFor(LandmarkId id, LandmarkId true_id) const
{
	const auto it = votes_.find(id);
	if (it == votes_.end()) return 0;
	const auto vote = it->second.find(true_id);
	return vote == it->second.end() ? 0 : vote->second;
}

std::map<LandmarkId, LandmarkId> AssociationAudit::filterToTrue() const
{
	std::map<LandmarkId, LandmarkId> out;
	for (const auto& [filter_id, votes] : votes_)
		out[filter_id] = std::max_element(votes.begin(), votes.end(), [](const auto& a, const auto& b) {
							 return a.second < b.second;
						 })->first;
	return out;
}

std::size_t AssociationAudit::wrongCount() const
{
	std::size_t wrong = 0;
	std::map<LandmarkId, std::size_t> filter_landmarks_per_true;
	for (const auto& [filter_id, votes] : votes_)
	{
		std::size_t total = 0, best = 0;
		LandmarkId best_id = 0;
		for (const auto& [true_id, n] : votes)
		{
			total += n;
			if (n > best) best = n, best_id = true_id;
		}
		wrong += total - best;
		++filter_landmarks_per_true[best_id];
	}
	for (const auto& [true_id, n] : filter_landmarks_per_true) wrong += n - 1;
	return wrong;
}

}  // namespace esif
