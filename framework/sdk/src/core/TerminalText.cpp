/// \file TerminalText.cpp
/// The byte filter of TerminalText.h: a small UTF-8 decoder that keeps what
/// a terminal shows as text and escapes what it would act on.

#include <esif/core/TerminalText.h>

#include <cstdio>

namespace esif
{
namespace
{
std::string escapedByte(unsigned char c)
{
	char code[5];
	std::snprintf(code, sizeof(code), "\\x%02x", c);
	return code;
}

std::string escapedBytes(const std::string& bytes)
{
	std::string out;
	for (const char b : bytes) out += escapedByte(static_cast<unsigned char>(b));
	return out;
}

/// Length of the UTF-8 sequence `lead` starts; 0 when no valid one starts
/// with it (a continuation byte, an overlong lead 0xc0/0xc1, 0xf5 and up).
std::size_t sequenceLength(unsigned char lead)
{
	if (lead >= 0xc2 && lead <= 0xdf) return 2;
	if (lead >= 0xe0 && lead <= 0xef) return 3;
	if (lead >= 0xf0 && lead <= 0xf4) return 4;
	return 0;
}

/// Whether `c` may follow `lead` (RFC 3629's table: no overlong form, no
/// surrogate, nothing beyond U+10FFFF).
bool validSecondByte(unsigned char lead, unsigned char c)
{
	if (c < 0x80 || c > 0xbf) return false;
	if (lead == 0xe0) return c >= 0xa0;
	if (lead == 0xed) return c <= 0x9f;
	if (lead == 0xf0) return c >= 0x90;
	if (lead == 0xf4) return c <= 0x8f;
	return true;
}

unsigned codePointOf(const std::string& sequence)
{
	const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(sequence[i]); };
	unsigned cp = byte(0) & (sequence.size() == 2 ? 0x1fu : sequence.size() == 3 ? 0x0fu : 0x07u);
	for (std::size_t i = 1; i < sequence.size(); ++i) cp = (cp << 6) | (byte(i) & 0x3fu);
	return cp;
}

/// C1 controls, and the bidirectional marks, embeddings, overrides and
/// isolates, which make a terminal show text in another order than it is.
bool actsOnTerminal(unsigned cp)
{
	return (cp >= 0x80 && cp <= 0x9f) || cp == 0x061c || cp == 0x200e || cp == 0x200f ||
		   (cp >= 0x202a && cp <= 0x202e) || (cp >= 0x2066 && cp <= 0x2069);
}
}  // namespace

std::string TerminalTextFilter::feed(const char* data, std::size_t size)
{
	std::string out;
	for (std::size_t i = 0; i < size; ++i)
	{
		const auto c = static_cast<unsigned char>(data[i]);
		if (!pending_.empty())
		{
			const auto lead = static_cast<unsigned char>(pending_[0]);
			const bool continues = pending_.size() == 1 ? validSecondByte(lead, c) : c >= 0x80 && c <= 0xbf;
			if (continues)
			{
				pending_ += static_cast<char>(c);
				if (pending_.size() == sequenceLength(lead)) settle(out);
				continue;
			}
			out += escapedBytes(pending_);	// a sequence cut short: not UTF-8
			pending_.clear();
		}
		if (c < 0x80)
		{
			const bool line_break = c == '\n' || c == '\t';
			out += (c < 0x20 && !(keep_line_breaks_ && line_break)) || c == 0x7f ? escapedByte(c)
																				 : std::string(1, static_cast<char>(c));
		}
		else if (sequenceLength(c) > 0)
			pending_ = static_cast<char>(c);
		else
			out += escapedByte(c);
	}
	return out;
}

std::string TerminalTextFilter::finish()
{
	std::string out = escapedBytes(pending_);
	pending_.clear();
	return out;
}

void TerminalTextFilter::settle(std::string& out)
{
	out += actsOnTerminal(codePointOf(pending_)) ? escapedBytes(pending_) : pending_;
	pending_.clear();
}

std::string escapedForTerminal(const std::string& text)
{
	TerminalTextFilter filter(false);
	std::string out = filter.feed(text.data(), text.size());
	return out + filter.finish();  // after feed: the operands of + have no order
}

}  // namespace esif
