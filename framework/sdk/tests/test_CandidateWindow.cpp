/// \file test_CandidateWindow.cpp
/// The association candidates of a scan (association/CandidateWindow.h): the
/// sensor's range and field of view plus margins, any landmark within the
/// range margin, the window widened on request, and a sensor of unknown
/// range or field of view.

#include <esif/association/CandidateWindow.h>

#include <gtest/gtest.h>

#include <cmath>

namespace
{
using esif::CandidateWindow;
using esif::Scan;

constexpr double kDeg = M_PI / 180.0;

Scan camera()
{
	Scan scan;
	scan.max_range_m = 5;
	scan.fov_rad = 60 * kDeg;
	return scan;
}

TEST(CandidateWindow, AdmitsTheFieldOfViewWidenedByTheMargins)
{
	const CandidateWindow window(camera(), 2.0, 10.0);
	EXPECT_TRUE(window.admits({6.9, 39.9 * kDeg}));
	EXPECT_TRUE(window.admits({6.9, -39.9 * kDeg}));
	EXPECT_FALSE(window.admits({7.1, 0.0}));
	EXPECT_FALSE(window.admits({3.0, 40.1 * kDeg}));
	EXPECT_FALSE(window.admits({3.0, M_PI}));
}

TEST(CandidateWindow, AdmitsEveryBearingWithinTheRangeMargin)
{
	// The robot may drive over a feature: close by, the bearing says little.
	const CandidateWindow window(camera(), 2.0, 10.0);
	EXPECT_TRUE(window.admits({1.9, M_PI}));
	EXPECT_FALSE(window.admits({2.1, M_PI}));
}

TEST(CandidateWindow, WidensByWhatTheCallerGives)
{
	const CandidateWindow window(camera(), 2.0, 10.0);
	EXPECT_FALSE(window.admits({7.5, 45 * kDeg}));
	EXPECT_TRUE(window.admits({7.5, 45 * kDeg}, {0.6, 6 * kDeg}));
	EXPECT_FALSE(window.admits({7.5, 45 * kDeg}, {0.4, 6 * kDeg}));
	EXPECT_FALSE(window.admits({7.5, 45 * kDeg}, {0.6, 4 * kDeg}));
}

TEST(CandidateWindow, AnUnknownRangeOrFieldOfViewLimitsNothing)
{
	const CandidateWindow window(Scan{}, 2.0, 10.0);
	EXPECT_TRUE(window.admits({1e6, M_PI}));

	Scan range_unknown = camera();
	range_unknown.max_range_m = 0;
	const CandidateWindow any_range(range_unknown, 2.0, 10.0);
	EXPECT_TRUE(any_range.admits({1e6, 0.0}));
	EXPECT_FALSE(any_range.admits({1e6, 41 * kDeg}));

	Scan fov_unknown = camera();
	fov_unknown.fov_rad = 0;
	const CandidateWindow any_bearing(fov_unknown, 2.0, 10.0);
	EXPECT_TRUE(any_bearing.admits({3.0, M_PI}));
	EXPECT_FALSE(any_bearing.admits({7.1, 0.0}));
}

}  // namespace
