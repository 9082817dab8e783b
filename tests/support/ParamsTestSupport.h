#pragma once
/// \file ParamsTestSupport.h
/// Loading a parameter struct from INI text as a plugin would (strict keys),
/// and catching the one-line ConfigError it gives.

#include <esif/config/ConfigFile.h>
#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>

#include <string>

namespace esif::test
{
/// Loads `Params` from section [section] of the INI text `body` (file name
/// "<section>.ini" in errors) and rejects unknown keys.
template <class Params>
Params loadParamsText(const std::string& section, const std::string& body)
{
	Params p;
	const auto s = ConfigFile::fromText("[" + section + "]\n" + body, section + ".ini").section(section);
	loadParams(p, s);
	s.rejectUnknownKeys();
	return p;
}

/// The ConfigError message of loadParamsText, or "" when it loads.
template <class Params>
std::string paramsErrorOf(const std::string& section, const std::string& body)
{
	try
	{
		loadParamsText<Params>(section, body);
	}
	catch (const ConfigError& e)
	{
		return e.what();
	}
	return "";
}

}  // namespace esif::test
