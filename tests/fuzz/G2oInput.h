#pragma once
/// \file G2oInput.h
/// One fuzz input for the g2o reader (G2oFormat.h): any text must give a
/// graph or one InputError line naming the file. Used by fuzz_g2o_reader
/// and test_FuzzRegressions.

#include "FuzzSupport.h"

#include <esif/formats/G2oFormat.h>

namespace esif::fuzz
{
inline Verdict g2oVerdict(const std::string& input)
{
	const std::string path = fileIn("input.g2o");
	writeFile(path, input.data(), input.size());
	return verdictOf(path, [&] { readG2oFile(path); });
}
}  // namespace esif::fuzz
