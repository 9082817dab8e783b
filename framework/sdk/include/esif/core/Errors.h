#pragma once
/// \file Errors.h
/// The three kinds of failure esif reports. Each carries one line of text that
/// names the file, INI key or step at fault, so the host can print it as is.

#include <stdexcept>
#include <string>

namespace esif
{
/// A configuration file, section, key or value is missing or invalid.
class ConfigError : public std::runtime_error
{
   public:
	using std::runtime_error::runtime_error;
};

/// An input file (rawlog, ground truth) is missing, unreadable or malformed.
class InputError : public std::runtime_error
{
   public:
	using std::runtime_error::runtime_error;
};

/// An estimator met a numerical failure (non-positive-definite covariance,
/// non-finite value) at a given step.
class NumericalError : public std::runtime_error
{
   public:
	using std::runtime_error::runtime_error;
};

/// One line of reason from any exception text: MRPT frames its messages with
/// a "==== MRPT exception ====" banner and a "Message:" label and appends a
/// stack trace, which would break esif's one-line error promise.
std::string oneLineReason(const std::string& exception_text);

/// An untrusted token (a command-line word) as a message may show it:
/// printable ASCII kept, any other byte as \xNN, cut after `max_chars`
/// characters with "...".
std::string printableToken(const std::string& token, std::size_t max_chars = 80);

/// `text` with its control characters (bytes below 0x20, and 0x7f) as \xNN,
/// so an error stays one line on a terminal whatever a path holds; other
/// bytes (UTF-8 names) are kept.
std::string withoutControlCharacters(const std::string& text);

}  // namespace esif
