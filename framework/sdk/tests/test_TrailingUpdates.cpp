// The update log of the incremental Cholesky factor (TrailingUpdates.h):
// when it gives up and asks for a fresh factorisation (Case ii of Sec. 3.3).

#include "sparse/TrailingUpdates.h"
#include <esif/sparse/InformationForm.h>

#include <gtest/gtest.h>
#include <numeric>

namespace
{
using namespace esif;

/// Ten 2-D points, factored in natural order (position g = scalar g).
struct TenPoints
{
	InformationForm info;
	std::vector<VarId> points;
	std::vector<int> position;
	TrailingUpdates log;

	TenPoints()
	{
		for (int i = 0; i < 10; ++i) points.push_back(info.addVariable(VarKind::Point2, Eigen::Vector2d::Zero()));
		position.resize(20);
		std::iota(position.begin(), position.end(), 0);
		log.restart(20);
	}

	/// An update of point `p` whose C has `columns` columns.
	UpdateTerm termOn(int p, int columns) const
	{
		return UpdateTerm{{points[static_cast<std::size_t>(p)]}, Eigen::MatrixXd::Ones(2, columns),
						  Eigen::VectorXd::Zero(2)};
	}
};

TEST(TrailingUpdates, GivesUpWhenTheTrailingPartReachesTheLimit)
{
	TenPoints t;
	t.log.record(t.info, t.termOn(9, 2), t.position, 6);  // positions 18-19: 2 scalars from the end
	EXPECT_FALSE(t.log.overflowed());
	EXPECT_EQ(t.log.start(), 18);
	t.log.record(t.info, t.termOn(8, 2), t.position, 6);  // 16-19: 4
	EXPECT_FALSE(t.log.overflowed());
	t.log.record(t.info, t.termOn(7, 2), t.position, 6);  // 14-19: 6, the limit
	EXPECT_TRUE(t.log.overflowed());
	EXPECT_TRUE(t.log.empty());
}

TEST(TrailingUpdates, CountsTheRankAnUpdateCanHaveNotItsColumns)
{
	// C C^T of a point has rank at most 2 whatever C's columns: six updates
	// of 6 columns log rank 12, not above 2 x limit = 12 (counting columns
	// gave up at the third, 18). A seventh passes it.
	TenPoints t;
	for (int k = 0; k < 6; ++k)
	{
		t.log.record(t.info, t.termOn(9, 6), t.position, 6);
		ASSERT_FALSE(t.log.overflowed()) << "update " << k;
	}
	EXPECT_EQ(t.log.terms().size(), 6u);
	t.log.record(t.info, t.termOn(9, 6), t.position, 6);
	EXPECT_TRUE(t.log.overflowed());
}

}  // namespace
