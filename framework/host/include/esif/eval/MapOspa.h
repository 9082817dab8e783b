#pragma once
/// \file MapOspa.h
/// The OSPA figures of a run on a rawlog (LandmarkSetDistance.h): the
/// cut-off c it uses, and its final map against the ground truth.
///
/// c is the largest error a landmark can have and still be re-observed
/// correctly by a filter that knows its pose exactly: a measurement passes
/// the 0.9999 chi-square gate (2 dof) every esif filter uses by default
/// while it is within sqrt(chi2inv(0.9999, 2)) = 4.29 standard deviations
/// along the major axis of its position covariance (the larger of the
/// range sigma and range x bearing sigma). c is that radius for the
/// rawlog's median measurement, so it follows the sensor: 4.29 x 0.1 m for
/// the book's simulated laser (0.1 m, 1 deg, 5 m range: the range sigma
/// is the larger). An estimate
/// farther than c from its true landmark would be re-created rather than
/// updated by a well-localised filter: it counts as much as a missing one.

#include <esif/core/Estimate.h>
#include <esif/core/StepInput.h>
#include <esif/formats/GroundTruth.h>

#include <optional>
#include <set>
#include <vector>

namespace esif
{
/// The OSPA cut-off of a run on `steps` (see the file comment); nullopt
/// when no step holds a measurement.
std::optional<double> ospaCutoff(const std::vector<StepInput>& steps);

/// The same, gathered one step at a time (a replay that does not hold its steps).
class OspaCutoff
{
   public:
	void add(const StepInput& step);
	std::optional<double> value() const;

   private:
	std::vector<double> sigmas_;  // of each measurement's position, largest axis
};

/// OSPA (order kOspaOrder, cut-off `c`) of the final map against the true
/// landmarks it could have found: those of `observed` (the true landmarks
/// of the measurements) the ground truth places, or every landmark of the
/// ground truth when `observed` is empty (no measurement carried its true
/// landmark). `truth` in the initial-pose frame; a landmark of the map that
/// is not finite is paired with nothing.
double truthOspa(const GroundTruth& truth, const Estimate& estimate, const std::set<LandmarkId>& observed, double c);

}  // namespace esif
