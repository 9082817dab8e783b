#pragma once
/// \file TerminalText.h
/// Text esif prints may carry a user's bytes (a path, a label, a token), and
/// a terminal takes some bytes as commands: C0 controls (ESC starts a
/// sequence that can move the cursor, retitle the window or rewrite the
/// screen), DEL, and the C1 controls, raw (0x9b is an 8-bit CSI to many
/// terminals) or UTF-8 encoded (U+0080-U+009F). This filter shows each such
/// byte as \xNN, together with any byte that is not valid UTF-8 and the
/// Unicode bidirectional formatting characters (which reorder what is
/// shown); UTF-8 names are kept. It works on a stream of bytes, so text
/// written in pieces is filtered as a whole (a UTF-8 sequence may be cut
/// between two writes).

#include <cstddef>
#include <string>

namespace esif
{
class TerminalTextFilter
{
   public:
	/// With `keep_line_breaks`, '\n' and '\t' pass (program output); without,
	/// they are escaped too (an error message must stay one line).
	explicit TerminalTextFilter(bool keep_line_breaks) : keep_line_breaks_(keep_line_breaks) {}

	/// The filtered form of `size` more bytes; an unfinished UTF-8 sequence
	/// at their end is held until the next call or finish().
	std::string feed(const char* data, std::size_t size);
	/// What is held (an unfinished sequence, shown escaped).
	std::string finish();

   private:
	void settle(std::string& out);

	bool keep_line_breaks_;
	std::string pending_;  ///< the start of a UTF-8 sequence not yet complete
};

/// `text` through a TerminalTextFilter that escapes line breaks too.
std::string escapedForTerminal(const std::string& text);

}  // namespace esif
