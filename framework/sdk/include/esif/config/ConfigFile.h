#pragma once
/// \file ConfigFile.h
/// An INI file read through MRPT's config classes, with strict checks MRPT
/// leaves out: a missing file is an error (MRPT yields an empty config), a
/// repeated section or key, a malformed header or a stray line is an error
/// naming its line (MRPT merges or skips them silently), and values are
/// parsed strictly by ConfigSection.

#include <esif/config/ConfigSection.h>

#include <map>
#include <string>
#include <vector>

namespace esif
{
class ConfigFile
{
   public:
	/// Reads `path`; throws ConfigError if it is missing or unreadable.
	static ConfigFile load(const std::string& path);
	/// Parses INI text held in memory (tests, overrides); `origin` names it in errors.
	static ConfigFile fromText(const std::string& text, const std::string& origin);

	/// Section `name`; an empty section (all keys defaulted) when absent.
	ConfigSection section(const std::string& name) const;
	bool hasSection(const std::string& name) const;
	std::vector<std::string> sectionNames() const;
	const std::string& origin() const { return origin_; }

	/// Sets or overrides one value (command-line or test overrides).
	void set(const std::string& section, const std::string& key, const std::string& value);

   private:
	std::string origin_;
	std::map<std::string, std::map<std::string, std::string>> values_;
};

}  // namespace esif
