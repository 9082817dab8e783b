#include <esif/core/Errors.h>
#include <esif/core/TerminalText.h>
#include <esif/core/Text.h>

#include <filesystem>
#include <new>

#include <cstdio>
#include <sstream>

namespace esif
{
std::string oneLineReason(const std::string& text)
{
	std::istringstream lines(text);
	for (std::string line; std::getline(lines, line);)
	{
		line.erase(0, line.find_first_not_of(" \t"));
		if (line.empty() || line.rfind("====", 0) == 0) continue;
		if (line.rfind("Message:", 0) == 0) line.erase(0, line.find_first_not_of(" \t", 8));
		if (!line.empty()) return line;
	}
	return text.substr(0, text.find('\n'));
}

namespace
{
std::string hexByte(unsigned char c)
{
	char code[5];
	std::snprintf(code, sizeof(code), "\\x%02x", c);
	return code;
}
}  // namespace

std::string printableToken(const std::string& token, std::size_t max_chars)
{
	std::string out;
	std::size_t shown = 0;
	for (const char ch : token)
	{
		if (shown == max_chars) return out + "...";
		const auto c = static_cast<unsigned char>(ch);
		out += c >= 0x20 && c < 0x7f ? std::string(1, ch) : hexByte(c);
		++shown;
	}
	return out;
}

void rethrowWithPathReplaced(const std::string& from, const std::string& to)
{
	try
	{
		throw;
	}
	catch (const ConfigError& e)
	{
		throw ConfigError(replaceAll(e.what(), from, to));
	}
	catch (const InputError& e)
	{
		throw InputError(replaceAll(e.what(), from, to));
	}
	catch (const NumericalError& e)
	{
		throw NumericalError(replaceAll(e.what(), from, to));
	}
	catch (const std::bad_alloc&)
	{
		throw;	// out of memory stays out of memory (exit 3), whatever it names
	}
	catch (const std::filesystem::filesystem_error&)
	{
		throw;
	}
	catch (const std::exception& e)
	{
		throw std::runtime_error(replaceAll(e.what(), from, to));
	}
}

FailureReport reportCurrentException()
{
	const auto report = [](int code, const std::string& kind, const std::string& what) {
		return FailureReport{code, kind + escapedForTerminal(what)};
	};
	try
	{
		throw;
	}
	catch (const ConfigError& e)
	{
		return report(1, "esif: error: ", e.what());
	}
	catch (const InputError& e)
	{
		return report(1, "esif: error: ", e.what());
	}
	catch (const NumericalError& e)
	{
		return report(3, "esif: numerical failure: ", e.what());
	}
	catch (const std::filesystem::filesystem_error& e)
	{
		// A path esif could not stat, list or create that no reader checked
		// first: the path and the system's reason, an input problem.
		return report(1, "esif: error: ", e.path1().string() + ": " + e.code().message());
	}
	catch (const std::bad_alloc&)
	{
		return report(3, "esif: ", "out of memory");
	}
	catch (const std::exception& e)
	{
		// MRPT exceptions carry a banner and a multi-line stack: one line of reason.
		return report(4, "esif: internal error: ", oneLineReason(e.what()));
	}
	catch (...)
	{
		return report(4, "esif: internal error: ", "an exception of unknown type");
	}
}

}  // namespace esif
