#pragma once
/// \file TerminationCleanup.h
/// What happens on SIGINT, SIGTERM and SIGHUP: the signals are blocked in
/// every thread and taken by one watcher thread (sigwait), which forwards
/// the signal to the running child runs and waits for them, removes the
/// temporary files, folders and locks registered here, and ends the process
/// with 128 + the signal number. A handler that ran inside an arbitrary
/// thread could not safely remove folders; a watcher thread can, and a
/// mutex keeps it from doing so halfway through a folder swap.

#include <functional>
#include <mutex>
#include <string>
#include <sys/types.h>

namespace esif::termination
{
/// Blocks the termination signals in the calling thread. Call first in
/// main(), before any thread starts, so that every thread inherits the mask
/// and only the watcher receives them.
void blockSignals();

/// Restores an empty signal mask: for a forked child before exec (the mask
/// survives exec).
void unblockSignals();

/// Starts the watcher thread once (later calls do nothing). Without it the
/// blocked signals would stay pending forever.
void startWatcher();

/// For a process forked without exec (a run of the run server, RunServer.h):
/// forgets the paths and children inherited from the process it was forked
/// from, and starts its own watcher (the parent's thread was not copied).
/// Signals must still be blocked, as they are when inherited.
void restartInForkedChild();

/// Registers `path` (file or folder) to be removed if a signal ends the
/// process; paths are removed in the reverse order of registration.
void addPath(const std::string& path);
/// Unregisters `path` (it was moved into place or removed already).
void removePath(const std::string& path);

/// A line saying where the work stood, written to stderr when a signal ends
/// the process (after the cleanup): "esif: esif::Slsjf stopped by signal 15
/// after 123 of 500000 steps, ...", so that a run stopped by a time limit or by the user
/// still tells how far it got. `note` is called from the watcher thread: it
/// must read only what is safe to read concurrently (atomics). Replaces any
/// earlier note; clearStopNote() before what it reads goes away.
void setStopNote(std::function<std::string(int signal)> note);
void clearStopNote();

/// A child process to forward a signal to and wait for; several may run
/// at once (esif montecarlo --jobs). It may also be a run the run server
/// forked, which is not our child. Unregister it once it has ended.
void addChild(pid_t pid);
void removeChild(pid_t pid);

/// A server process (RunServer.h) that ends once `fd`, its socket, is
/// closed: after the children have ended, the watcher closes `fd` and waits
/// for the server. Unregister it before closing `fd` yourself.
void addServer(pid_t pid, int fd);
void removeServer(pid_t pid);

/// Held over steps that must not be cut in two by the cleanup (the swap of
/// a finished folder into place): the watcher waits for it.
std::unique_lock<std::mutex> holdOff();

}  // namespace esif::termination
