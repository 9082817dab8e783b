/// \file fuzz_ground_truth_reader.cpp
/// libFuzzer target: the readers of a rawlog's side files, picked by the
/// first input byte (GroundTruthInput.h).

#include "GroundTruthInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
	return esif::fuzz::reportFinding(
		esif::fuzz::groundTruthVerdict(std::string(reinterpret_cast<const char*>(data), size)));
}
