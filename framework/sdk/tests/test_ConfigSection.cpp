#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>

#include <gtest/gtest.h>

namespace
{
using namespace esif;

ConfigSection sectionOf(const std::string& text) { return ConfigFile::fromText("[s]\n" + text, "t.ini").section("s"); }

TEST(ConfigSection, ParsesNumbersStrictly)
{
	EXPECT_EQ(parseDouble("1.5e-3"), 1.5e-3);
	EXPECT_FALSE(parseDouble("12abc"));	 // MRPT's atof would give 12
	EXPECT_FALSE(parseDouble("abc"));  // ... and 0 here
	EXPECT_FALSE(parseDouble(""));
	EXPECT_FALSE(parseDouble("nan"));
	EXPECT_FALSE(parseDouble("inf"));
	EXPECT_EQ(parseInt("42"), 42);
	EXPECT_FALSE(parseInt("4.2"));
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
