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

/// Rethrows the exception being handled (call it inside a catch block
/// only) as the same esif type with `from` replaced by `to` in its message,
/// e.g. a partial folder by the output the user will look for; out of
/// memory and other non-esif exceptions keep their class (exit code).
[[noreturn]] void rethrowWithPathReplaced(const std::string& from, const std::string& to);

/// How esif reports a failure: its exit code and the one line it prints.
struct FailureReport
{
	int exit_code = 4;
	std::string line;  ///< "esif: error: ...", without a newline, control characters escaped
};

/// The report of the exception being handled (call it inside a catch block
/// only): ConfigError and InputError exit 1 ("esif: error: "), a
/// filesystem_error 1 naming its path and the system's reason,
/// NumericalError 3 ("esif: numerical failure: "), std::bad_alloc 3
/// ("esif: out of memory"), anything else 4 ("esif: internal error: " and
/// one line of reason). Control characters in the line are escaped
/// (TerminalText.h). The one mapping of the exit codes of robustness.md,
/// for the command's main thread and for every worker thread alike.
FailureReport reportCurrentException();

}  // namespace esif
