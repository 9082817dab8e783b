/// \file fuzz_g2o_reader.cpp
/// libFuzzer target: any text read as a g2o file (G2oInput.h).

#include "G2oInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
	return esif::fuzz::reportFinding(esif::fuzz::g2oVerdict(std::string(reinterpret_cast<const char*>(data), size)));
}
