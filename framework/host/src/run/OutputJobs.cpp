/// \file OutputJobs.cpp
/// See OutputJobs.h.

#include <esif/run/OutputJobs.h>

#include <chrono>
#include <exception>
#include <optional>
#include <system_error>
#include <thread>

namespace esif
{
void OutputJobs::add(std::string phase, std::function<void()> write)
{
	jobs_.push_back({std::move(phase), std::move(write), false});
}

void OutputJobs::addFigure(std::string phase, std::function<void()> write)
{
	jobs_.push_back({std::move(phase), std::move(write), true});
}

void OutputJobs::append(OutputJobs&& other)
{
	for (auto& job : other.jobs_) jobs_.push_back(std::move(job));
	other.jobs_.clear();
}

void OutputJobs::run(PhaseTimes* times)
{
	const std::vector<Job> jobs = std::move(jobs_);
	jobs_.clear();
	std::vector<double> seconds(jobs.size(), 0.0);
	std::vector<std::exception_ptr> failures(jobs.size());
	// Runs the jobs of one lane (figures or the rest) in the order added.
	const auto lane = [&](bool figures) {
		for (std::size_t i = 0; i < jobs.size(); ++i)
		{
			if (jobs[i].figure != figures) continue;
			const auto t0 = std::chrono::steady_clock::now();
			try
			{
				jobs[i].write();
			}
			catch (...)
			{
				failures[i] = std::current_exception();
			}
			seconds[i] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
		}
	};
	std::optional<std::thread> beside;
	try
	{
		beside.emplace(lane, true);
	}
	catch (const std::system_error&)
	{
		lane(true);	 // no thread to spare: the calling thread draws them too
	}
	lane(false);
	if (beside) beside->join();
	if (times)
		for (std::size_t i = 0; i < jobs.size(); ++i) times->add(jobs[i].phase, seconds[i]);
	for (const auto& failure : failures)
		if (failure) std::rethrow_exception(failure);
}

}  // namespace esif
