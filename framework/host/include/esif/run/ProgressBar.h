#pragma once
/// \file ProgressBar.h
/// A one-line progress bar on stderr for long replays; silent when stderr is
/// not a terminal (CI logs, pipes) so logs stay clean.

#include <chrono>
#include <cstddef>
#include <string>

namespace esif
{
class ProgressBar
{
   public:
	/// With `show_eta`, the time left is estimated from the mean time per
	/// item so far (items of a campaign take about as long as each other).
	ProgressBar(std::string label, std::size_t total, bool show_eta = false);
	~ProgressBar();
	/// Reports that `done` of `total` items are finished (redraws at most ~10 Hz).
	void update(std::size_t done);
	/// Clears the line.
	void finish();
	bool enabled() const { return enabled_; }

   private:
	std::string label_;
	std::size_t total_;
	bool enabled_;
	bool finished_ = false;
	bool show_eta_ = false;
	std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
	std::chrono::steady_clock::time_point last_draw_{};
};

}  // namespace esif
