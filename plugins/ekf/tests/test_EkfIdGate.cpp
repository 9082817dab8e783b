// The EKF's outlier gate on landmark IDs (LandmarkEkf, id_gate_chi2_quantile)
// on the committed grid196 log: clean, and with 1% of the measurements given
// a wrong ID (a misread beacon). The corrupted log is made here, in memory,
// from the clean one with a fixed-seed RNG; the IDs stored in the file stay
// the truth the audit and the evaluation score against.

#include <EsifTestSupport.h>
#include <WrongIds.h>

#include <esif/eval/Evaluator.h>
#include <esif/formats/GroundTruth.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

namespace
{
using namespace esif;

const std::string kGrid196 = test::sourcePath("rawlogs/grid196.rawlog");

struct GatedRun
{
	ReplayResult result;
	Accuracy accuracy;
	std::map<std::string, double> counters;
};

/// The EKF with the rawlog's IDs and, as the map-joining configs' local
/// maps, features closer than 0.3 m unused (configs/slsjf.ini says why):
/// without that rule one near-range bearing update can turn the heading, and
/// the clean run's landmark RMSE is 0.10 m instead of 0.034 m, dominated by
/// such events, so a 1.2x comparison would measure which of them a changed
/// measurement set happens to trigger rather than the gate (measured
/// without it: 0.129 m corrupted against 0.101 m clean).
GatedRun runEkf(const Rawlog& log, const std::string& section)
{
	auto ekf = test::makePlugin("EkfSlam", "association = known_ids\nmin_range_m = 0.3\n" + section);
	GatedRun r{replay(*ekf, log, {0, false}), {}, {}};
	r.accuracy = test::scoreAgainstTruth(r.result, groundTruthPrefixFor(kGrid196));
	r.counters = test::countersOf(*ekf);
	return r;
}

using test::corruptIds;
using test::MeasurementAt;

/// The corrupted measurements the gate can catch: those whose wrong ID names
/// a landmark the filter has already confirmed, i.e. whose beacon was seen
/// correctly in at least two earlier scans (initialised at the first, fused
/// at the second). A misread of a beacon not yet mapped can only start a
/// landmark (known IDs cannot tell it from a first sighting); one of a
/// beacon seen once drops it with the misread (LandmarkEkf: neither
/// sighting is more credible); both are rejected.
std::size_t catchable(const std::vector<MeasurementAt>& corrupted, const Rawlog& corrupted_log)
{
	std::map<LandmarkId, std::vector<std::size_t>> steps_of;  // beacon -> steps where truly seen
	for (std::size_t k = 0; k < corrupted_log.true_ids.size(); ++k)
		for (const auto& id : corrupted_log.true_ids[k])
			if (id && (steps_of[*id].empty() || steps_of[*id].back() != k)) steps_of[*id].push_back(k);
	std::size_t n = 0;
	for (const auto& [k, i] : corrupted)
	{
		const auto& seen = steps_of[*corrupted_log.steps[k].scan->measurements[i].id];
		n += std::lower_bound(seen.begin(), seen.end(), k) - seen.begin() >= 2;
	}
	return n;
}

struct CorruptedOutcome
{
	std::size_t rejected = 0;  ///< Rejected
	std::size_t fused = 0;	///< Matched to the landmark of the wrong ID
	std::size_t initialised = 0;  ///< New: a landmark created (or re-created) from it
};

CorruptedOutcome outcomeOf(const std::vector<MeasurementAt>& corrupted, const ReplayResult& r)
{
	CorruptedOutcome o;
	for (const auto& [k, i] : corrupted)
		switch (r.reports[k].associations[i].kind)
		{
			case Association::Kind::Rejected: ++o.rejected; break;
			case Association::Kind::Matched: ++o.fused; break;
			case Association::Kind::New: ++o.initialised; break;
		}
	return o;
}

class EkfIdGate : public ::testing::Test
{
   protected:
	static void SetUpTestSuite()
	{
		clean_log = new Rawlog(readRawlog(kGrid196));
		corrupted_log = new Rawlog(*clean_log);
		corrupted = new std::vector<MeasurementAt>(corruptIds(*corrupted_log, 0.01, 196));
		clean = new GatedRun(runEkf(*clean_log, ""));
	}
	static void TearDownTestSuite()
	{
		delete clean_log, delete corrupted_log, delete corrupted, delete clean;
	}
	static Rawlog* clean_log;
	static Rawlog* corrupted_log;
	static std::vector<MeasurementAt>* corrupted;
	static GatedRun* clean;
};
Rawlog* EkfIdGate::clean_log = nullptr;
Rawlog* EkfIdGate::corrupted_log = nullptr;
std::vector<MeasurementAt>* EkfIdGate::corrupted = nullptr;
GatedRun* EkfIdGate::clean = nullptr;

TEST_F(EkfIdGate, CleanLogRejectsFewMeasurementsAndKeepsTheEstimate)
{
	const auto ungated = runEkf(*clean_log, "id_gate_chi2_quantile = 1\n");
	const double measurements = static_cast<double>(clean_log->measurement_count);
	const double rejected = clean->counters.at("id_gate_rejected");
	std::cout << "clean grid196, gate 0.9999: landmark RMSE " << *clean->accuracy.landmark_rmse_m << " m, ATE "
			  << *clean->accuracy.ate_rmse_m << " m, gate rejections " << rejected << ", unconfirmed landmarks dropped "
			  << clean->counters.at("id_gate_dropped") << " of " << measurements
			  << " measurements; no gate: landmark RMSE " << *ungated.accuracy.landmark_rmse_m << " m, ATE "
			  << *ungated.accuracy.ate_rmse_m << " m\n";
	EXPECT_EQ(ungated.counters.at("id_gate_rejected"), 0);
	EXPECT_EQ(ungated.counters.at("id_gate_dropped"), 0);
	// A consistent filter's innovations fail the 0.9999 gate 1 time in 10^4;
	// the EKF is somewhat over-confident (90% of its landmarks pass the 95%
	// NEES bound, test_EkfGrid196), which makes the tail heavier. 10 times
	// the nominal rate still means the gate removes almost no information.
	EXPECT_LE(rejected + clean->counters.at("id_gate_dropped"), 10 * 1e-4 * measurements);
	// Whatever the gate removed leaves the estimate as it was: within 1 cm
	// of RMSE, a tenth of the sensor's range sigma (0.1 m).
	EXPECT_NEAR(*clean->accuracy.landmark_rmse_m, *ungated.accuracy.landmark_rmse_m, 0.01);
	EXPECT_NEAR(*clean->accuracy.ate_rmse_m, *ungated.accuracy.ate_rmse_m, 0.01);
	EXPECT_EQ(clean->result.audit.wrongCount(), 0u);
}

TEST_F(EkfIdGate, WrongIdsAreRejectedAndTheMapKeepsItsAccuracy)
{
	const auto gated = runEkf(*corrupted_log, "");
	const auto o = outcomeOf(*corrupted, gated.result);
	const std::size_t can_catch = catchable(*corrupted, *corrupted_log);
	std::cout << "grid196 with " << corrupted->size() << " wrong IDs (1%, " << can_catch
			  << " of mapped and confirmed beacons), gate 0.9999: landmark RMSE " << *gated.accuracy.landmark_rmse_m
			  << " m over " << gated.accuracy.landmarks_evaluated << " landmarks (clean "
			  << *clean->accuracy.landmark_rmse_m << " over " << clean->accuracy.landmarks_evaluated << "), ATE "
			  << *gated.accuracy.ate_rmse_m << " m; corrupted measurements rejected " << o.rejected << ", fused "
			  << o.fused << ", initialised " << o.initialised << "; da_rejected " << gated.result.audit.rejectedCount()
			  << ", da_wrong " << gated.result.audit.wrongCount() << ", unconfirmed landmarks dropped "
			  << gated.counters.at("id_gate_dropped") << "\n";
	// A wrong ID names a landmark about 2.9 m (grid spacing 40 m / 14) or
	// more from the measured one, tens of sigmas of a 0.13 m innovation:
	// the gate catches every one whose landmark is mapped and confirmed.
	// The count of those is approximate (a corrupted earlier sighting can
	// leave a beacon unconfirmed one scan longer): 95% of it.
	EXPECT_GE(o.rejected, 0.95 * static_cast<double>(can_catch));
	// Most corrupted measurements are rejected: the misreads of beacons not
	// yet mapped are ~30% here (early in the run few beacons are mapped);
	// they start a landmark in the wrong place, never move the robot, and
	// the next correct sighting drops that landmark (it was never confirmed).
	EXPECT_GE(2 * o.rejected, corrupted->size());
	EXPECT_EQ(o.rejected + o.initialised, corrupted->size());
	// A wrong ID can pass only if its landmark lies within the gate of the
	// measured one: none does on a 2.9 m grid.
	EXPECT_EQ(o.fused, 0u);
	EXPECT_LE(*gated.accuracy.landmark_rmse_m, 1.2 * *clean->accuracy.landmark_rmse_m);
	EXPECT_LE(*gated.accuracy.ate_rmse_m, 1.2 * *clean->accuracy.ate_rmse_m);
}

TEST_F(EkfIdGate, WithoutTheGateWrongIdsRuinTheMap)
{
	// The issue this gate answers: IDs trusted blindly. The corrupted log
	// without the gate fuses every misread of a mapped beacon.
	const auto ungated = runEkf(*corrupted_log, "id_gate_chi2_quantile = 1\n");
	const auto o = outcomeOf(*corrupted, ungated.result);
	std::cout << "grid196 with wrong IDs, no gate: landmark RMSE " << *ungated.accuracy.landmark_rmse_m << " m, ATE "
			  << *ungated.accuracy.ate_rmse_m << " m; corrupted measurements fused " << o.fused << ", da_wrong "
			  << ungated.result.audit.wrongCount() << "\n";
	EXPECT_GT(o.fused, corrupted->size() / 2);
	// Without it the error is many times the clean one (measured 25 m
	// against 0.034 m: fused misreads pull the robot metres off, and later
	// correct sightings cannot pull it back against the corrupted map).
	EXPECT_GT(*ungated.accuracy.landmark_rmse_m, 2 * *clean->accuracy.landmark_rmse_m);
}

}  // namespace
