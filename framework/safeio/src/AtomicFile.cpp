#include <esif/core/Errors.h>
#include <esif/safeio/AtomicFile.h>
#include "CheckedWrite.h"
#include <esif/safeio/TerminationCleanup.h>

#include <filesystem>
#include <new>
#include <system_error>
#include <unistd.h>

namespace fs = std::filesystem;

namespace esif
{
namespace
{
/// A temporary name in the same folder (so rename() is atomic), unique per
/// process; the ".tmp" suffix keeps MRPT's extension-based gz detection off.
std::string temporaryNameFor(const std::string& path)
{
	const fs::path p(path);
	return (p.parent_path() / ("." + p.filename().string() + "." + std::to_string(::getpid()) + ".tmp"))
		.string();
}

/// Removes the temporary file; never throws, so that the error that made
/// the write fail is the one reported (e.g. on a read-only file system).
void discard(const std::string& tmp)
{
	std::error_code ec;
	fs::remove(tmp, ec);
	termination::removePath(tmp);
}

void writeThenRename(const std::string& path, const std::string& tmp, const std::function<void(const std::string&)>& write)
{
	write(tmp);
	std::error_code ec;
	fs::rename(tmp, path, ec);
	if (ec) throw InputError(path + ": cannot write output: " + ec.message());
}
}  // namespace

void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write)
{
	const std::string tmp = temporaryNameFor(path);
	termination::addPath(tmp);
	try
	{
		writeThenRename(path, tmp, write);
		termination::removePath(tmp);
	}
	catch (const ConfigError&)
	{
		discard(tmp);
		throw;
	}
	catch (const InputError&)
	{
		discard(tmp);
		throw;
	}
	catch (const NumericalError&)
	{
		discard(tmp);
		throw;
	}
	catch (const std::bad_alloc&)
	{
		discard(tmp);
		throw;	// out of memory, not a file that cannot be written
	}
	catch (const std::exception& e)
	{
		discard(tmp);
		throw InputError(path + ": cannot write output: " + e.what());
	}
}

void writeBytesAtomically(const std::string& path, const std::string& bytes)
{
	writeAtomically(path, [&](const std::string& tmp) { writeBytesChecked(tmp, bytes, path); });
}

void writeTextAtomically(const std::string& path, const std::string& text) { writeBytesAtomically(path, text); }

void ensureDirectory(const std::string& dir)
{
	std::error_code ec;
	fs::create_directories(dir, ec);
	if (ec || !fs::is_directory(dir))
		throw InputError(dir + ": cannot create output folder" + (ec ? ": " + ec.message() : ""));
}

}  // namespace esif
