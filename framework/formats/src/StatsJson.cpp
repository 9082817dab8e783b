#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/formats/StatsJson.h>

#include <nlohmann/json.hpp>

#include <climits>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace esif
{
void Stats::set(const std::string& key, StatValue value)
{
	if (auto* d = std::get_if<double>(&value); d && !std::isfinite(*d)) value = nullptr;  // JSON has no NaN
	for (auto& kv : items_)
		if (kv.first == key)
		{
			kv.second = std::move(value);
			return;
		}
	items_.emplace_back(key, std::move(value));
}

void Stats::set(const std::string& key, const std::optional<double>& value)
{
	if (value)
		set(key, StatValue(*value));
	else
		set(key, StatValue(nullptr));
}

std::optional<StatValue> Stats::get(const std::string& key) const
{
	for (const auto& kv : items_)
		if (kv.first == key) return kv.second;
	return std::nullopt;
}

std::optional<double> Stats::number(const std::string& key) const
{
	const auto v = get(key);
	if (!v) return std::nullopt;
	if (const auto* d = std::get_if<double>(&*v)) return *d;
	if (const auto* i = std::get_if<long long>(&*v)) return static_cast<double>(*i);
	return std::nullopt;
}

std::optional<std::string> Stats::text(const std::string& key) const
{
	const auto v = get(key);
	if (!v) return std::nullopt;
	if (const auto* t = std::get_if<std::string>(&*v)) return *t;
	return std::nullopt;
}

std::string statText(const StatValue& v)
{
	if (std::holds_alternative<std::nullptr_t>(v)) return "null";
	if (const auto* d = std::get_if<double>(&v)) return formatNumber(*d);
	if (const auto* i = std::get_if<long long>(&v)) return std::to_string(*i);
	return std::get<std::string>(v);
}

namespace
{
/// stats.json is a few kilobytes; anything near this is not one.
constexpr std::uintmax_t kMaxStatsBytes = 16u << 20;

using Json = nlohmann::ordered_json;  // keys stay in the order they were set

Json toJsonValue(const StatValue& v)
{
	if (const auto* d = std::get_if<double>(&v)) return *d;
	if (const auto* i = std::get_if<long long>(&v)) return *i;
	if (const auto* t = std::get_if<std::string>(&v)) return *t;
	return nullptr;
}

StatValue fromJsonValue(const Json& v, const std::string& key, const std::string& origin)
{
	if (v.is_null()) return nullptr;
	if (v.is_string()) return v.get<std::string>();
	if (v.is_number_float()) return v.get<double>();
	if (v.is_number_integer())
	{
		if (v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(LLONG_MAX))
			throw InputError(origin + ": stats JSON key '" + key + "': integer out of range");
		return v.get<long long>();
	}
	throw InputError(origin + ": stats JSON key '" + key + "': expected a number, a string or null, found " +
					 v.type_name());
}
}  // namespace

std::string Stats::toJson() const
{
	Json object = Json::object();
	for (const auto& [key, value] : items_) object[key] = toJsonValue(value);
	// Paths and labels are bytes: invalid UTF-8 becomes U+FFFD rather than
	// an exception halfway through a run's closing.
	return object.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

Stats Stats::load(const std::string& path)
{
	std::error_code ec;
	const auto size = std::filesystem::file_size(path, ec);
	if (ec) throw InputError(path + ": cannot open (" + ec.message() + ")");
	if (size > kMaxStatsBytes)
		throw InputError(path + ": " + std::to_string(size) + " bytes, more than a stats.json holds (" +
						 std::to_string(kMaxStatsBytes) + ")");
	std::ifstream in(path, std::ios::binary);
	if (!in) throw InputError(path + ": cannot open");
	std::stringstream ss;
	ss << in.rdbuf();
	return fromJson(ss.str(), path);
}

Stats Stats::fromJson(const std::string& text, const std::string& origin)
{
	Json object;
	try
	{
		object = Json::parse(text);
	}
	catch (const Json::parse_error& e)
	{
		throw InputError(origin + ": malformed stats JSON at offset " + std::to_string(e.byte) + ": " +
						 oneLineReason(e.what()));
	}
	if (!object.is_object()) throw InputError(origin + ": malformed stats JSON: expected one object");
	Stats out;
	for (const auto& [key, value] : object.items()) out.set(key, fromJsonValue(value, key, origin));
	return out;
}

}  // namespace esif
