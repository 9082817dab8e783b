/// \file Html.cpp
/// Escaping, tables, inlined figures and the page; see Html.h.

#include <esif/report/Html.h>

#include <mrpt/system/string_utils.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <vector>

namespace fs = std::filesystem;

namespace esif::html
{
namespace
{
/// Looks like a number to right-align: digits, sign, point, exponent, separators, "-" for none.
bool numeric(const std::string& text)
{
	if (text.empty()) return false;
	return text.find_first_not_of("0123456789+-.,eE% ") == std::string::npos;
}

std::string attribute(const char* name, const std::string& value)
{
	return value.empty() ? std::string() : std::string(" ") + name + "=\"" + escape(value) + "\"";
}

std::string cell(const Cell& c)
{
	const char* tag = c.heading ? "th" : "td";
	const std::string css = !c.heading && numeric(c.text) ? " class=\"num\"" : "";
	return std::string("<") + tag + css + attribute("title", c.title) + ">" + escape(c.text) + "</" + tag + ">";
}

std::string row(const std::vector<Cell>& cells)
{
	std::string out = "<tr>";
	for (const auto& c : cells) out += cell(c);
	return out + "</tr>\n";
}

constexpr unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

std::uint32_t bigEndian32(const std::string& bytes, std::size_t at)
{
	std::uint32_t v = 0;
	for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
	return v;
}

/// Why the PNG bytes are not inlined, or nothing: signature, IHDR and its size.
std::optional<std::string> pngProblem(const std::string& bytes)
{
	// Signature (8), IHDR length (4) and type (4), width (4), height (4).
	if (bytes.size() < 24 || bytes.compare(0, 8, reinterpret_cast<const char*>(kPngSignature), 8) != 0 ||
		bytes.compare(12, 4, "IHDR") != 0)
		return std::string("not a PNG file");
	const std::uint32_t w = bigEndian32(bytes, 16), h = bigEndian32(bytes, 20);
	if (w == 0 || h == 0 || w > kMaxImagePixels || h > kMaxImagePixels)
		return "image of " + std::to_string(w) + " x " + std::to_string(h) + " pixels (limit " +
			   std::to_string(kMaxImagePixels) + " each way)";
	return std::nullopt;
}

/// The file's bytes, or (empty) why they are not read: missing, not a file, too large, unreadable.
std::pair<std::optional<std::string>, std::string> readBounded(const std::string& path, std::uintmax_t max_bytes)
{
	std::error_code ec;
	if (!fs::exists(path, ec)) return {std::nullopt, "missing"};
	if (!fs::is_regular_file(path, ec)) return {std::nullopt, "not a regular file"};
	const std::uintmax_t size = fs::file_size(path, ec);
	if (ec) return {std::nullopt, "unreadable"};
	if (size > max_bytes)
		return {std::nullopt, std::to_string(size) + " bytes (limit " + std::to_string(max_bytes) + ")"};
	std::ifstream in(path, std::ios::binary);
	std::string bytes(static_cast<std::size_t>(size), '\0');
	if (!in.read(bytes.data(), static_cast<std::streamsize>(size))) return {std::nullopt, "unreadable"};
	return {std::move(bytes), ""};
}

std::string missingFigure(const std::string& path, const std::string& caption, const std::string& problem)
{
	return "<p class=\"note\">" + escape(caption) + ": " + escape(fs::path(path).filename().string()) +
		   " not shown (" + escape(problem) + ")</p>\n";
}

constexpr const char* kStyle =
	"body{font-family:sans-serif;margin:1.5em;color:#222}"
	"table{border-collapse:collapse;margin:0.5em 0}"
	"th,td{border:1px solid #bbb;padding:0.2em 0.5em}"
	"thead th{background:#eee}"
	"tbody th{text-align:left;font-weight:normal;font-family:monospace}"
	"code{font-size:1.05em}"
	"th[title]{text-decoration:underline dotted;cursor:help}"
	"td.num{text-align:right;font-variant-numeric:tabular-nums}"
	"figure{margin:1em 0}"
	"figure img{max-width:100%;height:auto;border:1px solid #ddd}"
	"figcaption{font-size:0.9em;color:#555}"
	"dl.legend dt{font-weight:bold;margin-top:0.3em}"
	"dl.legend dd{margin-left:1.5em}"
	"p.note{color:#8a4b00}"
	".runs{display:flex;flex-wrap:wrap;gap:1em}"
	".runs section{flex:1 1 560px}";
}  // namespace

std::string escape(std::string_view text)
{
	std::string out;
	out.reserve(text.size());
	for (const char c : text)
	{
		switch (c)
		{
			case '&': out += "&amp;"; break;
			case '<': out += "&lt;"; break;
			case '>': out += "&gt;"; break;
			case '"': out += "&quot;"; break;
			case '\'': out += "&#39;"; break;
			default: out += c;
		}
	}
	return out;
}

std::string withCode(std::string_view text)
{
	std::string out;
	bool code = false;
	std::size_t from = 0;
	for (std::size_t tick = text.find('`'); tick != std::string_view::npos; tick = text.find('`', from))
	{
		if (!code && text.find('`', tick + 1) == std::string_view::npos) break;	// a lone backtick stays
		out += escape(text.substr(from, tick - from)) + (code ? "</code>" : "<code>");
		code = !code;
		from = tick + 1;
	}
	return out + escape(text.substr(from));
}

std::string base64(std::string_view bytes)
{
	// MRPT's encoder wraps its output in lines; a data: URI wants none.
	std::string out;
	mrpt::system::encodeBase64(std::vector<std::uint8_t>(bytes.begin(), bytes.end()), out);
	out.erase(std::remove(out.begin(), out.end(), '\n'), out.end());
	return out;
}

std::string table(const Table& t)
{
	std::string out = "<table>\n<thead>" + row(t.header) + "</thead>\n<tbody>\n";
	for (const auto& r : t.rows) out += row(r);
	return out + "</tbody>\n</table>\n";
}

std::string pngFigure(const std::string& path, const std::string& caption, std::uintmax_t max_bytes)
{
	const auto [bytes, problem] = readBounded(path, max_bytes);
	if (!bytes) return missingFigure(path, caption, problem);
	if (const auto bad = pngProblem(*bytes)) return missingFigure(path, caption, *bad);
	return "<figure><img src=\"data:image/png;base64," + base64(*bytes) + "\" alt=\"" + escape(caption) +
		   "\" width=\"" + std::to_string(bigEndian32(*bytes, 16)) + "\" height=\"" +
		   std::to_string(bigEndian32(*bytes, 20)) + "\"><figcaption>" + escape(caption) + "</figcaption></figure>\n";
}

std::string heading(int level, std::string_view text)
{
	const std::string h = "h" + std::to_string(level);
	return "<" + h + ">" + escape(text) + "</" + h + ">\n";
}

std::string paragraph(std::string_view text, std::string_view css_class)
{
	return "<p" + attribute("class", std::string(css_class)) + ">" + escape(text) + "</p>\n";
}

std::string paragraphs(std::string_view lines, std::string_view css_class)
{
	std::string out;
	std::istringstream in{std::string(lines)};
	for (std::string line; std::getline(in, line);)
		if (!line.empty()) out += paragraph(line, css_class);
	return out;
}

std::string list(const std::vector<std::string>& items)
{
	std::string out = "<ul>\n";
	for (const auto& item : items) out += "<li>" + escape(item) + "</li>\n";
	return out + "</ul>\n";
}

std::string legend(const std::vector<std::pair<std::string, std::string>>& entries, bool code_terms)
{
	std::string out = "<dl class=\"legend\">\n";
	for (const auto& [term, description] : entries)
		out += "<dt>" + (code_terms ? "<code>" + escape(term) + "</code>" : escape(term)) + "</dt><dd>" +
			   withCode(description) + "</dd>\n";
	return out + "</dl>\n";
}

std::string page(std::string_view title, const std::string& body)
{
	return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + escape(title) +
		   "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n" + heading(1, title) + body +
		   "</body>\n</html>\n";
}

}  // namespace esif::html
