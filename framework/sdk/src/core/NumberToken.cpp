/// \file NumberToken.cpp
/// Strict number tokens; see NumberToken.h.

#include <esif/core/NumberToken.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace esif
{
namespace
{
/// Whether `token`, which std::from_chars read whole but found beyond a
/// double's range, lies above that range (else below it, towards zero).
/// from_chars tells neither, but the decimal exponent of the first
/// significant digit does: it is above 307 or below -323, never near 0.
bool aboveRange(std::string_view token)
{
	const std::size_t e = token.find_first_of("eE");
	std::string_view mantissa = token.substr(0, e);
	if (mantissa.front() == '-') mantissa.remove_prefix(1);
	const std::size_t point = std::min(mantissa.find('.'), mantissa.size());
	const std::size_t first = mantissa.find_first_of("123456789");	// there is one: zero is in range
	// Digits from the first significant one to the point, or minus the
	// zeros between the point and it: the exponent of that digit, plus one.
	const auto magnitude =
		first < point ? static_cast<long long>(point - first) : -static_cast<long long>(first - point - 1);
	if (e == std::string_view::npos) return magnitude > 0;
	std::string_view exponent = token.substr(e + 1);
	if (exponent.front() == '+') exponent.remove_prefix(1);
	// An exponent beyond a long long outweighs any mantissa a line can hold.
	const auto power = integerToken<long long>(exponent);
	if (!power) return exponent.front() != '-';
	return *power > -magnitude;
}
}  // namespace

std::optional<double> doubleToken(std::string_view token, NonFinite non_finite)
{
	const char* const end = token.data() + token.size();
	double v = 0;
	const auto r = std::from_chars(token.data(), end, v);
	if (r.ptr != end || (r.ec != std::errc() && r.ec != std::errc::result_out_of_range)) return std::nullopt;
	if (r.ec == std::errc::result_out_of_range)
	{
		const double magnitude = aboveRange(token) ? std::numeric_limits<double>::infinity() : 0.0;
		v = token.front() == '-' ? -magnitude : magnitude;
	}
	if (non_finite == NonFinite::rejected && !std::isfinite(v)) return std::nullopt;
	return v;
}

}  // namespace esif
