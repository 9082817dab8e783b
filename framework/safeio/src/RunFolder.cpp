/// \file RunFolder.cpp
/// The all-or-nothing output folder; see RunFolder.h.

#include <esif/core/Errors.h>
#include <esif/core/TextInput.h>
#include "CheckedWrite.h"
#include <esif/safeio/RunFolder.h>
#include <esif/safeio/TerminationCleanup.h>

#include <algorithm>
#include <cctype>
#include <set>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <iostream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace esif
{
namespace
{
/// First line of the marker; the lines after it list what esif wrote.
const char* const kMarkerHeader = "esif output folder";

/// The folder holding `path` ("." for a bare name).
fs::path parentOf(const fs::path& path) { return path.parent_path().empty() ? fs::path(".") : path.parent_path(); }

/// `dir` without a trailing separator, a symbolic link resolved (the link's
/// target is what the user means to replace), its parent created.
fs::path preparedTarget(const std::string& dir)
{
	fs::path p = fs::path(dir).lexically_normal();
	if (!p.has_filename()) p = p.parent_path();
	if (p.empty() || p.filename() == "." || p.filename() == "..")
		throw InputError(dir + ": name an output folder, not the current or parent folder");
	std::error_code ec;
	if (fs::is_symlink(fs::symlink_status(p, ec)))
	{
		p = fs::canonical(p, ec);
		if (ec) throw InputError(dir + ": cannot resolve the symbolic link: " + ec.message());
	}
	const fs::path parent = parentOf(p);
	fs::create_directories(parent, ec);
	if (ec) throw InputError(dir + ": cannot create the folder " + parent.string() + ": " + ec.message());
	return p;
}

std::string partialPrefix(const fs::path& target) { return "." + target.filename().string() + ".partial-"; }

/// Every entry under `dir` (links not followed), as paths relative to it in
/// generic form, folders with a trailing '/', the marker itself left out.
std::vector<std::string> entriesUnder(const fs::path& dir, const fs::path& shown_as)
{
	std::vector<std::string> out;
	std::error_code ec;
	for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
	{
		std::string rel = fs::relative(it->path(), dir).generic_string();
		if (rel == kOutputMarkerFile) continue;
		std::error_code type_ec;
		if (it->is_directory(type_ec) && !it->is_symlink(type_ec)) rel += '/';
		out.push_back(rel);
	}
	if (ec) throw InputError(shown_as.string() + ": cannot list the folder: " + ec.message());
	std::sort(out.begin(), out.end());
	return out;
}

/// The entries the marker of `dir` lists (empty for the markers of esif
/// versions that did not list them).
std::set<std::string> listedEntries(const fs::path& dir)
{
	TextLineReader in((dir / kOutputMarkerFile).string(), "esif output marker");
	std::set<std::string> listed;
	std::string line;
	if (!in.next(line) || line != kMarkerHeader)
		in.fail("not an esif output marker (its first line is not '" + std::string(kMarkerHeader) + "')");
	while (in.next(line))
		if (!line.empty() && line[0] != '#') listed.insert(line);
	return listed;
}

/// A folder esif may replace: none yet, an empty one, or one holding only
/// what the marker says esif wrote there. Any other is the user's: refused
/// naming the first file esif did not write, never deleted.
void checkReplaceable(const fs::path& target)
{
	std::error_code ec;
	if (!fs::exists(fs::symlink_status(target, ec))) return;
	if (!fs::is_directory(target, ec))
		throw InputError(target.string() + ": exists and is not a folder (not replaced)");
	if (fs::is_empty(target, ec)) return;
	if (!pathPresent((target / kOutputMarkerFile).string()))
		throw InputError(target.string() + ": not empty and not an esif output folder (no " + kOutputMarkerFile +
						 "); not replaced: remove it or choose another --out");
	const std::set<std::string> listed = listedEntries(target);
	for (const auto& entry : entriesUnder(target, target))
		if (!listed.count(entry))
			throw InputError(
				(target / entry).string() + ": not written by esif (not listed in its " + kOutputMarkerFile + ")" +
				(listed.empty() ? " and the folder's marker lists nothing (an earlier esif)" : "") + "; " +
				target.string() + " is not replaced: move the file away, or remove the folder, or choose another --out");
}

/// Whether `name` is exactly partialPrefix + a process ID.
bool isPartialName(const std::string& name, const std::string& prefix)
{
	return name.size() > prefix.size() && name.compare(0, prefix.size(), prefix) == 0 &&
		   std::all_of(name.begin() + static_cast<std::ptrdiff_t>(prefix.size()), name.end(),
					   [](unsigned char c) { return std::isdigit(c); });
}

fs::path createStaging(const fs::path& target)
{
	const fs::path staging = partialFolderOf(target);
	std::error_code ec;
	fs::create_directory(staging, ec);
	if (ec) throw InputError(target.string() + ": cannot create the folder " + staging.string() + ": " + ec.message());
	termination::addPath(staging.string());
	return staging;
}

/// Every file present and not empty, and no temporary file of AtomicFile.h left.
void verify(const fs::path& staging, const fs::path& target, const std::vector<std::string>& required)
{
	for (const auto& name : required)
	{
		std::error_code ec;
		const auto size = fs::file_size(staging / name, ec);
		if (ec || size == 0) throw InputError((target / name).string() + ": missing or empty after writing");
	}
	std::error_code ec;
	for (fs::recursive_directory_iterator it(staging, ec), end; !ec && it != end; it.increment(ec))
		if (it->path().extension() == ".tmp")
			throw InputError(
				(target / fs::relative(it->path(), staging)).string() + ": temporary file left after writing");
	if (ec) throw InputError(target.string() + ": cannot list the written folder: " + ec.message());
}

/// Swaps by two renames where the file system has no RENAME_EXCHANGE; the
/// old folder is put back if the second rename fails.
void swapByRenames(const fs::path& staging, const fs::path& target)
{
	const fs::path aside = staging.string() + ".old";
	if (std::rename(target.c_str(), aside.c_str()) != 0)
		throw InputError(target.string() + ": cannot move the previous folder aside: " + std::strerror(errno));
	if (std::rename(staging.c_str(), target.c_str()) != 0)
	{
		const int err = errno;
		std::rename(aside.c_str(), target.c_str());
		throw InputError(target.string() + ": cannot move the new folder into place: " + std::strerror(err));
	}
	std::rename(aside.c_str(), staging.c_str());  // so the caller finds the old tree where exchange leaves it
}

/// Puts `staging` at `target`; a previous `target` ends up at `staging`.
void swapIntoPlace(const fs::path& staging, const fs::path& target)
{
	std::error_code ec;
	if (!fs::exists(fs::symlink_status(target, ec)))
	{
		if (std::rename(staging.c_str(), target.c_str()) != 0)
			throw InputError(target.string() + ": cannot move the new folder into place: " + std::strerror(errno));
		return;
	}
	if (::renameat2(AT_FDCWD, staging.c_str(), AT_FDCWD, target.c_str(), RENAME_EXCHANGE) == 0) return;
	if (errno == EINVAL || errno == ENOSYS || errno == EOPNOTSUPP) return swapByRenames(staging, target);
	throw InputError(target.string() + ": cannot replace the previous folder: " + std::strerror(errno));
}

}  // namespace

fs::path partialFolderOf(const fs::path& target)
{
	return target.parent_path() / (partialPrefix(target) + std::to_string(::getpid()));
}

void removeStalePartials(const fs::path& target)
{
	const std::string prefix = partialPrefix(target);
	std::error_code ec;
	for (fs::directory_iterator it(parentOf(target), ec), end; !ec && it != end; it.increment(ec))
		if (isPartialName(it->path().filename().string(), prefix))
		{
			std::error_code ignored;
			fs::remove_all(it->path(), ignored);
		}
}

RunFolder::RunFolder(const std::string& target)
	: target_(preparedTarget(target)), lock_(target_)
{
	checkReplaceable(target_);
	removeStalePartials(target_);
	staging_ = createStaging(target_);
}

RunFolder::~RunFolder()
{
	// Before commit it holds the unfinished outputs, after it the previous
	// folder if commit could not remove it: either way it goes.
	std::error_code ec;
	fs::remove_all(staging_, ec);
	termination::removePath(staging_.string());
}

void RunFolder::commit(const std::vector<std::string>& required)
{
	verify(staging_, target_, required);
	std::string marker = std::string(kMarkerHeader) +
						 "\n# what esif wrote here: a later run replaces this folder only while it holds nothing else\n";
	for (const auto& entry : entriesUnder(staging_, target_)) marker += entry + "\n";
	writeBytesChecked((staging_ / kOutputMarkerFile).string(), marker, (target_ / kOutputMarkerFile).string());
	syncFolder(staging_.string());
	{
		// The watcher must not remove the partial folder between the swap and
		// the moment it holds the previous folder.
		const auto hold = termination::holdOff();
		swapIntoPlace(staging_, target_);
	}
	syncFolder(parentOf(target_).string());
	std::error_code ec;
	fs::remove_all(staging_, ec);  // the previous folder, if any
	if (ec)
		std::cerr << "esif: warning: " << staging_.string() << ": the previous output could not be removed ("
				  << ec.message() << "); the next run into " << target_.string() << " removes it\n";
}

void RunFolder::rethrowNamingTarget() const { rethrowWithPathReplaced(staging_.string(), target_.string()); }

}  // namespace esif
