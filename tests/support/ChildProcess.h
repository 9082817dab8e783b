#pragma once
/// \file ChildProcess.h
/// Runs the esif binary as a child the test controls: optional resource
/// limits before exec, its pid to signal, and its merged output. popen()
/// (EsifTestSupport.h) gives neither the pid nor a way to set limits.

#include <gtest/gtest.h>

#include <cerrno>
#include <csignal>
#include <optional>
#include <string>
#include <vector>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace esif::test
{
struct Spawned
{
	pid_t pid = -1;
	int output_fd = -1;	 ///< stdout and stderr of the child
};

/// Resource limits for a spawned esif.
struct SpawnLimits
{
	/// RLIMIT_FSIZE, with SIGXFSZ ignored: a write beyond it fails with EFBIG,
	/// as on a full disk, instead of killing the process.
	std::optional<rlim_t> file_size;
	/// RLIMIT_AS: an allocation beyond it fails (std::bad_alloc).
	std::optional<rlim_t> address_space;
	/// RLIMIT_NOFILE: no descriptor beyond it (pipes and locks fail).
	std::optional<rlim_t> open_files;
};

/// Starts `esif ARGS...` under `limits`.
inline Spawned spawnEsif(const std::vector<std::string>& args, const SpawnLimits& limits)
{
	std::vector<std::string> all = {ESIF_BINARY};
	all.insert(all.end(), args.begin(), args.end());
	std::vector<char*> argv;
	for (auto& a : all) argv.push_back(a.data());
	argv.push_back(nullptr);
	int fds[2];
	if (::pipe(fds) != 0) return {};
	const pid_t pid = ::fork();
	if (pid == 0)
	{
		::dup2(fds[1], STDOUT_FILENO);
		::dup2(fds[1], STDERR_FILENO);
		::close(fds[0]);
		::close(fds[1]);
		if (limits.file_size) ::signal(SIGXFSZ, SIG_IGN);	// kept across exec
		for (const auto& [resource, value] : {std::pair{RLIMIT_FSIZE, limits.file_size},
											  std::pair{RLIMIT_AS, limits.address_space},
											  std::pair{RLIMIT_NOFILE, limits.open_files}})
			if (value)
			{
				const rlimit limit{*value, *value};
				::setrlimit(resource, &limit);
			}
		::execv(argv[0], argv.data());
		::_exit(127);
	}
	::close(fds[1]);
	return {pid, fds[0]};
}

/// Starts `esif ARGS...`; with `file_size_limit`, as SpawnLimits::file_size.
inline Spawned spawnEsif(const std::vector<std::string>& args, std::optional<rlim_t> file_size_limit = std::nullopt)
{
	return spawnEsif(args, SpawnLimits{file_size_limit, std::nullopt, std::nullopt});
}

/// Output until the child closes it, then its exit code (128 + N when
/// killed by signal N, as a shell reports it).
inline std::pair<int, std::string> finish(const Spawned& child)
{
	std::string out;
	char buf[4096];
	for (ssize_t n; (n = ::read(child.output_fd, buf, sizeof(buf))) != 0;)
	{
		if (n < 0 && errno == EINTR) continue;
		if (n < 0) break;
		out.append(buf, static_cast<std::size_t>(n));
	}
	::close(child.output_fd);
	int status = 0;
	while (::waitpid(child.pid, &status, 0) < 0 && errno == EINTR)
	{
	}
	return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), out};
}

}  // namespace esif::test
