#include <esif/core/Errors.h>

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

std::string withoutControlCharacters(const std::string& text)
{
	std::string out;
	for (const char ch : text)
	{
		const auto c = static_cast<unsigned char>(ch);
		out += c < 0x20 || c == 0x7f ? hexByte(c) : std::string(1, ch);
	}
	return out;
}

}  // namespace esif
