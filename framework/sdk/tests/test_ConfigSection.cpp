#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>

#include <gtest/gtest.h>

namespace
{
using namespace esif;

ConfigSection sectionOf(const std::string& text) { return ConfigFile::fromText("[s]\n" + text, "t.ini").section("s"); }

/// One key `x` holding `value` as it is (no trimming by an INI parser).
ConfigSection keyWithValue(const std::string& value) { return ConfigSection("t.ini", "s", {{"x", value}}); }

TEST(ConfigSection, ParsesNumbersStrictly)
{
	EXPECT_EQ(keyWithValue("1.5e-3").getDouble("x"), 1.5e-3);
	EXPECT_EQ(keyWithValue("1e-310").getDouble("x"), 1e-310);	// subnormal: finite
	// MRPT's atof would read "12abc" as 12 and "abc" as 0; no '+', no hexadecimal.
	for (const char* bad : {"12abc", "abc", "", "nan", "inf", "-inf", "1e999", " 1.5", "1.5 ", "+1.5", "0x1p3"})
		EXPECT_THROW(keyWithValue(bad).getDouble("x"), ConfigError) << "'" << bad << "'";
	EXPECT_EQ(keyWithValue("42").getInt("x", 0), 42);
	for (const char* bad : {"4.2", "", " 42", "42 ", "1e3", "+42", "99999999999999999999"})
		EXPECT_THROW(keyWithValue(bad).getInt("x", 0), ConfigError) << "'" << bad << "'";
	EXPECT_EQ(parseBool("true"), true);
	EXPECT_EQ(parseBool("0"), false);
	EXPECT_FALSE(parseBool("maybe"));
}

TEST(ConfigSection, ErrorsNameFileSectionKeyAndValue)
{
	const auto s = sectionOf("x = 12abc\n");
	try
	{
		s.getDouble("x");
		FAIL() << "expected ConfigError";
	}
	catch (const ConfigError& e)
	{
		EXPECT_EQ(std::string(e.what()), "t.ini: [s] x = 12abc: not a finite number");
	}
}

TEST(ConfigSection, MissingRequiredKeyIsAnError)
{
	const auto s = sectionOf("");
	EXPECT_THROW(s.getDouble("needed"), ConfigError);
	EXPECT_EQ(s.getDouble("optional", 2.5), 2.5);
}

TEST(ConfigSection, UnknownKeysAreRejected)
{
	const auto s = sectionOf("known = 1\ntypo_key = 2\n");
	s.getInt("known", 0);
	try
	{
		s.rejectUnknownKeys();
		FAIL() << "expected ConfigError";
	}
	catch (const ConfigError& e)
	{
		EXPECT_NE(std::string(e.what()).find("typo_key"), std::string::npos);
	}
}

TEST(ConfigSection, TrailingCommentsAreStripped)
{
	const auto s = sectionOf("x = 3.5   // metres\n");
	EXPECT_EQ(s.getDouble("x"), 3.5);
}

TEST(ConfigFile, MissingFileIsAnError)
{
	EXPECT_THROW(ConfigFile::load("/nonexistent/esif.ini"), ConfigError);
}

}  // namespace
