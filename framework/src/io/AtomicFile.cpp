#include <esif/core/Errors.h>
#include <esif/io/AtomicFile.h>

#include <filesystem>
#include <fstream>
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
}  // namespace

void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write)
{
	const std::string tmp = temporaryNameFor(path);
	try
	{
		write(tmp);
		std::error_code ec;
		fs::rename(tmp, path, ec);
		if (ec) throw InputError(path + ": cannot write output: " + ec.message());
	}
	catch (const ConfigError&)
	{
		fs::remove(tmp);
		throw;
	}
	catch (const InputError&)
	{
		fs::remove(tmp);
		throw;
	}
	catch (const NumericalError&)
	{
		fs::remove(tmp);
		throw;
	}
	catch (const std::exception& e)
	{
		fs::remove(tmp);
		throw InputError(path + ": cannot write output: " + e.what());
	}
}

void writeTextAtomically(const std::string& path, const std::string& text)
{
	writeAtomically(path, [&](const std::string& tmp) {
		std::ofstream out(tmp, std::ios::binary);
		if (!out) throw InputError(path + ": cannot open for writing");
		out << text;
		out.close();
		if (!out) throw InputError(path + ": write failed");
	});
}

void ensureDirectory(const std::string& dir)
{
	std::error_code ec;
	fs::create_directories(dir, ec);
	if (ec || !fs::is_directory(dir))
		throw InputError(dir + ": cannot create output folder" + (ec ? ": " + ec.message() : ""));
}

}  // namespace esif
