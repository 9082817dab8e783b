#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>
#include <esif/core/TextInput.h>

#include "IniStructure.h"

#include <mrpt/config/CConfigFileMemory.h>

#include <new>

namespace esif
{
namespace
{
/// Reads every section and key through MRPT's INI parser. MRPT strips
/// trailing `//` comments and surrounding blanks; values stay text here and
/// are parsed strictly by ConfigSection.
std::map<std::string, std::map<std::string, std::string>> readAll(const mrpt::config::CConfigFileMemory& cfg)
{
	std::map<std::string, std::map<std::string, std::string>> out;
	std::vector<std::string> sections;
	cfg.getAllSections(sections);
	for (const auto& s : sections)
	{
		std::vector<std::string> keys;
		cfg.getAllKeys(s, keys);
		auto& dst = out[s];
		for (const auto& k : keys) dst[k] = cfg.read_string(s, k, "");
	}
	return out;
}
}  // namespace

ConfigFile ConfigFile::load(const std::string& path)
{
	// MRPT's CConfigFile silently yields an empty config for a missing file.
	std::string text;
	try
	{
		text = readTextFile(path, "config file");
	}
	catch (const InputError& e)
	{
		throw ConfigError(e.what());
	}
	return fromText(text, path);
}

ConfigFile ConfigFile::fromText(const std::string& text, const std::string& origin)
{
	checkIniStructure(text, origin);
	ConfigFile out;
	out.origin_ = origin;
	try
	{
		mrpt::config::CConfigFileMemory cfg(text);
		out.values_ = readAll(cfg);
	}
	catch (const std::bad_alloc&)
	{
		throw;
	}
	catch (const std::exception& e)
	{
		throw ConfigError(origin + ": not a valid INI file: " + oneLineReason(e.what()));
	}
	return out;
}

ConfigSection ConfigFile::section(const std::string& name) const
{
	const auto it = values_.find(name);
	return ConfigSection(origin_, name, it == values_.end() ? std::map<std::string, std::string>{} : it->second);
}

bool ConfigFile::hasSection(const std::string& name) const { return values_.count(name) != 0; }

std::vector<std::string> ConfigFile::sectionNames() const
{
	std::vector<std::string> out;
	for (const auto& kv : values_) out.push_back(kv.first);
	return out;
}

void ConfigFile::set(const std::string& section, const std::string& key, const std::string& value)
{
	values_[section][key] = value;
}

}  // namespace esif
