/// \file fuzz_mrclam_importer.cpp
/// libFuzzer target: `esif import mrclam` on a recording one of whose five
/// files is replaced by the input (ImporterInput.h).

#include "ImporterInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
	return esif::fuzz::reportFinding(
		esif::fuzz::mrclamVerdict(std::string(reinterpret_cast<const char*>(data), size)));
}
