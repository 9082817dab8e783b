/// \file RunServer.cpp
/// The fork server and its protocol; see RunServer.h.
///
/// One SOCK_SEQPACKET socket joins esif to the server. A request is one
/// message: a byte (1 = discard stdout) and the run's arguments, each ended
/// by NUL, with two descriptors attached (SCM_RIGHTS): the write end of a
/// reply socket and the run's stderr. For each request the server forks a
/// helper, which forks the run, sends its pid on the reply socket, waits
/// for it and sends its wait status. The server reaps finished helpers as
/// requests come, and when esif closes its end it waits for the rest.

#include <esif/safeio/RunServer.h>

#include "ChildWait.h"

#include <esif/safeio/TerminationCleanup.h>

#include <array>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <iostream>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

namespace esif
{
namespace
{
/// Requests larger than this are refused by the sender: arguments are a
/// handful of paths and options.
constexpr std::size_t kMaxRequestBytes = 64 * 1024;

/// One request on the server socket: the payload and, as SCM_RIGHTS, two
/// descriptors (the reply socket and the run's stderr). Not copyable: the
/// header points into the object itself.
struct TwoFdMessage
{
	alignas(cmsghdr) std::array<char, CMSG_SPACE(2 * sizeof(int))> control{};
	iovec io{};
	msghdr header{};

	TwoFdMessage(void* payload, std::size_t size) : io{payload, size}
	{
		header.msg_iov = &io;
		header.msg_iovlen = 1;
		header.msg_control = control.data();
		header.msg_controllen = control.size();
	}
	TwoFdMessage(const TwoFdMessage&) = delete;
	TwoFdMessage& operator=(const TwoFdMessage&) = delete;
};

int& serverSocket()
{
	static int fd = -1;
	return fd;
}

/// send() without SIGPIPE, the whole buffer or false.
bool sendAll(int fd, const void* data, std::size_t size)
{
	const char* p = static_cast<const char*>(data);
	while (size > 0)
	{
		const ssize_t n = ::send(fd, p, size, MSG_NOSIGNAL);
		if (n < 0 && errno == EINTR) continue;
		if (n <= 0) return false;
		p += n;
		size -= static_cast<std::size_t>(n);
	}
	return true;
}

bool readAll(int fd, void* data, std::size_t size)
{
	char* p = static_cast<char*>(data);
	while (size > 0)
	{
		const ssize_t n = ::read(fd, p, size);
		if (n < 0 && errno == EINTR) continue;
		if (n <= 0) return false;
		p += n;
		size -= static_cast<std::size_t>(n);
	}
	return true;
}

/// The run: esif's entry point with the request's arguments, stdout and
/// stderr where the request says, and a signal watcher of its own.
[[noreturn]] void becomeRun(const std::vector<std::string>& args, bool discard_stdout, int stderr_fd, EntryPoint entry)
{
	::dup2(stderr_fd, STDERR_FILENO);
	::close(stderr_fd);
	if (discard_stdout)
	{
		const int null_fd = ::open("/dev/null", O_WRONLY);
		if (null_fd >= 0) ::dup2(null_fd, STDOUT_FILENO);
		if (null_fd > STDOUT_FILENO) ::close(null_fd);
	}
	termination::restartInForkedChild();
	std::vector<std::string> words = args;
	std::vector<char*> argv;
	for (auto& w : words) argv.push_back(w.data());
	argv.push_back(nullptr);
	// exit(), as when main() returns: static destructors run and streams flush.
	std::exit(entry(static_cast<int>(words.size()), argv.data()));
}

/// The helper: forks the run, reports its pid and then its wait status.
[[noreturn]] void becomeHelper(
	const std::vector<std::string>& args, bool discard_stdout, int reply_fd, int stderr_fd, EntryPoint entry)
{
	const pid_t run = ::fork();
	if (run == 0)
	{
		::close(reply_fd);
		becomeRun(args, discard_stdout, stderr_fd, entry);
	}
	::close(stderr_fd);
	const std::int32_t pid = run;
	if (!sendAll(reply_fd, &pid, sizeof(pid)) || run < 0) ::_exit(0);
	const std::int32_t wire_status = safeio_detail::waitForChild(run);
	sendAll(reply_fd, &wire_status, sizeof(wire_status));
	::_exit(0);
}

/// Splits a request's payload into its stdout flag and arguments; false
/// when it is malformed.
bool parseRequest(const char* data, std::size_t size, bool& discard_stdout, std::vector<std::string>& args)
{
	if (size < 2 || data[size - 1] != '\0') return false;
	discard_stdout = data[0] == 1;
	for (std::size_t start = 1; start < size;)
	{
		const std::size_t end = std::strlen(data + start) + start;
		args.emplace_back(data + start, end - start);
		start = end + 1;
	}
	return !args.empty();
}

/// Once esif has closed its end: every helper ends when its run does.
[[noreturn]] void waitForHelpersAndExit()
{
	int status = 0;
	while (::waitpid(-1, &status, 0) > 0 || errno == EINTR)
	{
	}
	::_exit(0);
}

/// The server loop: one helper per request, until esif closes its end.
[[noreturn]] void serve(int fd, EntryPoint entry)
{
	std::vector<char> payload(kMaxRequestBytes);
	for (;;)
	{
		TwoFdMessage message(payload.data(), payload.size());
		const ssize_t n = ::recvmsg(fd, &message.header, MSG_CMSG_CLOEXEC);
		if (n < 0 && errno == EINTR) continue;
		if (n <= 0) waitForHelpersAndExit();  // esif has closed its end
		int status = 0;
		while (::waitpid(-1, &status, WNOHANG) > 0)
		{
		}
		const cmsghdr* header = CMSG_FIRSTHDR(&message.header);
		if (!header || header->cmsg_type != SCM_RIGHTS || header->cmsg_len != CMSG_LEN(2 * sizeof(int))) continue;
		int fds[2];
		std::memcpy(fds, CMSG_DATA(header), sizeof(fds));
		bool discard_stdout = false;
		std::vector<std::string> args;
		if (parseRequest(payload.data(), static_cast<std::size_t>(n), discard_stdout, args) && ::fork() == 0)
		{
			::close(fd);
			becomeHelper(args, discard_stdout, fds[0], fds[1], entry);
		}
		// The reply socket closes here unless a helper holds it: esif reads
		// a failed request as a vanished server.
		::close(fds[0]);
		::close(fds[1]);
	}
}
}  // namespace

RunServer::RunServer(EntryPoint entry)
{
	if (serverSocket() >= 0) return;
	int fds[2];
	if (::socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, fds) != 0) return;
	std::cout.flush();
	std::cerr.flush();
	pid_ = ::fork();
	if (pid_ == 0)
	{
		::close(fds[0]);
		serve(fds[1], entry);
	}
	::close(fds[1]);
	if (pid_ < 0)
	{
		::close(fds[0]);
		return;
	}
	serverSocket() = fds[0];
	termination::addServer(pid_, fds[0]);
}

