/// \file OutputJobs.cpp
/// See OutputJobs.h.

#include <esif/run/OutputJobs.h>

#include <chrono>
#include <exception>
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

void OutputJobs::dropFigures()
{
	std::vector<Job> kept;
	for (auto& job : jobs_)
		if (!job.figure) kept.push_back(std::move(job));
	jobs_ = std::move(kept);
}

void OutputJobs::run(PhaseTimes* times)
{
	const std::vector<Job> jobs = std::move(jobs_);
	jobs_.clear();
	std::vector<double> seconds(jobs.size(), 0.0);
	std::vector<std::exception_ptr> failures(jobs.size());
	const auto runJob = [&](std::size_t i) {
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
	};
	std::vector<std::thread> beside;
	std::vector<std::size_t> left;	// figures no thread could be started for
	for (std::size_t i = 0; i < jobs.size(); ++i)
	{
		if (!jobs[i].figure) continue;
		try
		{
			beside.emplace_back(runJob, i);
		}
		catch (const std::system_error&)
		{
			left.push_back(i);
		}
	}
	for (std::size_t i = 0; i < jobs.size(); ++i)
		if (!jobs[i].figure) runJob(i);
	for (const std::size_t i : left) runJob(i);
	for (std::thread& t : beside) t.join();
	if (times)
		for (std::size_t i = 0; i < jobs.size(); ++i) times->add(jobs[i].phase, seconds[i]);
	for (const auto& failure : failures)
		if (failure) std::rethrow_exception(failure);
}

}  // namespace esif
