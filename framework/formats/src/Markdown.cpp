/// \file Markdown.cpp
/// Escaping of foreign text in Markdown; see Markdown.h.

#include <esif/formats/Markdown.h>

#include <algorithm>

namespace esif::markdown
{
std::string text(const std::string& raw)
{
	std::string out;
	out.reserve(raw.size());
	for (const char c : raw)
		switch (c)
		{
			case '|': out += "&#124;"; break;
			case '&': out += "&amp;"; break;
			case '<': out += "&lt;"; break;
			case '>': out += "&gt;"; break;
			case '\n':
			case '\r': out += ' '; break;
			default: out += c;
		}
	return out;
}

std::string lines(const std::string& raw)
{
	std::string out;
	for (std::size_t at = 0; at < raw.size();)
	{
		const std::size_t end = std::min(raw.find('\n', at), raw.size());
		out += text(raw.substr(at, end - at));
		if (end < raw.size()) out += '\n';
		at = end + 1;
	}
	return out;
}

}  // namespace esif::markdown
