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

}  // namespace esif
