// Reading trajectory.tum / landmarks.txt back, and one run's difference from
// a reference run, on hand-made files whose differences are known.

#include <EsifTestSupport.h>

#include <esif/core/Errors.h>
#include <esif/compare/ComparisonTable.h>
#include <esif/eval/RunDifference.h>
#include <esif/formats/MapWriter.h>
#include <esif/formats/RunOutputReader.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace
{
using namespace esif;

constexpr double kDeg = M_PI / 180.0;

/// One TUM row of a planar pose (x, y, yaw [deg]) at time t.
std::string tumRow(double t, double x, double y, double yaw_deg)
{
	std::ostringstream s;
	s << std::setprecision(17) << t << " " << x << " " << y << " 0 0 0 " << std::sin(0.5 * yaw_deg * kDeg) << " "
	  << std::cos(0.5 * yaw_deg * kDeg) << "\n";
	return s.str();
}

std::string write(const test::TempDir& dir, const std::string& name, const std::string& text)
{
	const auto path = dir.file(name);
	std::ofstream(path) << text;
	return path;
}

/// `run` as a run solved with the rawlog's IDs: each landmark stands for
/// the true landmark of its own ID.
RunOutputs identifiedByIds(RunOutputs run)
{
	LandmarkIdentities ids{true, {}};
	for (const auto& lm : run.landmarks) ids.landmarks.push_back({lm.id, lm.id, 1, 1});
	run.identities = ids;
	return run;
}

/// The difference of two runs both solved with the rawlog's IDs (no cut-off needed).
RunDifference differenceById(const RunOutputs& run, const RunOutputs& reference)
{
	return runDifference(identifiedByIds(run), identifiedByIds(reference), std::nullopt);
}

/// The InputError message of `f`, or "" when it does not throw one.
template <class F>
std::string inputErrorOf(F f)
{
	try
	{
		f();
	}
	catch (const InputError& e)
	{
		return e.what();
	}
	return "";
}

TEST(RunOutputReader, ReadsWhatTheWritersWrite)
{
	test::TempDir dir;
	std::vector<TrajectoryPoint> traj(3);
	traj[0].time_s = 0.0;
	traj[1].time_s = 0.1;
	traj[1].pose.mean = {1.5, -2.0, 3.0};
	traj[2].time_s = 0.2;
	traj[2].pose.mean = {2.0, -2.5, -3.1};
	writeTrajectoryTum(traj, dir.file("trajectory.tum"));
	Estimate est;
	est.landmarks.resize(2);
	est.landmarks[0].id = 7;
	est.landmarks[0].mean << 1.25, -3.5;
	est.landmarks[0].cov << 0.04, 0.01, 0.01, 0.09;
	est.landmarks[1].id = 3;
	est.landmarks[1].mean << std::nan(""), 0;  // a diverged landmark is written as nan
	writeLandmarksTxt(est, dir.file("landmarks.txt"));

	const RunOutputs back = readRunOutputs(dir.path());
	ASSERT_EQ(back.trajectory.size(), 3u);
	EXPECT_EQ(back.trajectory[1].time_s, 0.1);
	EXPECT_NEAR(back.trajectory[1].pose.x, 1.5, 1e-15);
	EXPECT_NEAR(back.trajectory[1].pose.phi, 3.0, 1e-12);
	EXPECT_NEAR(back.trajectory[2].pose.phi, -3.1, 1e-12);
	ASSERT_EQ(back.landmarks.size(), 2u);
	EXPECT_EQ(back.landmarks[0].id, 7);
	EXPECT_EQ(back.landmarks[0].mean, Eigen::Vector2d(1.25, -3.5));
	EXPECT_EQ(back.landmarks[0].cov(0, 1), 0.01);
	EXPECT_EQ(back.landmarks[0].cov(1, 1), 0.09);
	EXPECT_EQ(back.landmarks[1].id, 3);
	EXPECT_TRUE(std::isnan(back.landmarks[1].mean.x()));
}

/// The same files read as a reference: a diverged landmark, a position out
/// of bounds, an ID MRPT cannot carry or a trajectory of another length are
/// refused at their line instead of being dropped or averaged.
TEST(RunOutputReader, AReferenceIsHeldToTheBounds)
{
	test::TempDir dir;
	const auto write = [&](const std::string& name, const std::string& text) { std::ofstream(dir.file(name)) << text; };
	const auto errorOf = [&](std::optional<std::size_t> steps) {
		try
		{
			readReferenceRun(dir.path(), steps);
		}
		catch (const InputError& e)
		{
			return std::string(e.what());
		}
		return std::string();
	};
	write("trajectory.tum", "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n");
	write("landmarks.txt", "7 1 2 0.1 0 0.1\n");
	EXPECT_EQ(errorOf(2), "");
	EXPECT_EQ(errorOf(3), dir.file("trajectory.tum") + ": 2 rows, the rawlog has 3 steps (a reference run must be of the "
													   "same rawlog, whole)");
	write("landmarks.txt", "7 nan 2 0.1 0 0.1\n");
	EXPECT_EQ(errorOf(2).rfind(dir.file("landmarks.txt") + ":1: position (nan, 2) is not finite or beyond 1e+07 m", 0), 0u)
		<< errorOf(2);
	EXPECT_NO_THROW(readRunOutputs(dir.path())) << "a compared run may hold it";
	write("landmarks.txt", "-7 1 2 0.1 0 0.1\n");
	EXPECT_EQ(errorOf(2), dir.file("landmarks.txt") + ":1: landmark ID -7 is outside 0..2147483647 (MRPT's landmark IDs)");
	write("landmarks.txt", "2147483648 1 2 0.1 0 0.1\n");
	EXPECT_NE(errorOf(2).find(":1: landmark ID 2147483648 is outside"), std::string::npos);
	write("landmarks.txt", "7 1 2 0.1 0 0.1\n");
	write("trajectory.tum", "0 0 0 0 0 0 0 1\n1 1e308 0 0 0 0 0 1\n");
	EXPECT_EQ(errorOf(2).rfind(dir.file("trajectory.tum") + ":2: position (1e+308, 0) is not finite", 0), 0u)
		<< errorOf(2);
	write("trajectory.tum", "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 nan 1\n");
	EXPECT_EQ(errorOf(2), dir.file("trajectory.tum") + ":2: the rotation (qx qy qz qw) is not finite");
}

TEST(RunDifference, LandmarksOfRunsWithTheRawlogsIdsPairedByThemWithKnownRmsAndMax)
{
	RunOutputs ref, run;
	ref.landmarks = {{1, {0, 0}, {}}, {2, {10, 10}, {}}, {3, {5, 5}, {}}};
	// ID 1 off by (3, 4): 5 m; ID 2 off by 1 m; ID 3 missing; ID 9 is not in the reference.
	run.landmarks = {{9, {100, 100}, {}}, {2, {10, 11}, {}}, {1, {3, 4}, {}}};
	const RunDifference d = differenceById(run, ref);
	EXPECT_EQ(d.landmarks_in_reference, 3u);
	EXPECT_EQ(d.landmarks_matched, 2u);
	ASSERT_TRUE(d.landmark_max_m && d.landmark_rms_m);
	EXPECT_DOUBLE_EQ(*d.landmark_max_m, 5.0);
	EXPECT_DOUBLE_EQ(*d.landmark_rms_m, std::sqrt((25.0 + 1.0) / 2.0));
	// No trajectories: nothing to compare.
	EXPECT_EQ(d.steps_compared, 0u);
	EXPECT_FALSE(d.trajectory_rms_m);
	EXPECT_FALSE(d.trajectory_max_m);
	EXPECT_FALSE(d.heading_rms_deg);
}

TEST(RunDifference, NonFiniteAndUnmatchedLandmarksAreNotCounted)
{
	RunOutputs ref, run;
	ref.landmarks = {{1, {0, 0}, {}}, {2, {std::nan(""), 0}, {}}, {3, {1, 1}, {}}};
	run.landmarks = {{1, {0, 2}, {}}, {2, {0, 0}, {}}, {3, {INFINITY, 1}, {}}, {4, {0, 0}, {}}};
	const RunDifference d = differenceById(run, ref);
	EXPECT_EQ(d.landmarks_matched, 1u);
	EXPECT_EQ(d.landmarks_in_reference, 3u);
	EXPECT_DOUBLE_EQ(*d.landmark_rms_m, 2.0);
	EXPECT_DOUBLE_EQ(*d.landmark_max_m, 2.0);

	RunOutputs none;
	none.landmarks = {{5, {0, 0}, {}}};
	const RunDifference e = differenceById(none, ref);
	EXPECT_EQ(e.landmarks_matched, 0u);
	EXPECT_FALSE(e.landmark_rms_m);
	EXPECT_FALSE(e.landmark_max_m);
}

TEST(RunDifference, TrajectoryByStepWithHeadingWrappedAt180)
{
	test::TempDir dir;
	const auto ref_path = write(
		dir, "ref.tum",
		"# esif trajectory (TUM): timestamp x y z qx qy qz qw\n" + tumRow(0, 0, 0, 0) + tumRow(1, 1, 0, 179) +
			tumRow(2, 2, 0, 90));
	// Step 0: same pose. Step 1: (3, 4) off, heading -179 vs 179 = 2 deg across
	// the wrap. Step 2: 1 m off, heading 100 vs 90 deg. Step 3: not in the reference.
	const auto run_path = write(
		dir, "run.tum",
		tumRow(0, 0, 0, 0) + "\n" + tumRow(1, 4, 4, -179) + tumRow(2, 2, 1, 100) + tumRow(3, 50, 50, 0));
	RunOutputs ref, run;
	ref.trajectory = readTrajectoryTum(ref_path);
	run.trajectory = readTrajectoryTum(run_path);
	ASSERT_EQ(run.trajectory.size(), 4u);
	EXPECT_NEAR(run.trajectory[1].pose.phi, -179 * kDeg, 1e-12);

	const RunDifference d = differenceById(run, ref);
	EXPECT_EQ(d.steps_compared, 3u);
	EXPECT_NEAR(*d.trajectory_max_m, 5.0, 1e-12);
	EXPECT_NEAR(*d.trajectory_rms_m, std::sqrt((0.0 + 25.0 + 1.0) / 3.0), 1e-12);
	EXPECT_NEAR(*d.heading_rms_deg, std::sqrt((0.0 + 4.0 + 100.0) / 3.0), 1e-9);
	// Symmetric in the two runs.
	const RunDifference r = differenceById(ref, run);
	EXPECT_NEAR(*r.heading_rms_deg, *d.heading_rms_deg, 1e-12);
	EXPECT_NEAR(*r.trajectory_rms_m, *d.trajectory_rms_m, 1e-12);
}

TEST(RunDifference, StepsArePairedByTimeNotLine)
{
	RunOutputs ref, run;
	ref.trajectory = {{0.0, {0, 0, 0}}, {0.5, {1, 0, 0}}, {1.0, {2, 0, 0}}};
	run.trajectory = {{0.5, {1, 2, 0}}, {1.0, {2, 0, 0}}};
	const RunDifference d = differenceById(run, ref);
	EXPECT_EQ(d.steps_compared, 2u);
	EXPECT_DOUBLE_EQ(*d.trajectory_max_m, 2.0);
	EXPECT_DOUBLE_EQ(*d.trajectory_rms_m, std::sqrt(2.0));
	EXPECT_DOUBLE_EQ(*d.heading_rms_deg, 0.0);
}

TEST(RunDifference, ReferenceItselfIsZeroWithItsOwnCount)
{
	RunOutputs ref;
	ref.trajectory = {{0.0, {0, 0, 0}}, {1.0, {1, 2, 3}}};
	ref.landmarks = {{1, {1, 1}, {}}, {2, {std::nan(""), 0}, {}}};
	const RunDifference d = referenceItself(ref);
	EXPECT_EQ(*d.trajectory_rms_m, 0.0);
	EXPECT_EQ(*d.trajectory_max_m, 0.0);
	EXPECT_EQ(*d.heading_rms_deg, 0.0);
	EXPECT_EQ(*d.landmark_rms_m, 0.0);
	EXPECT_EQ(*d.landmark_max_m, 0.0);
	EXPECT_EQ(d.landmarks_matched, 2u);
	EXPECT_EQ(d.landmarks_in_reference, 2u);
}

TEST(RunDifference, ColumnsAppearInTablesOnlyWhenSet)
{
	Stats a, b;
	a.set("label", StatValue(std::string("ekf")));
	b.set("label", StatValue(std::string("other")));
	for (const auto& k : runDifferenceKeys())
	{
		EXPECT_EQ(comparisonText({a, b}).find(k), std::string::npos) << k;
		EXPECT_EQ(comparisonMarkdown({a, b}).find(k), std::string::npos) << k;
		EXPECT_EQ(comparisonCsv({a, b}).find(k), std::string::npos) << k;
	}
	RunOutputs ref, run;
	const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
	ref.landmarks = {{1, {0, 0}, I}, {2, {1, 1}, I}};
	run.landmarks = {{1, {3, 4}, I}};
	setDifferenceStats(a, referenceItself(ref));
	setDifferenceStats(b, differenceById(run, ref));
	const auto csv = comparisonCsv({a, b});
	// One matched landmark fits no rotation; with unit covariances the
	// reference's own landmarks are inside their ellipse and
	// the run's, 5 m off, is not.
	EXPECT_NE(csv.find("label,ref_traj_rms_m,ref_traj_max_m,ref_heading_rms_deg,ref_landmark_rms_m,"
					   "ref_landmark_max_m,ref_landmarks_matched,ref_landmarks_paired_by,ref_ospa_m,ref_rotation_deg,"
					   "ref_landmark_rms_aligned_m,ref_landmarks_in_own95\n"),
			  std::string::npos)
		<< csv;
	EXPECT_NE(csv.find("ekf,,,,0,0,2,itself,0,0,0,1\n"), std::string::npos) << csv;
	EXPECT_NE(csv.find("other,,,,5,5,1,true landmark,,,,0\n"), std::string::npos) << csv;
	const auto text = comparisonText({a, b});
	for (const auto& k : runDifferenceKeys()) EXPECT_NE(text.find(k), std::string::npos) << k;
	EXPECT_NE(comparisonMarkdown({a, b}).find("| ref_landmarks_matched | 2 | 1 |"), std::string::npos);
}

/// A reference solved with the IDs (its landmarks numbered by their true
/// landmarks) and a run that associated on its own (numbered 0, 1, 2, ...
/// in the order it created them): paired through what each landmark stands
/// for, never by number.
TEST(RunDifference, PairsThroughTrueLandmarksWhateverTheNumbers)
{
	RunOutputs ref, run;
	ref.landmarks = {{1, {0, 0}, {}}, {2, {10, 0}, {}}, {3, {20, 0}, {}}};
	ref.identities = LandmarkIdentities{true, {{1, 1, 9, 9}, {2, 2, 9, 9}, {3, 3, 9, 9}}};
	// Its landmark 0 is true 3 (0.3 m off), 1 is true 1 (0.4 m off), 2 is true
	// 2 (1 m off); 3 is a duplicate of true 1 with fewer measurements (far
	// off, left out); 4 is clutter. By number, 1-1, 2-2 and 3-3 would pair
	// landmarks 10 m and more apart.
	run.landmarks = {{0, {20, 0.3}, {}}, {1, {0.4, 0}, {}}, {2, {10, 1}, {}}, {3, {5, 5}, {}}, {4, {-9, -9}, {}}};
	run.identities =
		LandmarkIdentities{true, {{0, 3, 5, 5}, {1, 1, 6, 7}, {2, 2, 4, 4}, {3, 1, 2, 2}, {4, std::nullopt, 0, 3}}};
	const RunDifference d = runDifference(run, ref, 2.0);
	EXPECT_EQ(d.pairing, LandmarkPairing::TrueLandmark);
	EXPECT_EQ(d.landmarks_matched, 3u);
	EXPECT_NEAR(*d.landmark_rms_m, std::sqrt((0.09 + 0.16 + 1.0) / 3.0), 1e-12);
	EXPECT_NEAR(*d.landmark_max_m, 1.0, 1e-12);
	// OSPA over all five against three: three pairs below c = 2, two extra at c.
	EXPECT_NEAR(*d.ospa_m, std::sqrt((0.09 + 0.16 + 1.0 + 4.0 + 4.0) / 5.0), 1e-12);
	EXPECT_EQ(landmarkPairingText(d.pairing, d.cutoff_m), "true landmark");
}

/// Where a run has no identities (no measurement carried its true landmark,
/// or a folder without landmark_identities.txt), the optimal assignment
/// within c pairs the maps, and the row says so.
TEST(RunDifference, WithoutIdentitiesPairsByAssignmentWithinTheCutoff)
{
	RunOutputs ref, run;
	ref.landmarks = {{1, {0, 0}, {}}, {2, {10, 0}, {}}, {3, {20, 0}, {}}};
	ref.identities = LandmarkIdentities{true, {{1, 1, 9, 9}, {2, 2, 9, 9}, {3, 3, 9, 9}}};
	run.landmarks = {{3, {0.5, 0}, {}}, {1, {10, 0.2}, {}}, {2, {35, 0}, {}}};
	run.identities = LandmarkIdentities{false, {{3, std::nullopt, 0, 4}, {1, std::nullopt, 0, 4}, {2, std::nullopt, 0, 4}}};
	const RunDifference d = runDifference(run, ref, 1.0);
	EXPECT_EQ(d.pairing, LandmarkPairing::Assignment);
	EXPECT_EQ(d.landmarks_matched, 2u);	 // 15 m is beyond c
	EXPECT_NEAR(*d.landmark_rms_m, std::sqrt((0.25 + 0.04) / 2.0), 1e-12);
	EXPECT_NEAR(*d.ospa_m, std::sqrt((0.25 + 0.04 + 1.0) / 3.0), 1e-12);
	EXPECT_EQ(landmarkPairingText(d.pairing, d.cutoff_m), "assignment within c = 1 m");
	// A reference folder without identities (another solver's): the same.
	run.identities = identifiedByIds(run).identities;
	ref.identities.reset();
	EXPECT_EQ(runDifference(run, ref, 1.0).landmarks_matched, 2u);
	// No cut-off (runs on local maps): nothing is paired.
	const RunDifference none = runDifference(run, ref, std::nullopt);
	EXPECT_EQ(none.pairing, LandmarkPairing::None);
	EXPECT_EQ(none.landmarks_matched, 0u);
	EXPECT_FALSE(none.ospa_m);
}

TEST(RunDifference, BestFitRotationTellsARotatedMapFromADistortedOne)
{
	// The run's map is the reference turned by 4.3 deg about (10, -5) (the
	// EKF's Victoria Park error is almost all such a rotation): every
	// difference is large, the best-fit rotation is exactly -4.3 deg (it
	// turns the run back) and nothing is left after it.
	RunOutputs ref, run;
	const double a = 4.3 * kDeg;
	const Eigen::Vector2d centre(10, -5);
	const Eigen::Matrix2d R = Eigen::Rotation2Dd(a).toRotationMatrix();
	for (int i = 0; i < 20; ++i)
	{
		const Eigen::Vector2d p(3.0 * i - 20.0, 40.0 * std::sin(0.7 * i));
		ref.landmarks.push_back({i, p, Eigen::Matrix2d::Identity()});
		run.landmarks.push_back({i, centre + R * (p - centre), Eigen::Matrix2d::Identity()});
	}
	const RunDifference d = differenceById(run, ref);
	// MRPT's se2_l2 sums in single precision (SSE): 1e-6 deg and 1e-6 m
	// seen at these 40 m coordinates; 1e-5 leaves a margin.
	EXPECT_GT(*d.landmark_rms_m, 1.0);
	EXPECT_NEAR(*d.best_fit_rotation_deg, -4.3, 1e-5);
	EXPECT_NEAR(*d.landmark_rms_aligned_m, 0.0, 1e-5);
}

TEST(RunDifference, CountsReferencePositionsInsideTheRunsOwn95Ellipse)
{
	// A thin ellipse along x (sigma 1 m by 0.1 m): 2 m along x is inside
	// (d^T P^-1 d = 4 <= 5.991), 0.3 m along y is outside (9), 0.2 m along y
	// inside (4), and a landmark without a positive-definite covariance is
	// not counted at all.
	const Eigen::Matrix2d P = Eigen::Vector2d(1.0, 0.01).asDiagonal();
	RunOutputs ref, run;
	ref.landmarks = {{1, {2, 0}, {}}, {2, {0, 0.3}, {}}, {3, {0, 0.2}, {}}, {4, {5, 5}, {}}};
	run.landmarks = {{1, {0, 0}, P}, {2, {0, 0}, P}, {3, {0, 0}, P}, {4, {0, 0}, Eigen::Matrix2d::Zero()}};
	const RunDifference d = differenceById(run, ref);
	EXPECT_EQ(d.landmarks_matched, 4u);
	EXPECT_EQ(d.landmarks_with_covariance, 3u);
	EXPECT_NEAR(*d.landmarks_inside_own95_fraction, 2.0 / 3.0, 1e-12);
}

TEST(RunOutputReader, MalformedLinesNameFileAndLine)
{
	test::TempDir dir;
	const std::string ok = tumRow(0, 0, 0, 0);
	struct Case
	{
		std::string text, expected;
	};
	for (const Case& c : std::vector<Case>{
			 {"# header\n" + ok + "0.1 1 2 0 0 0 zero 1\n", "t.tum:3: 'zero' is not a number"},
			 {ok + "0.1 1 2 0 0 0 1\n", "t.tum:2: expected 8 numbers 'timestamp x y z qx qy qz qw', found 7"},
			 {ok + "0.1 1 2 0 0 0 0.5 1 7\n", "t.tum:2: expected 8 numbers"},
			 {ok + ok, "t.tum:2: timestamp 0 is not after the previous one (0)"},
			 {"nan 0 0 0 0 0 0 1\n", "t.tum:1: timestamp nan is not finite"},
			 {"0 0 0 0 0 0 0 0\n", "t.tum:1: quaternion"},
			 {ok + "1 2 3 0 0 0 0 1x\n", "t.tum:2: '1x' is not a number"},
		 })
	{
		const auto path = write(dir, "t.tum", c.text);
		const auto msg = inputErrorOf([&] { readTrajectoryTum(path); });
		EXPECT_NE(msg.find(c.expected), std::string::npos) << "expected '" << c.expected << "' in '" << msg << "'";
		EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
		EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
	}
	for (const Case& c : std::vector<Case>{
			 {"# id x y cxx cxy cyy\n1 0 0 0 0 0\n1 2 3 0 0 0\n",
			  "l.txt:3: duplicate landmark ID 1 (first on line 2)"},
			 {"1 0 0 0 0\n", "l.txt:1: expected 'id x y cxx cxy cyy' (an integer ID and 5 numbers), found 5 values"},
			 {"\n1.5 0 0 0 0 0\n", "l.txt:2: landmark ID '1.5' is not an integer"},
			 {"1 0 y 0 0 0\n", "l.txt:1: 'y' is not a number"},
		 })
	{
		const auto path = write(dir, "l.txt", c.text);
		const auto msg = inputErrorOf([&] { readLandmarksTxt(path); });
		EXPECT_NE(msg.find(c.expected), std::string::npos) << "expected '" << c.expected << "' in '" << msg << "'";
		EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
	}
}

TEST(RunOutputReader, MissingFilesAreNamed)
{
	test::TempDir dir;
	EXPECT_EQ(inputErrorOf([&] { readTrajectoryTum(dir.file("none.tum")); }),
			  dir.file("none.tum") + ": trajectory not found");
	EXPECT_EQ(inputErrorOf([&] { readLandmarksTxt(dir.path()); }), dir.path() + ": landmark map is a folder, not a file");
	write(dir, "trajectory.tum", tumRow(0, 0, 0, 0));
	EXPECT_EQ(inputErrorOf([&] { readRunOutputs(dir.path()); }), dir.file("landmarks.txt") + ": landmark map not found");
}

TEST(RunOutputReader, EmptyFilesHoldNothing)
{
	test::TempDir dir;
	EXPECT_TRUE(readTrajectoryTum(write(dir, "t.tum", "# only a header\n")).empty());
	EXPECT_TRUE(readLandmarksTxt(write(dir, "l.txt", "")).empty());
}

}  // namespace
