/// \file TextInput.cpp
/// Checked opening and bounded line splitting of text inputs; see TextInput.h.

#include <esif/core/Errors.h>
#include <esif/core/TextInput.h>

#include <cerrno>
#include <cstring>
#include <sstream>
#include <sys/stat.h>

namespace esif
{
namespace
{
constexpr std::size_t kChunkBytes = std::size_t{64} << 10;

/// Why `path` cannot be stat()ed, in words a user acts on.
std::string statProblem(const std::string& path, int err)
{
	if (err == ENOENT)
	{
		struct stat link{};
		return ::lstat(path.c_str(), &link) == 0 ? "is a dangling symbolic link" : "not found";
	}
	if (err == ELOOP) return "is a loop of symbolic links";
	return std::string("cannot be read: ") + std::strerror(err);
}

/// Throws at the first NUL byte of `line` (line `number` of `path`).
void checkNoNul(const std::string& line, const std::string& path, std::size_t number)
{
	if (const auto at = line.find('\0'); at != std::string::npos)
		throw InputError(
			path + ":" + std::to_string(number) + ": a NUL byte at column " + std::to_string(at + 1) +
			" (not a text file)");
}

[[noreturn]] void failLongLine(const std::string& path, std::size_t number)
{
	throw InputError(
		path + ":" + std::to_string(number) + ": line longer than " + std::to_string(kMaxTextLineBytes) +
		" bytes (not a text file of this kind)");
}
}  // namespace

bool pathPresent(const std::string& path)
{
	struct stat link{};
	return ::lstat(path.c_str(), &link) == 0;
}

std::uintmax_t requireRegularFile(const std::string& path, const std::string& what)
{
	struct stat st{};
	if (::stat(path.c_str(), &st) != 0) throw InputError(path + ": " + what + " " + statProblem(path, errno));
	if (S_ISDIR(st.st_mode)) throw InputError(path + ": " + what + " is a folder, not a file");
	if (!S_ISREG(st.st_mode))
		throw InputError(path + ": " + what + " is not a regular file (a device, FIFO or socket is not read)");
	return static_cast<std::uintmax_t>(st.st_size);
}

TextLineReader::TextLineReader(std::string path, const std::string& what) : path_(std::move(path))
{
	requireRegularFile(path_, what);
	in_.open(path_, std::ios::binary);
	if (!in_) throw InputError(path_ + ": cannot open " + what + ": " + std::strerror(errno));
}

bool TextLineReader::fill()
{
	if (at_end_) return false;
	buffer_.erase(0, begin_);
	begin_ = 0;
	const std::size_t before = buffer_.size();
	buffer_.resize(before + kChunkBytes);
	in_.read(&buffer_[before], static_cast<std::streamsize>(kChunkBytes));
	const auto got = static_cast<std::size_t>(in_.gcount());
	buffer_.resize(before + got);
	if (in_.bad()) throw InputError(path_ + ": read error: " + std::strerror(errno));
	if (got < kChunkBytes) at_end_ = true;
	return got > 0;
}

bool TextLineReader::next(std::string& line)
{
	for (std::size_t searched = begin_;;)
	{
		const auto newline = buffer_.find('\n', searched);
		if (newline != std::string::npos)
		{
			if (newline - begin_ > kMaxTextLineBytes) failLongLine(path_, line_number_ + 1);
			line.assign(buffer_, begin_, newline - begin_);
			begin_ = newline + 1;
			break;
		}
		if (buffer_.size() - begin_ > kMaxTextLineBytes) failLongLine(path_, line_number_ + 1);
		searched = buffer_.size() - begin_;	 // relative: fill() moves the unread part to the front
		if (!fill())
		{
			if (begin_ == buffer_.size()) return false;
			line.assign(buffer_, begin_, std::string::npos);  // a last line without '\n'
			begin_ = buffer_.size();
			break;
		}
	}
	++line_number_;
	checkNoNul(line, path_, line_number_);
	return true;
}

std::string TextLineReader::where() const { return path_ + ":" + std::to_string(line_number_); }

void TextLineReader::fail(const std::string& problem) const { throw InputError(where() + ": " + problem); }

std::string readTextFile(const std::string& path, const std::string& what)
{
	TextLineReader reader(path, what);
	std::string text, line;
	while (reader.next(line)) text.append(line).push_back('\n');
	return text;
}

std::vector<std::string> whitespaceTokens(const std::string& line)
{
	std::vector<std::string> out;
	std::istringstream ss(line);
	for (std::string tok; ss >> tok;) out.push_back(tok);
	return out;
}

}  // namespace esif
