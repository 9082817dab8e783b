/// \file fuzz_rawlog_reader.cpp
/// libFuzzer target: any byte string read as an (inflated) rawlog must give
/// a Rawlog or one InputError line; any other exception, a crash or memory
/// beyond libFuzzer's -rss_limit_mb is a finding. MRPT's own deserialisers
/// run in the reader's sandboxed child, so their faults must surface here as
/// InputError too.

#include <esif/core/Errors.h>
#include <esif/formats/RawlogReader.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
	try
	{
		const esif::Rawlog log =
			esif::readRawlogFromMemory("fuzz.rawlog", std::string(reinterpret_cast<const char*>(data), size));
		if (log.steps.empty()) std::abort();  // the reader promises at least one step
	}
	catch (const esif::InputError& e)
	{
		const std::string line = e.what();
		// One line naming the input: the promise esif makes for every bad file.
		if (line.find('\n') != std::string::npos || line.rfind("fuzz.rawlog", 0) != 0)
		{
			std::fprintf(stderr, "message is not one line naming the file: %s\n", e.what());
			std::abort();
		}
	}
	return 0;
}
