#pragma once
/// \file PhaseTimes.h
/// Where a run's time goes besides the filter: reading the input, the
/// evaluation and each output file, in the order they happen. stats.json
/// holds them as time_<phase>_s beside wall_s (the filter) and total_wall_s
/// (the whole pipeline), so `bench/end_to_end.sh` and a user can see what a
/// run costs on top of its filter.

#include <esif/formats/StatsJson.h>

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace esif
{
class PhaseTimes
{
   public:
	/// Runs `work()` and records its duration under `phase` (e.g. "read",
	/// "map_png"); a phase timed twice adds up.
	template <class Work>
	decltype(auto) time(const std::string& phase, Work&& work)
	{
		const auto t0 = std::chrono::steady_clock::now();
		struct Record
		{
			PhaseTimes& times;
			const std::string& phase;
			std::chrono::steady_clock::time_point t0;
			~Record() { times.add(phase, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()); }
		} record{*this, phase, t0};
		return work();
	}

	void add(const std::string& phase, double seconds);

	/// Sets time_<phase>_s for every phase, in the order first timed.
	void setStats(Stats& stats) const;

   private:
	std::vector<std::pair<std::string, double>> phases_;
};

}  // namespace esif
