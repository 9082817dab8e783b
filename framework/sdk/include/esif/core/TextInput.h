#pragma once
/// \file TextInput.h
/// Every text file esif reads (configs, ground truth, local maps, g2o,
/// associations, run outputs, datasets) is opened and split into lines
/// here, so the same rules hold for all of them: only a regular file is read
/// (a folder, a device such as /dev/zero, a FIFO, a dangling link or a loop
/// of links is one InputError naming the path, never a silent empty input or
/// a filesystem_error), a line is at most kMaxTextLineBytes long and holds
/// no NUL byte (an error naming file:line), so no input grows the process
/// beyond a bounded multiple of its own size.

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace esif
{
/// Longest line of any esif text input: 1 MiB. The longest legitimate line
/// is a row of a local map's information matrix, about 25 bytes per entry
/// (a state of 40,000 dimensions would fill it; the authors' maps have 75).
inline constexpr std::size_t kMaxTextLineBytes = std::size_t{1} << 20;

/// Whether anything is at `path`, a dangling or looping symbolic link
/// included (it is then an error to read, not an absent optional input).
bool pathPresent(const std::string& path);

/// Throws InputError "PATH: <what> ..." unless `path` is a regular file
/// (links followed): not found, a folder, a device or FIFO, a dangling link
/// or a loop of links each have their own message. Returns its size.
std::uintmax_t requireRegularFile(const std::string& path, const std::string& what);

/// The blank-separated tokens of `line` (spaces, tabs, a trailing '\r').
std::vector<std::string> whitespaceTokens(const std::string& line);

/// A text file read line by line under the rules above. Lines are returned
/// without their '\n' (a '\r' before it stays: callers that split on blanks
/// treat it as one).
class TextLineReader
{
   public:
	/// Opens `path`; `what` says what it should be ("ground-truth landmarks").
	TextLineReader(std::string path, const std::string& what);

	/// The next line into `line`; false at the end of the file.
	bool next(std::string& line);

	const std::string& path() const { return path_; }
	/// Number (1-based) of the line `next` returned last.
	std::size_t lineNumber() const { return line_number_; }
	/// "PATH:LINE" of that line, for messages.
	std::string where() const;
	/// Throws InputError "PATH:LINE: problem".
	[[noreturn]] void fail(const std::string& problem) const;

   private:
	bool fill();

	std::string path_;
	std::ifstream in_;
	std::string buffer_;
	std::size_t begin_ = 0;	 // start of the unread part of buffer_
	std::size_t line_number_ = 0;
	bool at_end_ = false;
};

/// The whole of a text file under the same rules (for INI files).
std::string readTextFile(const std::string& path, const std::string& what);

}  // namespace esif
