#pragma once
/// \file Markdown.h
/// Text taken from a config, a path or a run's error (a label, a file name,
/// an error line) inside esif's Markdown files (comparison.md, summary.md):
/// it must show as written, never end a table cell or a row, and never be
/// HTML to a renderer that lets inline HTML through.

#include <string>

namespace esif::markdown
{
/// `text` with '|', '&', '<' and '>' as character references: a '|' would
/// end a GFM table cell (a reference is decoded after the cells are split,
/// so the reader sees the '|' and no tool splits there), and no tag and no
/// entity of the user's reaches the page; line breaks become spaces (a row
/// is one line). Emphasis characters are left as they are: they change a
/// word's look, not the table or the page.
std::string text(const std::string& raw);

/// The same for text of several lines (a note under a table): each line
/// escaped as text(), the line breaks kept.
std::string lines(const std::string& raw);

}  // namespace esif::markdown
