#pragma once
/// \file StatsJson.h
/// The flat key/value record of one run (stats.json): numbers, strings and
/// nulls in a fixed key order. Flat on purpose: comparison.csv has the same
/// keys as columns. Written and read with nlohmann/json (Debian's
/// nlohmann-json3-dev), in the order the keys were set.

#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace esif
{
using StatValue = std::variant<std::nullptr_t, double, long long, std::string>;

class Stats
{
   public:
	void set(const std::string& key, StatValue value);
	void set(const std::string& key, const std::optional<double>& value);
	std::optional<StatValue> get(const std::string& key) const;
	/// The value as a number, nullopt for null, strings or missing keys.
	std::optional<double> number(const std::string& key) const;
	/// The value as a string, nullopt for numbers, null or missing keys.
	std::optional<std::string> text(const std::string& key) const;
	const std::vector<std::pair<std::string, StatValue>>& items() const { return items_; }

	std::string toJson() const;
	/// Parses one JSON object of numbers, strings and nulls (what toJson()
	/// writes); throws InputError naming `origin` otherwise.
	static Stats fromJson(const std::string& text, const std::string& origin);
	/// Reads and parses a stats.json file; throws InputError naming `path`.
	static Stats load(const std::string& path);

   private:
	std::vector<std::pair<std::string, StatValue>> items_;
};

/// Text of a value for tables and CSV ("null" -> empty for CSV is the caller's choice).
std::string statText(const StatValue& v);

}  // namespace esif
