#pragma once
/// \file AssociationAudit.h
/// Counts a filter's data-association decisions and, when the rawlog carries
/// landmark IDs (shown to the filter or hidden from it), checks them against
/// those IDs.

#include <esif/core/Estimate.h>

#include <map>
#include <optional>
#include <vector>

namespace esif
{
class AssociationAudit
{
   public:
	/// Records one step: the filter's report and the IDs stored in the file.
	void record(const StepReport& report, const std::vector<std::optional<LandmarkId>>& true_ids);

	std::size_t newCount() const { return new_; }
	std::size_t matchedCount() const { return matched_; }
	std::size_t rejectedCount() const { return rejected_; }

	/// Whether any measurement carried a true ID.
	bool hasTruth() const { return !votes_.empty(); }

	/// The true ID each filter landmark stands for: the ID most of the
	/// measurements assigned to it carried.
	std::map<LandmarkId, LandmarkId> filterToTrue() const;

	/// Measurements used (new or matched) whose true ID differs from the one
	/// their filter landmark stands for, plus true landmarks split over
	/// several filter landmarks (each extra filter landmark counts once).
	std::size_t wrongCount() const;

   private:
	std::size_t new_ = 0, matched_ = 0, rejected_ = 0;
	// filter landmark -> (true ID -> measurements)
	std::map<LandmarkId, std::map<LandmarkId, std::size_t>> votes_;
};

}  // namespace esif
