#pragma once
/// \file Sandbox.h
/// Runs a function in a forked child under an address-space and a CPU limit,
/// so that a fault in third-party code it calls (a null dereference inside
/// MRPT's deserialisers, an allocation sized by a corrupt count, an endless
/// loop) ends the child, not the caller, and can be reported as one line.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace esif
{
struct SandboxLimits
{
	std::size_t address_space_bytes = 0;  ///< extra address space the child may map beyond its start
	unsigned cpu_seconds = 0;			  ///< CPU time the child may use
};

/// Shared with the child: it writes where it is so the parent can say where
/// it stopped, and what it produced (a digest) so the parent can hold its
/// own result against the one the child vouched for.
struct SandboxProgress
{
	volatile std::size_t position = 0;
	volatile std::uint64_t result = 0;
};

struct SandboxOutcome
{
	enum class Kind
	{
		kSucceeded,	   ///< the function returned
		kFailed,	   ///< it threw: `message` is what()
		kOutOfMemory,  ///< an allocation failed against the address-space limit
		kCpuLimit,	   ///< it used up its CPU time
		kInterrupted,  ///< SIGINT, SIGTERM or SIGHUP ended it (the user stopped esif)
		kCrashed,	   ///< it was ended by a signal (`signal_number`) or ended itself (`message`)
	};
	Kind kind = Kind::kSucceeded;
	std::string message;
	int signal_number = 0;
	std::size_t position = 0;  ///< the last SandboxProgress::position the child wrote
	std::uint64_t result = 0;  ///< the SandboxProgress::result it wrote
	/// The address-space limit the process was started under, when it was
	/// lower than the one asked for (the child then ran under it); 0 otherwise.
	std::uint64_t address_space_cap = 0;
};

/// Calls `work(progress)` in a forked child under `limits` and waits for it.
/// The child never returns into the caller's code: it leaves with _exit, so
/// no destructor, atexit handler or stdio buffer of the parent runs twice.
/// Throws InputError only when the child cannot be started at all.
SandboxOutcome runInSandbox(const std::function<void(SandboxProgress&)>& work, const SandboxLimits& limits);

}  // namespace esif
