#pragma once
/// \file NumberToken.h
/// The one reader of a number written as text, for every file and config
/// esif reads. A token is a number only when it is one whole ("12abc", " 12"
/// and "" are not), read with std::from_chars: locale-independent like the
/// writers' std::to_chars, and, unlike strtod, without a leading '+' or
/// hexadecimal ("0x1p3"), which no esif writer and no data set writes.

#include <charconv>
#include <optional>
#include <string_view>
#include <system_error>
#include <type_traits>

namespace esif
{
/// Whether a token may read as NaN or an infinity ("nan", "inf", or a
/// number beyond a double's range): run outputs of a diverged filter hold
/// them; configs and input data must not.
enum class NonFinite
{
	rejected,
	accepted
};

/// `token` as an integer T: decimal digits after an optional '-'; nullopt
/// when anything else is in it ("7.0", "1e3", "+7") or T cannot hold it.
template <class T>
std::optional<T> integerToken(std::string_view token)
{
	static_assert(std::is_integral_v<T>, "doubleToken reads real numbers");
	T v{};
	const auto r = std::from_chars(token.data(), token.data() + token.size(), v);
	if (r.ec != std::errc() || r.ptr != token.data() + token.size()) return std::nullopt;
	return v;
}

/// `token` as the nearest double: a number beyond a double's range reads
/// as an infinity and one below its smallest subnormal as zero, as the C
/// library rounds them. nullopt when the token is not a number, or when it
/// reads as NaN or an infinity and `non_finite` is NonFinite::rejected.
std::optional<double> doubleToken(std::string_view token, NonFinite non_finite);

}  // namespace esif
