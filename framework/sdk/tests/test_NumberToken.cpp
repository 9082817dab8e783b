#include <esif/core/NumberToken.h>

#include <gtest/gtest.h>
#include <cmath>
#include <limits>

namespace
{
using namespace esif;

TEST(NumberToken, IntegersAreDecimalDigitsWhole)
{
	EXPECT_EQ(integerToken<long>("42"), 42);
	EXPECT_EQ(integerToken<long>("-7"), -7);
	EXPECT_EQ(integerToken<long>("007"), 7);
	for (const char* bad : {"", "4.2", "7.0", "1e3", "12abc", " 12", "12 ", "+12", "0x10", "-"})
		EXPECT_FALSE(integerToken<long>(bad)) << "'" << bad << "'";
	EXPECT_FALSE(integerToken<int>("99999999999"));  // beyond the type
	EXPECT_FALSE(integerToken<std::size_t>("-1"));
}

TEST(NumberToken, DoublesAreReadWholeWithoutLocale)
{
	for (const NonFinite n : {NonFinite::rejected, NonFinite::accepted})
	{
		EXPECT_EQ(doubleToken("1.5e-3", n), 1.5e-3);
		EXPECT_EQ(doubleToken("-.5", n), -0.5);
		EXPECT_EQ(doubleToken("3.", n), 3.0);
		// Not numbers, as a whole: strtod would read a prefix of most of
		// them, a leading blank, a '+' or hexadecimal.
		for (const char* bad : {"", "12abc", "abc", " 1", "1 ", "1,5", "+1", "0x1p3", "1e", "-", "."})
			EXPECT_FALSE(doubleToken(bad, n)) << "'" << bad << "'";
	}
}

TEST(NumberToken, NonFiniteValuesOnlyWhenAccepted)
{
	for (const char* token : {"nan", "NaN", "-nan", "inf", "-inf", "infinity", "1e999", "-1e400"})
	{
		EXPECT_FALSE(doubleToken(token, NonFinite::rejected)) << token;
		const auto v = doubleToken(token, NonFinite::accepted);
		ASSERT_TRUE(v) << token;
		EXPECT_FALSE(std::isfinite(*v)) << token;
	}
	// Beyond a double's range, the nearest double: an infinity of the sign.
	EXPECT_EQ(doubleToken("-1e400", NonFinite::accepted), -std::numeric_limits<double>::infinity());
	EXPECT_EQ(doubleToken("1000000e303", NonFinite::accepted), std::numeric_limits<double>::infinity());
	EXPECT_EQ(doubleToken("1e99999999999999999999999", NonFinite::accepted), std::numeric_limits<double>::infinity());
}

TEST(NumberToken, TinyValuesReadAsTheNearestDouble)
{
	// Subnormal numbers are finite doubles (a %.17g writer writes them);
	// below the smallest one a number rounds to zero, keeping its sign.
	EXPECT_EQ(doubleToken("1e-310", NonFinite::rejected), 1e-310);
	EXPECT_EQ(doubleToken("4.9406564584124654e-324", NonFinite::rejected), std::numeric_limits<double>::denorm_min());
	const auto zero = doubleToken("-1e-400", NonFinite::rejected);
	ASSERT_TRUE(zero);
	EXPECT_EQ(*zero, 0.0);
	EXPECT_TRUE(std::signbit(*zero));
	EXPECT_EQ(doubleToken("0.0001e-330", NonFinite::rejected), 0.0);
	EXPECT_EQ(doubleToken("1e-99999999999999999999999", NonFinite::rejected), 0.0);
}

}  // namespace
