/// \file GnuplotProcess.cpp
/// See GnuplotProcess.h. The script goes in, the figures and gnuplot's
/// messages come back through memory files rather than pipes or files of
/// gnuplot's own: nothing can block on a full pipe, a gnuplot that dies
/// early cannot raise SIGPIPE in esif, and a full disk is met by esif's
/// checked writes, not by a renderer that may not notice.

#include "GnuplotProcess.h"

#include <esif/core/Errors.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace esif::plot
{
namespace
{
/// At most this much of gnuplot's stderr is read back for the error line.
constexpr std::size_t kMaxMessageBytes = 4096;
/// A figure larger than this is not a figure we asked for.
constexpr off_t kMaxFigureBytes = off_t(512) << 20;
/// gnuplot's output i is its descriptor kFirstOutputFd + i.
constexpr int kFirstOutputFd = 3;

/// Closes a descriptor when it goes out of scope.
struct Fd
{
	int fd = -1;
	Fd() = default;
	explicit Fd(int f) : fd(f) {}
	Fd(Fd&& o) noexcept : fd(o.fd) { o.fd = -1; }
	Fd(const Fd&) = delete;
	~Fd()
	{
		if (fd >= 0) ::close(fd);
	}
};

[[noreturn]] void fail(const std::string& path, const std::string& what)
{
	throw InputError(path + ": cannot run gnuplot: " + what + ": " + std::strerror(errno));
}

/// A close-on-exec memory file numbered above the descriptors gnuplot's
/// outputs are moved to, so that moving one cannot overwrite another.
Fd memoryFile(const char* name, const std::string& path)
{
	Fd raw(::memfd_create(name, MFD_CLOEXEC));
	if (raw.fd < 0) fail(path, "memfd_create");
	Fd high(::fcntl(raw.fd, F_DUPFD_CLOEXEC, 16));
	if (high.fd < 0) fail(path, "fcntl");
	return high;
}

void writeAll(int fd, const std::string& bytes, const std::string& path)
{
	std::size_t done = 0;
	while (done < bytes.size())
	{
		const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
		if (n < 0 && errno == EINTR) continue;
		if (n <= 0) fail(path, "writing its script");
		done += static_cast<std::size_t>(n);
	}
	if (::lseek(fd, 0, SEEK_SET) != 0) fail(path, "lseek");
}

std::string readAll(int fd, off_t limit, const std::string& path)
{
	struct stat st{};
	if (::fstat(fd, &st) != 0) fail(path, "fstat");
	const off_t size = std::min(st.st_size, limit);
	std::string bytes(static_cast<std::size_t>(size), '\0');
	std::size_t done = 0;
	while (done < bytes.size())
	{
		const ssize_t n = ::pread(fd, bytes.data() + done, bytes.size() - done, static_cast<off_t>(done));
		if (n < 0 && errno == EINTR) continue;
		if (n <= 0) break;
		done += static_cast<std::size_t>(n);
	}
	bytes.resize(done);
	return bytes;
}

/// The line of gnuplot's stderr that says what went wrong (gnuplot echoes
/// the failing command first, then "line N: <message>").
std::string errorLine(const std::string& text)
{
	std::string fallback;
	std::size_t start = 0;
	while (start < text.size())
	{
		std::size_t end = text.find('\n', start);
		if (end == std::string::npos) end = text.size();
		std::string line = text.substr(start, end - start);
		const std::size_t first = line.find_first_not_of(" \t^");
		line = first == std::string::npos ? "" : line.substr(first);
		if (line.rfind("line ", 0) == 0 || line.find("rror") != std::string::npos) return line;
		if (!line.empty() && fallback.empty()) fallback = line;
		start = end + 1;
	}
	return fallback.empty() ? "no message" : fallback;
}

pid_t spawnGnuplot(int script_fd, int message_fd, const std::vector<Fd>& outputs, const std::string& path)
{
	posix_spawn_file_actions_t actions;
	posix_spawn_file_actions_init(&actions);
	posix_spawn_file_actions_adddup2(&actions, script_fd, STDIN_FILENO);
	posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
	posix_spawn_file_actions_adddup2(&actions, message_fd, STDERR_FILENO);
	for (std::size_t i = 0; i < outputs.size(); ++i)
		posix_spawn_file_actions_adddup2(&actions, outputs[i].fd, kFirstOutputFd + static_cast<int>(i));
	char program[] = "gnuplot";
	char defaults[] = "-d";
	char* argv[] = {program, defaults, nullptr};
	pid_t pid = -1;
	const int rc = ::posix_spawnp(&pid, program, &actions, nullptr, argv, environ);
	posix_spawn_file_actions_destroy(&actions);
	if (rc == ENOENT)
		throw InputError(path + ": gnuplot not found on PATH: it draws esif's figures (Debian: apt-get install gnuplot-nox)");
	if (rc != 0) throw InputError(path + ": cannot start gnuplot: " + std::strerror(rc));
	return pid;
}

int waitFor(pid_t pid)
{
	int status = 0;
	while (::waitpid(pid, &status, 0) < 0)
		if (errno != EINTR) return -1;
	return status;
}
}  // namespace

std::string gnuplotOutput(int index) { return "/dev/fd/" + std::to_string(kFirstOutputFd + index); }

std::vector<std::string> runGnuplot(const std::string& script, int outputs, const std::string& figure_path)
{
	Fd script_fd = memoryFile("esif-gnuplot-script", figure_path);
	Fd message_fd = memoryFile("esif-gnuplot-messages", figure_path);
	std::vector<Fd> output_fds;
	for (int i = 0; i < outputs; ++i) output_fds.push_back(memoryFile("esif-gnuplot-figure", figure_path));
	writeAll(script_fd.fd, script, figure_path);
	const int status = waitFor(spawnGnuplot(script_fd.fd, message_fd.fd, output_fds, figure_path));
	if (status < 0) fail(figure_path, "waiting for it");
	if (WIFSIGNALED(status))
		throw InputError(figure_path + ": gnuplot was killed by signal " + std::to_string(WTERMSIG(status)));
	if (WEXITSTATUS(status) != 0)
		throw InputError(figure_path + ": gnuplot failed: " + errorLine(readAll(message_fd.fd, kMaxMessageBytes, figure_path)));
	std::vector<std::string> files;
	for (const Fd& fd : output_fds)
	{
		files.push_back(readAll(fd.fd, kMaxFigureBytes, figure_path));
		if (files.back().empty()) throw InputError(figure_path + ": gnuplot wrote nothing");
	}
	return files;
}

}  // namespace esif::plot
