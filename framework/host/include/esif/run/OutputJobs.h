#pragma once
/// \file OutputJobs.h
/// A run's output files are independent of each other: drawing map.png
/// does not need map.simplemap's gzip. OutputJobs writes each figure on a
/// thread of its own while the calling thread writes the rest, each timed
/// under its own phase, and keeps what a sequential writer promised: the
/// phases appear in stats.json in the order the jobs were added, and when
/// some fail, every other job still finishes before the first failure (in
/// that order) is thrown.
///
/// MRPT's serialisers (simple maps, scenes, landmark maps) keep lazily built
/// global state, so they stay on the calling thread; a figure is a gnuplot
/// process fed from its own script (render/src/PlotScript.h), so its thread
/// mostly waits, and the figures of a run are drawn at the same time.

#include <esif/run/PhaseTimes.h>

#include <functional>
#include <string>
#include <vector>

namespace esif
{
class OutputJobs
{
   public:
	/// Adds `write`, timed as `phase` (e.g. "map_simplemap"), to the calling
	/// thread's lane.
	void add(std::string phase, std::function<void()> write);
	/// Adds a figure: drawn on a thread of its own beside the calling thread.
	void addFigure(std::string phase, std::function<void()> write);
	/// Adds `other`'s jobs after these.
	void append(OutputJobs&& other);
	/// Forgets the figures added so far (`esif run --no-figures`).
	void dropFigures();

	/// Runs every job added (each figure on its own thread when one can be
	/// started, else on the calling thread after the rest), records each
	/// one's time in `times` when given, and forgets the jobs. Rethrows the
	/// first failure in the order added.
	void run(PhaseTimes* times);

   private:
	struct Job
	{
		std::string phase;
		std::function<void()> write;
		bool figure = false;
	};
	std::vector<Job> jobs_;
};

}  // namespace esif
