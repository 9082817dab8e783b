#include <esif/config/ConfigSection.h>
#include <esif/core/Errors.h>
#include <esif/core/NumberToken.h>

#include <algorithm>
#include <cctype>

namespace esif
{
std::optional<bool> parseBool(const std::string& text)
{
	std::string t = text;
	std::transform(t.begin(), t.end(), t.begin(), [](unsigned char c) { return std::tolower(c); });
	if (t == "true" || t == "1" || t == "yes" || t == "on") return true;
	if (t == "false" || t == "0" || t == "no" || t == "off") return false;
	return std::nullopt;
}

ConfigSection::ConfigSection(std::string origin, std::string name, std::map<std::string, std::string> values)
	: origin_(std::move(origin)),
	  name_(std::move(name)),
	  values_(std::move(values)),
	  used_(std::make_shared<std::set<std::string>>())
{
}

bool ConfigSection::has(const std::string& key) const { return values_.count(key) != 0; }

std::optional<std::string> ConfigSection::raw(const std::string& key) const
{
	const auto it = values_.find(key);
	if (it == values_.end()) return std::nullopt;
	used_->insert(key);
	return it->second;
}

std::string ConfigSection::describe(const std::string& key, const std::string& problem) const
{
	const auto it = values_.find(key);
	const std::string value = it == values_.end() ? std::string() : " = " + it->second;
	return origin_ + ": [" + name_ + "] " + key + value + ": " + problem;
}

std::string ConfigSection::describeKey(const std::string& key, const std::string& problem) const
{
	return origin_ + ": [" + name_ + "] " + key + ": " + problem;
}

double ConfigSection::getDouble(const std::string& key) const
{
	const auto text = raw(key);
	if (!text) throw ConfigError(describeKey(key, "missing (no default): set it in the INI file"));
	const auto v = doubleToken(*text, NonFinite::rejected);
	if (!v) throw ConfigError(describe(key, "not a finite number"));
	return *v;
}

double ConfigSection::getDouble(const std::string& key, double dflt) const
{
	return has(key) ? getDouble(key) : dflt;
}

long ConfigSection::getInt(const std::string& key, long dflt) const
{
	const auto text = raw(key);
	if (!text) return dflt;
	const auto v = integerToken<long>(*text);
	if (!v) throw ConfigError(describe(key, "not an integer"));
	return *v;
}

bool ConfigSection::getBool(const std::string& key, bool dflt) const
{
	const auto text = raw(key);
	if (!text) return dflt;
	const auto v = parseBool(*text);
	if (!v) throw ConfigError(describe(key, "not a boolean (true/false)"));
	return *v;
}

std::string ConfigSection::getString(const std::string& key) const
{
	const auto text = raw(key);
	if (!text) throw ConfigError(describeKey(key, "missing (no default): set it in the INI file"));
	if (text->empty()) throw ConfigError(describeKey(key, "empty value"));
	return *text;
}

std::string ConfigSection::getString(const std::string& key, const std::string& dflt) const
{
	return has(key) ? getString(key) : dflt;
}

void ConfigSection::rejectUnknownKeys() const
{
	for (const auto& [key, value] : values_)
		if (!used_->count(key))
			throw ConfigError(describeKey(key, "unknown key (misspelt? `esif plugins` lists the keys)"));
}

}  // namespace esif
