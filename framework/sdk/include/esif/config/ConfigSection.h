#pragma once
/// \file ConfigSection.h
/// One INI section with strict typed access: a value must be consumed whole
/// ("12abc" is not 12), and keys nobody asked for are reported as unknown.

#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace esif
{
class ConfigSection
{
   public:
	ConfigSection(std::string origin, std::string name, std::map<std::string, std::string> values);

	const std::string& name() const { return name_; }
	bool has(const std::string& key) const;

	/// Raw text of `key`, marking it as used; nullopt when absent.
	std::optional<std::string> raw(const std::string& key) const;

	double getDouble(const std::string& key) const;	 ///< required
	double getDouble(const std::string& key, double dflt) const;
	long getInt(const std::string& key, long dflt) const;
	bool getBool(const std::string& key, bool dflt) const;
	std::string getString(const std::string& key) const;  ///< required
	std::string getString(const std::string& key, const std::string& dflt) const;

	/// Throws ConfigError naming the first key that was never read.
	void rejectUnknownKeys() const;

	/// "file: [section] key = value: problem", the one-line error format.
	std::string describe(const std::string& key, const std::string& problem) const;
	/// "file: [section] key: problem" for a key without a value.
	std::string describeKey(const std::string& key, const std::string& problem) const;

   private:
	std::string origin_;
	std::string name_;
	std::map<std::string, std::string> values_;
	std::shared_ptr<std::set<std::string>> used_;  // shared: copies see the same usage
};

/// `text` as a boolean: true/1/yes/on or false/0/no/off, in any case.
std::optional<bool> parseBool(const std::string& text);

}  // namespace esif
