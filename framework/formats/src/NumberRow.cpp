/// \file NumberRow.cpp
/// A line of named numeric columns; see NumberRow.h.

#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/core/InputBounds.h>
#include <esif/core/NumberToken.h>
#include <esif/core/TextInput.h>
#include "NumberRow.h"

#include <cmath>

namespace esif
{
namespace
{
/// Why a coordinate or heading beyond its bound is refused: no real one is that far.
const char* const kImplausible = " (a corrupt file or the wrong units)";
}  // namespace

NumberRow::Columns::Columns(std::vector<std::string> names, std::size_t integers)
	: count_(names.size()), integers_(integers)
{
	std::string list;
	for (const auto& n : names) list += (list.empty() ? "" : " ") + n;
	what_ = std::to_string(count_) + (count_ == 1 ? " column '" : " columns '") + list + "'";
	name_ = [names = std::move(names)](std::size_t i) { return names[i]; };
}

NumberRow::Columns::Columns(std::size_t count, std::string what, std::function<std::string(std::size_t)> name)
	: count_(count), what_(std::move(what)), name_(std::move(name))
{
}

NumberRow::NumberRow(const std::string& line, const Columns& columns, std::string where)
	: columns_(columns), where_(std::move(where)), tokens_(whitespaceTokens(line))
{
	requireCount();
	for (std::size_t i = 0; i < tokens_.size(); ++i) read(i);
}

void NumberRow::requireCount() const
{
	const std::size_t found = tokens_.size(), expected = columns_.size();
	if (found == expected) return;
	if (found == 0) throw InputError(where_ + ": empty line, expected " + columns_.what());
	throw InputError(
		where_ + ": " + (found > expected ? "extra values" : "too few values") + ": expected " + columns_.what() +
		", found " + std::to_string(found));
}

void NumberRow::read(std::size_t i)
{
	if (columns_.isInteger(i))
	{
		const auto v = integerToken<long>(tokens_[i]);
		if (!v) fail(i, "not an integer");
		integers_.push_back(*v);
		values_.push_back(static_cast<double>(*v));
		return;
	}
	const auto v = doubleToken(tokens_[i], NonFinite::accepted);
	if (!v) fail(i, "not a number");
	if (!std::isfinite(*v)) fail(i, "not a finite number");
	values_.push_back(*v);
}

double NumberRow::bounded(std::size_t i, double lo, double hi, const std::string& unit, const std::string& why) const
{
	if (values_[i] < lo || values_[i] > hi)
		fail(i, "must be in [" + formatNumber(lo) + ", " + formatNumber(hi) + "] " + unit + " (" + why + ")");
	return values_[i];
}

double NumberRow::coordinate(std::size_t i) const
{
	if (std::abs(values_[i]) > kMaxCoordinate_m)
		fail(i, "must be within +-" + formatNumber(kMaxCoordinate_m) + " m" + kImplausible);
	return values_[i];
}

double NumberRow::heading(std::size_t i) const
{
	if (std::abs(values_[i]) > kMaxHeading_rad)
		fail(i, "must be within +-" + formatNumber(kMaxHeading_rad) + " rad" + kImplausible);
	return values_[i];
}

long NumberRow::wholeNumber(std::size_t i, long lo, long hi) const
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
	// The token as written while it is not read; after, the value read.
	std::string value = "'" + tokens_[i] + "'";
	if (i < integers_.size())
		value = std::to_string(integers_[i]);
	else if (i < values_.size())
		value = formatNumber(values_[i]);
	throw InputError(
		where_ + ": column " + std::to_string(i + 1) + " (" + columns_.name(i) + ") = " + value + ": " + rule);
}

}  // namespace esif
