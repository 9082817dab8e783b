/// \file NumberRow.cpp
/// A line of named numeric columns; see NumberRow.h.

#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/core/InputBounds.h>
#include <esif/core/TextInput.h>
#include "NumberRow.h"

#include <cmath>
#include <cstdlib>

namespace esif
{
NumberRow::NumberRow(const std::string& line, const std::vector<const char*>& names, std::string where)
	: names_(names), where_(std::move(where))
{
	tokens_ = whitespaceTokens(line);
	if (tokens_.size() != names.size())
	{
		std::string list;
		for (const char* n : names) list += (list.empty() ? "" : " ") + std::string(n);
		throw InputError(
			where_ + ": expected " + std::to_string(names.size()) + " columns '" + list + "', found " +
			std::to_string(tokens_.size()));
	}
	for (std::size_t i = 0; i < tokens_.size(); ++i)
	{
		char* end = nullptr;
		const double v = std::strtod(tokens_[i].c_str(), &end);
		if (end == tokens_[i].c_str() || *end != '\0') fail(i, "not a number");
		if (!std::isfinite(v)) fail(i, "not a finite number");
		values_.push_back(v);
	}
}

double NumberRow::bounded(std::size_t i, double lo, double hi, const std::string& unit, const std::string& why) const
{
	if (values_[i] < lo || values_[i] > hi)
		fail(i, "must be in [" + formatNumber(lo) + ", " + formatNumber(hi) + "] " + unit + " (" + why + ")");
	return values_[i];
}

double NumberRow::coordinate(std::size_t i) const
{
	if (std::abs(values_[i]) > kMaxCoordinate_m) fail(i, "must be within +-" + formatNumber(kMaxCoordinate_m) + " m");
	return values_[i];
}

double NumberRow::heading(std::size_t i) const
{
	if (std::abs(values_[i]) > kMaxHeading_rad) fail(i, "must be within +-" + formatNumber(kMaxHeading_rad) + " rad");
	return values_[i];
}

long NumberRow::integer(std::size_t i, long lo, long hi) const
{
	const double v = values_[i];
	if (v != std::floor(v)) fail(i, "must be a whole number");
	if (v < static_cast<double>(lo) || v > static_cast<double>(hi))
		fail(i, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
	return static_cast<long>(v);
}

LandmarkId NumberRow::landmarkId(std::size_t i) const
{
	const double v = values_[i];
	if (v != std::floor(v)) fail(i, "a landmark ID must be an integer, not fractional");
	if (v < 0 || v > static_cast<double>(kMaxLandmarkId))
		fail(i, "a landmark ID must be in [0, " + std::to_string(kMaxLandmarkId) + "]");
	return static_cast<LandmarkId>(v);
}

void NumberRow::fail(std::size_t i, const std::string& rule) const
{
	// The value as read while it is not a finite number; as parsed after.
	const std::string value = i < values_.size() ? formatNumber(values_[i]) : "'" + tokens_[i] + "'";
	throw InputError(where_ + ": column " + std::to_string(i + 1) + " (" + names_[i] + ") = " + value + ": " + rule);
}

}  // namespace esif
