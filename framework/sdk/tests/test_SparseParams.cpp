// Parameters and counters of the sparse core: INI names, validation
// messages, the (name, value) list for CostFigures.

#include <esif/config/ConfigFile.h>
#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/sparse/SparseCounters.h>
#include <esif/sparse/SparseRecoveryParams.h>

#include <ParamsTestSupport.h>

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace
{
using namespace esif;

SparseRecoveryParams load(const std::string& text) { return test::loadParamsText<SparseRecoveryParams>("dslam", text); }

std::string errorOf(const std::string& text) { return test::paramsErrorOf<SparseRecoveryParams>("dslam", text); }

TEST(SparseRecoveryParams, DefaultsAreValidAndDescribed)
{
	const auto p = load("");
	EXPECT_EQ(p.recovery, RecoveryMethod::IncrementalCholesky);
	EXPECT_EQ(p.reordering, Reordering::Distance);
	const auto infos = describeParams(SparseRecoveryParams{});
	ASSERT_EQ(infos.size(), 10u);
	EXPECT_EQ(infos[0].key, "recovery");
	EXPECT_EQ(infos[0].value, "incremental_cholesky");
	EXPECT_EQ(infos[1].value, "distance");
}

TEST(SparseRecoveryParams, MethodsAreSetByName)
{
	EXPECT_EQ(load("recovery = pcg").recovery, RecoveryMethod::Pcg);
	EXPECT_EQ(load("recovery = fresh_cholesky").recovery, RecoveryMethod::FreshCholesky);
	EXPECT_EQ(load("reordering = camd").reordering, Reordering::Camd);
	EXPECT_EQ(load("reordering = nested_dissection").reordering, Reordering::NestedDissection);
	const auto p = load("n0 = 100\npcg_relative_tolerance = 1e-12\nic_drop_tolerance = 0");
	EXPECT_EQ(p.n0, 100);
	EXPECT_EQ(p.pcg_relative_tolerance, 1e-12);
	EXPECT_EQ(p.ic_drop_tolerance, 0.0);
	EXPECT_STREQ(recoveryMethodName(RecoveryMethod::Pcg), "pcg");
	EXPECT_STREQ(reorderingName(Reordering::Camd), "camd");
	EXPECT_STREQ(reorderingName(Reordering::NestedDissection), "nested_dissection");
	const auto f = load("reorder_trigger = fill_growth\nmax_fill_growth = 0.5");
	EXPECT_EQ(f.reorder_trigger, ReorderTrigger::FillGrowth);
	EXPECT_EQ(f.max_fill_growth, 0.5);
	EXPECT_STREQ(reorderTriggerName(ReorderTrigger::TrailingDimension), "trailing_dimension");
}

TEST(SparseRecoveryParams, EveryReorderingHasItsOwnFigureTitle)
{
	std::set<std::string> titles;
	for (Reordering r : {Reordering::Distance, Reordering::Camd, Reordering::Amd, Reordering::NestedDissection})
	{
		const std::string title = reorderingTitle(r);
		EXPECT_NE(title.find("reordering"), std::string::npos) << title;
		titles.insert(title);
	}
	EXPECT_EQ(titles.size(), 4u);
	EXPECT_STREQ(reorderingTitle(Reordering::NestedDissection), "nested-dissection reordering");
}

TEST(SparseRecoveryParams, InvalidValuesAreNamed)
{
	EXPECT_NE(errorOf("recovery = cholesky").find("recovery"), std::string::npos);
	EXPECT_NE(errorOf("reordering = metis").find("reordering"), std::string::npos);
	EXPECT_NE(errorOf("n0 = 0").find("n0"), std::string::npos);
	EXPECT_NE(errorOf("reorder_trigger = fill").find("reorder_trigger"), std::string::npos);
	EXPECT_NE(errorOf("max_fill_growth = 0").find("max_fill_growth"), std::string::npos);
	EXPECT_NE(errorOf("pcg_relative_tolerance = 1").find("pcg_relative_tolerance"), std::string::npos);
	EXPECT_NE(errorOf("min_pivot_ratio = 0").find("min_pivot_ratio"), std::string::npos);
	EXPECT_NE(errorOf("pcg_max_iterations = abc").find("pcg_max_iterations"), std::string::npos);
	EXPECT_NE(errorOf("no_such_key = 1").find("no_such_key"), std::string::npos);
}

TEST(SparseCounters, ListsEveryCounterByName)
{
	SparseCounters c;
	c.factor_nnz = 42;
	c.pcg_iterations_max = 2;
	c.back_substitution_columns = 7;
	c.recovery_time_s = 0.5;
	const auto list = c.list();
	ASSERT_EQ(list.size(), 15u);
	EXPECT_EQ(list[1].first, "sparse_factor_nnz");
	EXPECT_EQ(list[1].second, 42.0);
	EXPECT_EQ(list[2].first, "sparse_top_separator_scalars");
	EXPECT_EQ(list[7].first, "sparse_pcg_iterations_max");
	EXPECT_EQ(list[7].second, 2.0);
	EXPECT_EQ(list[8].first, "sparse_back_substitution_columns");
	EXPECT_EQ(list[8].second, 7.0);
	EXPECT_EQ(list[10].first, "sparse_updown_flops");
	EXPECT_EQ(list[14].first, "sparse_recovery_time_s");
	EXPECT_EQ(c.list("dslam_")[0].first, "dslam_information_nnz");
}

}  // namespace
