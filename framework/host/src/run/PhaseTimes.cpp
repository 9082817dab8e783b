#include <esif/run/PhaseTimes.h>

#include <algorithm>

namespace esif
{
void PhaseTimes::add(const std::string& phase, double seconds)
{
	const auto it = std::find_if(phases_.begin(), phases_.end(), [&](const auto& p) { return p.first == phase; });
	if (it != phases_.end())
		it->second += seconds;
	else
		phases_.emplace_back(phase, seconds);
}

void PhaseTimes::setStats(Stats& stats) const
{
	for (const auto& [phase, seconds] : phases_) stats.set("time_" + phase + "_s", StatValue(seconds));
}

}  // namespace esif
