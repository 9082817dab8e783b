/// \file FileSetRecord.cpp
/// Stamps and the record's text; see FileSetRecord.h.

#include "FileSetRecord.h"

#include <esif/safeio/FileSet.h>

#include <esif/core/Errors.h>
#include <esif/core/Text.h>
#include <esif/core/TextInput.h>

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace esif
{
namespace
{
const char* const kRecordHeader = "esif output files";

/// Closes a descriptor when it goes out of scope.
struct Descriptor
{
	int fd;
	~Descriptor()
	{
		if (fd >= 0) ::close(fd);
	}
};

std::string entryLine(const char* tag, const RecordEntry& e)
{
	char stamp[64];
	std::snprintf(stamp, sizeof(stamp), " %ju %08x ", e.stamp.size, static_cast<unsigned>(e.stamp.crc));
	return tag + std::string(stamp) + e.name + "\n";
}

/// "file SIZE CRC NAME" / "removed SIZE CRC NAME" into an entry.
RecordEntry parseEntry(const std::string& rest, const TextLineReader& in)
{
	RecordEntry e;
	unsigned crc = 0;
	int consumed = 0;
	if (std::sscanf(rest.c_str(), "%ju %8x %n", &e.stamp.size, &crc, &consumed) != 2 || consumed <= 0)
		in.fail("expected 'SIZE CRC NAME'");
	e.stamp.crc = crc;
	e.name = rest.substr(static_cast<std::size_t>(consumed));
	if (!isRecordableName(e.name)) in.fail("'" + printableToken(e.name) + "' is not a file name of this folder");
	return e;
}
}  // namespace

std::optional<FileStamp> stampOf(const std::filesystem::path& path)
{
	// O_NOFOLLOW: a link is not the file esif wrote; O_NONBLOCK: a FIFO
	// opens at once (and is then refused as not regular).
	const Descriptor file{::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC)};
	if (file.fd < 0) return std::nullopt;
	struct stat st{};
	if (::fstat(file.fd, &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
	FileStamp stamp;
	uLong crc = ::crc32(0L, Z_NULL, 0);
	char buffer[1 << 16];
	for (ssize_t n; (n = ::read(file.fd, buffer, sizeof(buffer))) != 0;)
	{
		if (n < 0 && errno == EINTR) continue;
		if (n < 0) throw InputError(path.string() + ": cannot read: " + std::strerror(errno));
		crc = ::crc32(crc, reinterpret_cast<const Bytef*>(buffer), static_cast<uInt>(n));
		stamp.size += static_cast<std::uintmax_t>(n);
	}
	stamp.crc = static_cast<std::uint32_t>(crc);
	return stamp;
}

bool isRecordableName(const std::string& name)
{
	return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos &&
		   !holdsControlCharacter(name);
}

const RecordEntry* FileSetRecord::file(const std::string& name) const
{
	const auto it = std::find_if(files.begin(), files.end(), [&](const RecordEntry& e) { return e.name == name; });
	return it == files.end() ? nullptr : &*it;
}

std::string FileSetRecord::text() const
{
	std::string out = std::string(kRecordHeader) +
					  "\n# what esif wrote here: a later esif replaces these files only while each is as listed\n";
	out += "kind " + kind + "\n";
	out += committing_from.empty() ? "state complete\n" : "state committing " + committing_from + "\n";
	for (const auto& e : files) out += entryLine("file", e);
	for (const auto& e : removed) out += entryLine("removed", e);
	return out;
}

std::optional<FileSetRecord> FileSetRecord::read(const std::filesystem::path& path)
{
	if (!pathPresent(path.string())) return std::nullopt;
	TextLineReader in(path.string(), "esif record of output files");
	FileSetRecord record;
	std::string line;
	if (!in.next(line) || line != kRecordHeader) in.fail("not a record of esif output files");
	bool stated = false;
	while (in.next(line))
	{
		if (line.empty() || line[0] == '#') continue;
		const auto space = line.find(' ');
		const std::string tag = line.substr(0, space), rest = space == std::string::npos ? "" : line.substr(space + 1);
		if (tag == "kind")
			record.kind = rest;
		else if (tag == "state" && rest == "complete")
			stated = true;
		else if (tag == "state" && rest.rfind("committing ", 0) == 0)
		{
			record.committing_from = rest.substr(11);
			if (!isRecordableName(record.committing_from)) in.fail("not a partial folder of this folder");
			stated = true;
		}
		else if (tag == "file")
			record.files.push_back(parseEntry(rest, in));
		else if (tag == "removed")
			record.removed.push_back(parseEntry(rest, in));
		else
			in.fail("unexpected line '" + printableToken(line) + "'");
	}
	if (record.kind.empty() || !stated) in.fail("the record has no kind or no state");
	return record;
}

std::filesystem::path fileSetRecordOf(const std::filesystem::path& first)
{
	const auto folder = first.parent_path().empty() ? std::filesystem::path(".") : first.parent_path();
	return folder / ("." + first.filename().string() + ".esif-files");
}

void requireCompleteFileSet(const std::string& file)
{
	const std::filesystem::path first = std::filesystem::path(file).lexically_normal();
	std::optional<FileSetRecord> record;
	try
	{
		record = FileSetRecord::read(fileSetRecordOf(first));
	}
	catch (const InputError&)
	{
		return;	 // not a record this reader can judge: the file is read as any other
	}
	if (!record || record->committing_from.empty()) return;
	std::string others;
	for (const auto& e : record->files)
		if (e.name != first.filename().string()) others += (others.empty() ? "" : ", ") + e.name;
	throw InputError(
		file + ": esif was stopped while replacing it" + (others.empty() ? "" : " and " + others) +
		", so they may not belong together: run the command that wrote " + first.filename().string() + " again");
}

}  // namespace esif
