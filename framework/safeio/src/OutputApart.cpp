/// \file OutputApart.cpp
/// The output-versus-input check; see OutputApart.h.

#include <esif/core/Errors.h>
#include <esif/safeio/OutputApart.h>

#include <algorithm>
#include <filesystem>

namespace fs = std::filesystem;

namespace esif
{
namespace
{
/// `path` absolute, with the links of its existing part resolved and `.`
/// and `..` removed; without a trailing separator.
fs::path resolved(const std::string& path)
{
	std::error_code ec;
	fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
	if (ec) p = fs::absolute(path, ec).lexically_normal();
	if (!p.has_filename() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
	return p;
}

/// Whether `inner` is `outer` or lies inside it, component by component
/// ("a/bc" is not inside "a/b").
bool isWithin(const fs::path& inner, const fs::path& outer)
{
	auto o = outer.begin(), i = inner.begin();
	for (; o != outer.end(); ++o, ++i)
		if (i == inner.end() || *i != *o) return false;
	return true;
}
}  // namespace

void requireOutputApart(const std::string& out, const std::vector<NamedInput>& inputs, const std::string& option)
{
	const fs::path target = resolved(out);
	for (const auto& input : inputs)
	{
		if (input.path.empty()) continue;
		const fs::path source = resolved(input.path);
		const bool inside_input = isWithin(target, source), holds_input = isWithin(source, target);
		if (!inside_input && !holds_input) continue;
		const char* relation = inside_input && holds_input ? "is" : holds_input ? "holds" : "lies inside";
		throw InputError(
			out + ": " + option + " " + relation + " " + input.what + " " + input.path +
			" (esif never writes over its inputs): choose another " + option);
	}
}

}  // namespace esif
