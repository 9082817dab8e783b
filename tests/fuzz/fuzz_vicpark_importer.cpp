/// \file fuzz_vicpark_importer.cpp
/// libFuzzer target: `esif import victoria-park` on any text (ImporterInput.h).

#include "ImporterInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
	return esif::fuzz::reportFinding(
		esif::fuzz::victoriaParkVerdict(std::string(reinterpret_cast<const char*>(data), size)));
}
