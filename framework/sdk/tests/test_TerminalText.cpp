// What esif prints may carry a user's bytes: the terminal filter
// (TerminalText.h) shows every byte a terminal would act on as \xNN and
// keeps UTF-8 text; the failure report (Errors.h) maps every exception to
// its exit code and one filtered line.

#include <esif/core/Errors.h>
#include <esif/core/TerminalText.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <new>
#include <system_error>

namespace
{
using esif::escapedForTerminal;
using esif::TerminalTextFilter;

TEST(TerminalText, ControlsRawOrUtf8EncodedAreShownEscaped)
{
	EXPECT_EQ(escapedForTerminal("a\x1b[31mb"), "a\\x1b[31mb");	// ESC: a C0 control
	EXPECT_EQ(escapedForTerminal("a\nb\tc\x7f"), "a\\x0ab\\x09c\\x7f");
	// C1 controls: 0x9b alone is an 8-bit CSI (and no UTF-8), c2 9b is U+009B.
	EXPECT_EQ(escapedForTerminal("\x9b" "31m"), "\\x9b31m");
	EXPECT_EQ(escapedForTerminal("\xc2\x9b" "32m"), "\\xc2\\x9b32m");
	EXPECT_EQ(escapedForTerminal("\xc2\x85"), "\\xc2\\x85");	// NEL
	// A bidirectional override reorders what the terminal shows.
	EXPECT_EQ(escapedForTerminal("a\xe2\x80\xae" "b"), "a\\xe2\\x80\\xaeb");
}

TEST(TerminalText, Utf8TextIsKeptAndBrokenUtf8Escaped)
{
	EXPECT_EQ(escapedForTerminal("Kn\xc3\xb6" "del \xe2\x82\xac \xf0\x9f\x98\x80"), "Kn\xc3\xb6" "del \xe2\x82\xac \xf0\x9f\x98\x80");
	EXPECT_EQ(escapedForTerminal("\xc2\xa0"), "\xc2\xa0");	// U+00A0, just past the C1 block
	EXPECT_EQ(escapedForTerminal("\xc3"), "\\xc3");	 // cut short at the end
	EXPECT_EQ(escapedForTerminal("\xc3(x"), "\\xc3(x");  // cut short by an ASCII byte
	EXPECT_EQ(escapedForTerminal("\xc0\xaf"), "\\xc0\\xaf");  // an overlong '/'
	EXPECT_EQ(escapedForTerminal("\xed\xa0\x80"), "\\xed\\xa0\\x80");  // a surrogate
	EXPECT_EQ(escapedForTerminal("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");	// beyond U+10FFFF
}

TEST(TerminalText, ASequenceCutBetweenTwoWritesIsJudgedWhole)
{
	TerminalTextFilter filter(true);
	std::string out = filter.feed("x\xc2", 2);
	EXPECT_EQ(out, "x");  // held until the next byte says what it is
	out += filter.feed("\x9b" "y\n", 3);
	out += filter.feed("\xc3", 1);
	out += filter.feed("\xa9", 1);
	out += filter.feed("\xe2\x82", 2);
	out += filter.finish();
	EXPECT_EQ(out, "x\\xc2\\x9by\n\xc3\xa9\\xe2\\x82");  // line breaks kept for program output
}

/// The exit code and line of the exception `make` throws.
template <class Make>
esif::FailureReport reportOf(Make&& make)
{
	try
	{
		make();
	}
	catch (...)
	{
		return esif::reportCurrentException();
	}
	ADD_FAILURE() << "nothing thrown";
	return {};
}

TEST(FailureReport, EachExceptionHasItsExitCodeAndOneFilteredLine)
{
	const auto config = reportOf([] { throw esif::ConfigError("a.ini: [x] y: bad"); });
	EXPECT_EQ(config.exit_code, 1);
	EXPECT_EQ(config.line, "esif: error: a.ini: [x] y: bad");
	EXPECT_EQ(reportOf([] { throw esif::InputError("f\x1b]0;title\x07"); }).line, "esif: error: f\\x1b]0;title\\x07");
	const auto numeric = reportOf([] { throw esif::NumericalError("step 3: not finite"); });
	EXPECT_EQ(numeric.exit_code, 3);
	EXPECT_EQ(numeric.line, "esif: numerical failure: step 3: not finite");
	// Out of memory wherever it happens: 3, never an internal error.
	const auto memory = reportOf([] { throw std::bad_alloc(); });
	EXPECT_EQ(memory.exit_code, 3);
	EXPECT_EQ(memory.line, "esif: out of memory");
	const auto path = reportOf([] {
		throw std::filesystem::filesystem_error("x", "/no/where", std::make_error_code(std::errc::permission_denied));
	});
	EXPECT_EQ(path.exit_code, 1);
	EXPECT_EQ(path.line, "esif: error: /no/where: Permission denied");
	const auto other = reportOf([] { throw std::runtime_error("==== MRPT exception ====\nMessage: bad thing\nstack"); });
	EXPECT_EQ(other.exit_code, 4);
	EXPECT_EQ(other.line, "esif: internal error: bad thing");
	EXPECT_EQ(reportOf([] { throw 42; }).exit_code, 4);
}

TEST(FailureReport, ARenamedExceptionKeepsItsClass)
{
	const auto renamed = [](auto make) {
		return reportOf([&] {
			try
			{
				make();
			}
			catch (...)
			{
				esif::rethrowWithPathReplaced("/out/.x.partial-1", "/out/x");
			}
		});
	};
	EXPECT_EQ(renamed([] { throw esif::InputError("/out/.x.partial-1/stats.json: cannot write"); }).line,
			  "esif: error: /out/x/stats.json: cannot write");
	EXPECT_EQ(renamed([] { throw esif::NumericalError("/out/.x.partial-1: nan"); }).exit_code, 3);
	EXPECT_EQ(renamed([] { throw std::bad_alloc(); }).exit_code, 3);
}

}  // namespace
