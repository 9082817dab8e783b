/// \file fuzz_ini_reader.cpp
/// libFuzzer target: any text read as an esif INI file and bound to the
/// host's [esif] parameters must load or give one ConfigError line; any other
/// exception, a crash or a sanitizer report is a finding.

#include <esif/config/ConfigFile.h>
#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/run/HostParams.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
	try
	{
		const auto cfg =
			esif::ConfigFile::fromText(std::string(reinterpret_cast<const char*>(data), size), "fuzz.ini");
		esif::HostParams host;
		esif::loadParams(host, cfg.section("esif"));
	}
	catch (const esif::ConfigError& e)
	{
		if (std::string(e.what()).find('\n') != std::string::npos)
		{
			std::fprintf(stderr, "message is not one line: %s\n", e.what());
			std::abort();
		}
	}
	return 0;
}
