/// \file test_ConfigFile.cpp
/// The INI faults MRPT's parser passes over silently (it merges repeated
/// sections and keys ignoring case, the last value winning; it swallows the
/// lines after a bad header; it skips stray lines) are errors naming the line.

#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>

#include <gtest/gtest.h>

namespace
{
using namespace esif;

/// The ConfigError message for `text`, or "" when it loads.
std::string errorOf(const std::string& text)
{
	try
	{
		ConfigFile::fromText(text, "c.ini");
	}
	catch (const ConfigError& e)
	{
		return e.what();
	}
	return "";
}

TEST(ConfigFile, RepeatedKeysAndSectionsAreErrorsNamingBothLines)
{
	EXPECT_EQ(errorOf("[esif]\nplugin = A\n; comment\nplugin = B\n"),
			  "c.ini:4: key 'plugin' in [esif] appears again (first at line 2; names are compared ignoring case)");
	EXPECT_EQ(errorOf("[esif]\nplugin = A\nPlugin = B\n"),
			  "c.ini:3: key 'Plugin' in [esif] appears again (first at line 2; names are compared ignoring case)");
	EXPECT_EQ(errorOf("[esif]\nplugin = A\n[ekf]\nx = 1\n[ESIF]\nlabel = l\n"),
			  "c.ini:5: section [ESIF] appears again (first at line 1; names are compared ignoring case)");
	// The same key in two sections is two keys.
	EXPECT_EQ(errorOf("[a]\nx = 1\n[b]\nx = 2\n"), "");
}

TEST(ConfigFile, MalformedHeadersAndStrayLinesAreErrors)
{
	EXPECT_EQ(errorOf("[esif]\nplugin = A\n[\nfoo = 1\n"), "c.ini:3: '[' is not a section header of the form [name]");
	EXPECT_EQ(errorOf("[esif\nplugin = A\n"), "c.ini:1: '[esif' is not a section header of the form [name]");
	EXPECT_EQ(errorOf("[ ]\n"), "c.ini:1: '[ ]' is not a section header of the form [name]");
	EXPECT_EQ(errorOf("[a]]\n"), "c.ini:1: '[a]]' is not a section header of the form [name]");
	EXPECT_EQ(errorOf("[esif]\nplugin EkfSlam\n"),
			  "c.ini:2: 'plugin EkfSlam' is neither a [section], a key = value line nor a comment");
	EXPECT_EQ(errorOf("[esif]\n = 3\n"), "c.ini:2: '= 3' is neither a [section], a key = value line nor a comment");
}

/// MRPT joins a line ending in '\' with the next (the key there is lost
/// into the value) and stops reading at a NUL byte (the rest of the file is
/// silently dropped): both are errors naming the line.
TEST(ConfigFile, ContinuationLinesAndControlCharactersAreErrors)
{
	EXPECT_EQ(errorOf("[esif]\nlabel = ekf \\\nhide_landmark_ids = true\n"),
			  "c.ini:2: ends in '\\', which MRPT's parser joins with the next line; esif configs have no continued "
			  "lines: remove the '\\'");
	EXPECT_EQ(errorOf("; a comment \\\n[esif]\n"),
			  "c.ini:1: ends in '\\', which MRPT's parser joins with the next line, so that line would be lost in "
			  "this comment; esif configs have no continued lines: remove the '\\'");
	EXPECT_NE(errorOf("[a]\nx = 1 // note \\\n\n").find("c.ini:2: ends in '\\'"), std::string::npos)
		<< "a value ending in '\\' takes in the next line, whatever it holds";
	EXPECT_EQ(errorOf("# run: esif run \\\n#   --out x\n[esif]\nplugin = A\n"), "")
		<< "a shell command in comments, continued on a comment line, loses nothing";
	EXPECT_EQ(errorOf(std::string("[ekf]\njacobians = first_estimates\0\nx = 1\n", 41)),
			  "c.ini:2: control character 0x00 at column 28 (a NUL byte: MRPT's parser would drop the rest of the "
			  "file); a config is plain text");
	EXPECT_EQ(errorOf("[esif]\nlabel = a\x1b[31m\n"),
			  "c.ini:2: control character 0x1b at column 10; a config is plain text");
	EXPECT_EQ(errorOf("[esif]\r\n\tlabel = a b\r\n"), "") << "tabs and CR-LF line ends are text";
	EXPECT_EQ(errorOf("[esif]\nlabel = a\\b\n"), "") << "a backslash inside a value is fine";
}

TEST(ConfigFile, CommentsBlanksAndIndentationAreFine)
{
	const auto c = ConfigFile::fromText("; top\n# also\n\n  [esif]  \r\n\tplugin = EkfSlam ; note\r\nlabel=x\n", "c.ini");
	EXPECT_TRUE(c.hasSection("esif"));
}

}  // namespace
