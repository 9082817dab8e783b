#include <esif/config/ConfigFile.h>
#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>

#include <ParamsTestSupport.h>

#include <gtest/gtest.h>

namespace
{
using namespace esif;

enum class Mode
{
	Fast,
	Exact
};

struct ExampleParams
{
	double sigma_m = 0.1;
	int iterations = 3;
	bool verbose = false;
	Mode mode = Mode::Exact;

	void declare(ParamBinder& b)
	{
		b.real("sigma_m", sigma_m, "noise [m]", Bounds::positive());
		b.integer("iterations", iterations, "iterations", Bounds::closed(1, 10));
		b.flag("verbose", verbose, "print more");
		b.enumeration<Mode>("mode", mode, {{"fast", Mode::Fast}, {"exact", Mode::Exact}}, "mode");
	}
};

ExampleParams load(const std::string& text) { return test::loadParamsText<ExampleParams>("ex", text); }

std::string errorOf(const std::string& text) { return test::paramsErrorOf<ExampleParams>("ex", text); }

TEST(ParamBinder, DefaultsAreValidAndDescribed)
{
	const auto p = load("");
	EXPECT_EQ(p.sigma_m, 0.1);
	const auto infos = describeParams(ExampleParams{});
	ASSERT_EQ(infos.size(), 4u);
	EXPECT_EQ(infos[0].key, "sigma_m");
	EXPECT_EQ(infos[0].value, "0.1");
	EXPECT_EQ(infos[3].value, "exact");
}

TEST(ParamBinder, LoadsValues)
{
	const auto p = load("sigma_m = 0.5\niterations = 7\nverbose = true\nmode = fast\n");
	EXPECT_EQ(p.sigma_m, 0.5);
	EXPECT_EQ(p.iterations, 7);
	EXPECT_TRUE(p.verbose);
	EXPECT_EQ(p.mode, Mode::Fast);
}

TEST(ParamBinder, OutOfRangeValuesNameKeyValueAndRule)
{
	EXPECT_EQ(errorOf("sigma_m = -1\n"), "ex.ini: [ex] sigma_m = -1: must be > 0");
	EXPECT_EQ(errorOf("iterations = 11\n"), "ex.ini: [ex] iterations = 11: must be in [1, 10]");
	EXPECT_EQ(errorOf("mode = quick\n"), "ex.ini: [ex] mode = quick: must be one of fast|exact");
	EXPECT_NE(errorOf("verbose = perhaps\n").find("not a boolean"), std::string::npos);
}

}  // namespace
