#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/formats/StatsJson.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

namespace esif
{
void Stats::set(const std::string& key, StatValue value)
{
	if (auto* d = std::get_if<double>(&value); d && !std::isfinite(*d)) value = nullptr;  // JSON has no NaN
	for (auto& kv : items_)
		if (kv.first == key)
		{
			kv.second = std::move(value);
			return;
		}
	items_.emplace_back(key, std::move(value));
}

void Stats::set(const std::string& key, const std::optional<double>& value)
{
	if (value)
		set(key, StatValue(*value));
	else
		set(key, StatValue(nullptr));
}

std::optional<StatValue> Stats::get(const std::string& key) const
{
	for (const auto& kv : items_)
		if (kv.first == key) return kv.second;
	return std::nullopt;
}

std::optional<double> Stats::number(const std::string& key) const
{
	const auto v = get(key);
	if (!v) return std::nullopt;
	if (const auto* d = std::get_if<double>(&*v)) return *d;
	if (const auto* i = std::get_if<long long>(&*v)) return static_cast<double>(*i);
	return std::nullopt;
}

std::optional<std::string> Stats::text(const std::string& key) const
{
	const auto v = get(key);
	if (!v) return std::nullopt;
	if (const auto* t = std::get_if<std::string>(&*v)) return *t;
	return std::nullopt;
}

namespace
{
std::string quoted(const std::string& s)
{
	std::string out = "\"";
	for (const char c : s)
	{
		if (c == '"' || c == '\\')
			out += std::string("\\") + c;
		else if (c == '\n')
			out += "\\n";
		else if (static_cast<unsigned char>(c) < 0x20)
			out += ' ';
		else
			out += c;
	}
	return out + "\"";
}
}  // namespace

std::string statText(const StatValue& v)
{
	if (std::holds_alternative<std::nullptr_t>(v)) return "null";
	if (const auto* d = std::get_if<double>(&v)) return formatNumber(*d);
	if (const auto* i = std::get_if<long long>(&v)) return std::to_string(*i);
	return std::get<std::string>(v);
}

std::string Stats::toJson() const
{
	std::ostringstream out;
	out << "{\n";
	for (std::size_t k = 0; k < items_.size(); ++k)
	{
		const auto& [key, value] = items_[k];
		out << "  " << quoted(key) << ": "
			<< (std::holds_alternative<std::string>(value) ? quoted(std::get<std::string>(value)) : statText(value))
			<< (k + 1 < items_.size() ? ",\n" : "\n");
	}
	out << "}\n";
	return out.str();
}

Stats Stats::load(const std::string& path)
{
	std::ifstream in(path);
	if (!in) throw InputError(path + ": cannot open");
	std::stringstream ss;
	ss << in.rdbuf();
	return fromJson(ss.str(), path);
}

Stats Stats::fromJson(const std::string& text, const std::string& origin)
{
	Stats out;
	std::size_t i = 0;
	const auto fail = [&](const std::string& what) {
		throw InputError(origin + ": malformed stats JSON at offset " + std::to_string(i) + ": " + what);
	};
	const auto skip = [&] {
		while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
	};
	const auto readString = [&] {
		if (text[i] != '"') fail("expected a string");
		std::string s;
		for (++i; i < text.size() && text[i] != '"'; ++i)
		{
			if (text[i] == '\\' && i + 1 < text.size()) ++i, s += text[i] == 'n' ? '\n' : text[i];
			else s += text[i];
		}
		if (i >= text.size()) fail("unterminated string");
		++i;
		return s;
	};
	skip();
	if (i >= text.size() || text[i++] != '{') fail("expected '{'");
	for (;;)
	{
		skip();
		if (i < text.size() && text[i] == '}') break;
		const std::string key = readString();
		skip();
		if (i >= text.size() || text[i++] != ':') fail("expected ':'");
		skip();
		if (i >= text.size()) fail("missing value");
		if (text[i] == '"')
			out.set(key, StatValue(readString()));
		else if (text.compare(i, 4, "null") == 0)
			i += 4, out.set(key, StatValue(nullptr));
		else
		{
			std::size_t end = i;
			while (end < text.size() && (std::isdigit(static_cast<unsigned char>(text[end])) ||
										 std::string("+-.eE").find(text[end]) != std::string::npos))
				++end;
			const std::string num = text.substr(i, end - i);
			if (num.empty()) fail("expected a value");
			const bool integral = num.find_first_of(".eE") == std::string::npos;
			if (integral) out.set(key, StatValue(std::stoll(num)));
			else out.set(key, StatValue(std::stod(num)));
			i = end;
		}
		skip();
		if (i < text.size() && text[i] == ',') ++i;
	}
	return out;
}

}  // namespace esif
