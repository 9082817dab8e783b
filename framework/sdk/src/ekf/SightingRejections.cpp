#include <esif/ekf/SightingRejections.h>

namespace esif
{
SightingRejections& SightingRejections::operator+=(const SightingRejections& other)
{
	ambiguous_waits += other.ambiguous_waits;
	poorly_observed += other.poorly_observed;
	unconfirmed += other.unconfirmed;
	return *this;
}

void SightingRejections::appendCounters(
	std::vector<std::pair<std::string, double>>& counters, const std::string& prefix) const
{
	counters.emplace_back(prefix + "ambiguous_waits", static_cast<double>(ambiguous_waits));
	counters.emplace_back(prefix + "poorly_observed_sightings", static_cast<double>(poorly_observed));
	counters.emplace_back(prefix + "unconfirmed_sightings", static_cast<double>(unconfirmed));
}

}  // namespace esif
