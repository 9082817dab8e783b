/// \file fuzz_localmap_reader.cpp
/// libFuzzer target: the local-map folder readers, one file of a valid
/// folder replaced by the input (LocalMapInput.h).

#include "LocalMapInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
	return esif::fuzz::reportFinding(
		esif::fuzz::localMapVerdict(std::string(reinterpret_cast<const char*>(data), size)));
}
