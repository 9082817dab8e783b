#include <esif/core/Errors.h>

#include <sstream>

namespace esif
{
std::string oneLineReason(const std::string& text)
{
	std::istringstream lines(text);
	for (std::string line; std::getline(lines, line);)
	{
		line.erase(0, line.find_first_not_of(" \t"));
		if (line.empty() || line.rfind("====", 0) == 0) continue;
		if (line.rfind("Message:", 0) == 0) line.erase(0, line.find_first_not_of(" \t", 8));
		if (!line.empty()) return line;
	}
	return text.substr(0, text.find('\n'));
}

}  // namespace esif
