#pragma once
/// \file Html.h
/// The pieces of esif's one-page HTML reports (comparison.html,
/// summary.html): escaping, tables, figures inlined as data: URIs and the
/// page around them. A page is self-contained: inline CSS, images in the
/// page, no external resource and no script. Every text taken from a file,
/// a config or a path goes through escape().

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace esif::html
{
/// `text` with & < > " ' replaced by entities: safe in element content and
/// in quoted attribute values.
std::string escape(std::string_view text);

/// escape(text) with each `span` between backticks set in `<code>`.
std::string withCode(std::string_view text);

/// RFC 4648 base64 of `bytes`, with padding and no line breaks.
std::string base64(std::string_view bytes);

/// A table cell: its text (escaped when rendered), an optional hover
/// explanation (the title attribute) and whether it is a heading cell.
struct Cell
{
	std::string text;
	std::string title;
	bool heading = false;
};

/// A table: the header row, then the body rows.
struct Table
{
	std::vector<Cell> header;
	std::vector<std::vector<Cell>> rows;
};

/// `<table>` with `<thead>` and `<tbody>`; numeric-looking body cells are right-aligned by the page's CSS.
std::string table(const Table& t);

/// Largest image file inlined, and largest width or height in pixels.
inline constexpr std::uintmax_t kMaxImageBytes = 16u << 20;
inline constexpr std::uint32_t kMaxImagePixels = 16384;

/// A `<figure>` with the PNG at `path` inlined as a data: URI and
/// `caption` under it. A missing, unreadable, too large (`max_bytes`,
/// kMaxImagePixels) or non-PNG file gives a note in the page instead.
std::string pngFigure(const std::string& path, const std::string& caption, std::uintmax_t max_bytes = kMaxImageBytes);

/// `<h{level}>` with escaped text.
std::string heading(int level, std::string_view text);
/// `<p>` with escaped text; `css_class` may be empty.
std::string paragraph(std::string_view text, std::string_view css_class = "");
/// One `<p>` per non-empty line of `lines`.
std::string paragraphs(std::string_view lines, std::string_view css_class = "");
/// `<ul>` of escaped items.
std::string list(const std::vector<std::string>& items);

/// A definition list: each term (in `<code>` when `code_terms`) with its
/// description, escaped, `spans` in backticks set as code (withCode).
std::string legend(const std::vector<std::pair<std::string, std::string>>& entries, bool code_terms);

/// The whole document: doctype, UTF-8, escaped `title`, the inline style
/// sheet and `body` (already HTML).
std::string page(std::string_view title, const std::string& body);

}  // namespace esif::html
