#pragma once
/// \file FuzzSupport.h
/// What the file-reading fuzz targets share: the readers take paths, so each
/// input is written to a file of a private temporary folder first, and the
/// one rule every reader keeps for bad input: an esif error of one line
/// naming the file. Anything else (another exception, a crash, a sanitizer
/// report, memory over libFuzzer's -rss_limit_mb) is a finding.

#include <esif/core/Errors.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <unistd.h>

namespace esif::fuzz
{
/// A folder of this process under /tmp, made once (libFuzzer's workers are
/// processes) and removed when the process ends normally.
inline const std::string& privateFolder()
{
	struct Folder
	{
		std::string path;
		Folder()
		{
			char name[] = "/tmp/esif-fuzz-XXXXXX";
			if (!::mkdtemp(name)) std::abort();
			path = name;
		}
		~Folder()
		{
			std::error_code ignored;
			std::filesystem::remove_all(path, ignored);
		}
	};
	static const Folder folder;
	return folder.path;
}

inline std::string fileIn(const std::string& name) { return privateFolder() + "/" + name; }

inline void writeFile(const std::string& path, const char* data, std::size_t size)
{
	std::ofstream out(path, std::ios::binary | std::ios::trunc);
	out.write(data, static_cast<std::streamsize>(size));
	if (!out) std::abort();
}

/// What became of one input: read, or refused; and a finding when the
/// refusal broke the rule (not one line naming the file).
struct Verdict
{
	bool refused = false;
	std::optional<std::string> finding;
};

/// Calls `read()` and judges it. Exceptions other than InputError are
/// findings too: they propagate, and libFuzzer reports them.
template <class Read>
Verdict verdictOf(const std::string& file, Read&& read)
{
	try
	{
		read();
	}
	catch (const InputError& e)
	{
		const std::string line = e.what();
		if (line.find('\n') != std::string::npos || line.find(file) == std::string::npos)
			return {true, "message is not one line naming " + file + ": " + line};
		return {true, std::nullopt};
	}
	return {};
}

/// The body of a target: a finding is printed and aborts the process.
inline int reportFinding(const Verdict& verdict)
{
	if (!verdict.finding) return 0;
	std::fprintf(stderr, "%s\n", verdict.finding->c_str());
	std::abort();
}
}  // namespace esif::fuzz
