#pragma once
/// \file AssociationAudit.h
/// Counts a filter's data-association decisions and, when the rawlog carries
/// landmark IDs (shown to the filter or hidden from it), checks them against
/// those IDs.

#include <esif/core/Estimate.h>

#include <map>
#include <optional>
#include <set>
#include <vector>

namespace esif
{
class AssociationAudit
{
   public:
	/// Records one step: the filter's report and the IDs stored in the file.
	void record(const StepReport& report, const std::vector<std::optional<LandmarkId>>& true_ids);

	/// Records which measurements of `step` the filter was given a landmark
	/// ID for (the rawlog's shown, or another run's associations) and which
	/// of those it rejected anyway.
	void recordGivenIds(const StepReport& report, const StepInput& step);
	/// The same with `given[first + i]` telling whether measurement i of the
	/// step had an ID (a replay's record of the steps it no longer holds).
	void recordGivenIds(const StepReport& report, const std::vector<bool>& given, std::size_t first);

	/// Whether recordGivenIds was called (rawlog runs); measurements given an
	/// ID, and those of them rejected.
	bool tracksGivenIds() const { return tracks_given_; }
	std::size_t givenIdCount() const { return given_ids_; }
	std::size_t givenIdRejectedCount() const { return given_ids_rejected_; }

	std::size_t newCount() const { return new_; }
	std::size_t matchedCount() const { return matched_; }
	std::size_t rejectedCount() const { return rejected_; }

	/// Whether any measurement carried a true ID (used or rejected).
	bool hasTruth() const { return with_truth_ > 0; }

	/// Measurements that carried a true ID, used or rejected.
	std::size_t measurementsWithTruth() const { return with_truth_; }

	/// The distinct true IDs the measurements carried, used or rejected.
	const std::set<LandmarkId>& trueLandmarks() const { return true_landmarks_; }

	/// Measurements used on filter landmark `id` (new or matched), with or without a true ID.
	std::size_t usedOn(LandmarkId id) const;

	/// Of those, the ones whose true ID was `true_id`.
	std::size_t votesFor(LandmarkId id, LandmarkId true_id) const;

	/// The true ID each filter landmark stands for: the ID most of the
	/// measurements assigned to it carried.
	std::map<LandmarkId, LandmarkId> filterToTrue() const;

	/// Measurements used (new or matched) whose true ID differs from the one
	/// their filter landmark stands for, plus true landmarks split over
	/// several filter landmarks (each extra filter landmark counts once).
	std::size_t wrongCount() const;

   private:
	void countGivenId(const Association& a);

	std::size_t new_ = 0, matched_ = 0, rejected_ = 0, with_truth_ = 0;
	bool tracks_given_ = false;
	std::size_t given_ids_ = 0, given_ids_rejected_ = 0;
	// filter landmark -> (true ID -> measurements)
	std::map<LandmarkId, std::map<LandmarkId, std::size_t>> votes_;
	// filter landmark -> measurements used on it
	std::map<LandmarkId, std::size_t> used_;
	std::set<LandmarkId> true_landmarks_;
};

}  // namespace esif