RunServer::~RunServer()
{
	if (pid_ <= 0) return;
	termination::removeServer(pid_);
	::close(serverSocket());
	serverSocket() = -1;
	safeio_detail::waitForChild(pid_);
}

bool runServerStarted() { return serverSocket() >= 0; }

ServedRun startServedRun(const std::vector<std::string>& args, int stderr_fd, bool discard_stdout)
{
	ServedRun run;
	std::string payload(1, discard_stdout ? '\1' : '\0');
	for (const auto& a : args) payload.append(a.c_str(), a.size() + 1);
	int reply[2];
	if (serverSocket() < 0 || payload.size() > kMaxRequestBytes ||
		::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, reply) != 0)
		return run;
	TwoFdMessage message(payload.data(), payload.size());
	cmsghdr* header = CMSG_FIRSTHDR(&message.header);
	header->cmsg_level = SOL_SOCKET;
	header->cmsg_type = SCM_RIGHTS;
	header->cmsg_len = CMSG_LEN(2 * sizeof(int));
	const int passed[2] = {reply[1], stderr_fd};
	std::memcpy(CMSG_DATA(header), passed, sizeof(passed));
	ssize_t sent;
	while ((sent = ::sendmsg(serverSocket(), &message.header, MSG_NOSIGNAL)) < 0 && errno == EINTR)
	{
	}
	::close(reply[1]);
	std::int32_t pid = -1;
	if (sent != static_cast<ssize_t>(payload.size()) || !readAll(reply[0], &pid, sizeof(pid)) || pid <= 0)
	{
		::close(reply[0]);
		return run;
	}
	run.pid = pid;
	run.reply_fd = reply[0];
	return run;
}

int waitServedRun(ServedRun& run)
{
	std::int32_t status = 0;
	const bool reported = readAll(run.reply_fd, &status, sizeof(status));
	::close(run.reply_fd);
	run.reply_fd = -1;
	return reported ? status : SIGKILL;	 // a wait status with WIFSIGNALED, WTERMSIG == SIGKILL
}

}  // namespace esif
