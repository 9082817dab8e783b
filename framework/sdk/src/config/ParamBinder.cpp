#include <esif/config/ConfigSection.h>
#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>

#include <cstdio>

namespace esif
{
std::string formatNumber(double v)
{
	char buf[64];
	for (int precision = 6; precision <= 17; ++precision)
	{
		std::snprintf(buf, sizeof(buf), "%.*g", precision, v);
		if (std::strtod(buf, nullptr) == v) break;
	}
	return buf;
}

bool Bounds::contains(double v) const
{
	const bool above = lo_open ? v > lo : v >= lo;
	const bool below = hi_open ? v < hi : v <= hi;
	return above && below;
}

std::string Bounds::text() const
{
	const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
	if (has_lo && has_hi)
		return "must be in " + std::string(lo_open ? "(" : "[") + formatNumber(lo) + ", " + formatNumber(hi) +
			(hi_open ? ")" : "]");
	if (has_lo) return std::string("must be ") + (lo_open ? "> " : ">= ") + formatNumber(lo);
	if (has_hi) return std::string("must be ") + (hi_open ? "< " : "<= ") + formatNumber(hi);
	return "any finite number";
}

void LoadingBinder::real(const char* key, double& field, const char*, Bounds bounds)
{
	field = section_.getDouble(key, field);
	if (!bounds.contains(field)) throw ConfigError(section_.describe(key, bounds.text()));
}

void LoadingBinder::integer(const char* key, int& field, const char*, Bounds bounds)
{
	const long v = section_.getInt(key, field);
	if (!bounds.contains(static_cast<double>(v)) || v > std::numeric_limits<int>::max() ||
		v < std::numeric_limits<int>::min())
		throw ConfigError(section_.describe(key, bounds.text()));
	field = static_cast<int>(v);
}

void LoadingBinder::flag(const char* key, bool& field, const char*) { field = section_.getBool(key, field); }

void LoadingBinder::text(const char* key, std::string& field, const char*)
{
	field = section_.getString(key, field);
}

void LoadingBinder::choice(
	const char* key, std::string& field, const std::vector<std::string>& options, const char*)
{
	const std::string v = section_.getString(key, field);
	for (const auto& o : options)
		if (o == v)
		{
			field = v;
			return;
		}
	std::string list;
	for (const auto& o : options) list += (list.empty() ? "" : "|") + o;
	throw ConfigError(section_.describe(key, "must be one of " + list));
}

void DescribingBinder::real(const char* key, double& field, const char* doc, Bounds bounds)
{
	infos.push_back({key, formatNumber(field), std::string(doc) + " (" + bounds.text() + ")"});
}

void DescribingBinder::integer(const char* key, int& field, const char* doc, Bounds bounds)
{
	infos.push_back({key, std::to_string(field), std::string(doc) + " (" + bounds.text() + ")"});
}

void DescribingBinder::flag(const char* key, bool& field, const char* doc)
{
	infos.push_back({key, field ? "true" : "false", doc});
}

void DescribingBinder::text(const char* key, std::string& field, const char* doc) { infos.push_back({key, field, doc}); }

void DescribingBinder::choice(
	const char* key, std::string& field, const std::vector<std::string>& options, const char* doc)
{
	std::string list;
	for (const auto& o : options) list += (list.empty() ? "" : "|") + o;
	infos.push_back({key, field, std::string(doc) + " (" + list + ")"});
}

}  // namespace esif
