/// \file TerminalStreams.cpp
/// A streambuf that filters the bytes on their way to the stream's own
/// buffer; see TerminalStreams.h.

#include "TerminalStreams.h"

#include <esif/core/TerminalText.h>

#include <iostream>
#include <streambuf>

namespace esif::app
{
namespace
{
/// Forwards every byte at once (no buffer of its own, so output keeps its
/// order with stdio and with the other stream), filtered.
class FilteringBuffer : public std::streambuf
{
   public:
	explicit FilteringBuffer(std::streambuf* target) : target_(target), filter_(true) {}

	void finish()
	{
		forward(filter_.finish());
		target_->pubsync();
	}

   protected:
	int_type overflow(int_type c) override
	{
		if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
		const char byte = traits_type::to_char_type(c);
		return forward(filter_.feed(&byte, 1)) ? c : traits_type::eof();
	}

	std::streamsize xsputn(const char* s, std::streamsize n) override
	{
		return forward(filter_.feed(s, static_cast<std::size_t>(n))) ? n : 0;
	}

	int sync() override { return target_->pubsync(); }

   private:
	bool forward(const std::string& bytes)
	{
		return target_->sputn(bytes.data(), static_cast<std::streamsize>(bytes.size())) ==
			   static_cast<std::streamsize>(bytes.size());
	}

	std::streambuf* target_;
	TerminalTextFilter filter_;
};

FilteringBuffer* out_buffer = nullptr;
FilteringBuffer* err_buffer = nullptr;
}  // namespace

void filterTerminalStreams()
{
	if (out_buffer) return;
	// Never freed: the process ends with _Exit (HostMain.cpp), and a stream
	// may be written until then.
	out_buffer = new FilteringBuffer(std::cout.rdbuf());
	err_buffer = new FilteringBuffer(std::cerr.rdbuf());
	std::cout.rdbuf(out_buffer);
	std::cerr.rdbuf(err_buffer);
}

void finishTerminalStreams()
{
	if (out_buffer) out_buffer->finish();
	if (err_buffer) err_buffer->finish();
	std::cout.flush();
	std::cerr.flush();
}

}  // namespace esif::app
