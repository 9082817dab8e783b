#pragma once
/// \file DifferenceSpread.h
/// RMS and maximum of non-negative differences added one at a time: the
/// two statistics every comparison of two estimates reports.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>

namespace esif
{
class DifferenceSpread
{
   public:
	void add(double d)
	{
		sum_sq_ += d * d;
		max_ = std::max(max_, d);
		++count_;
	}
	std::size_t count() const { return count_; }
	/// nullopt when nothing was added.
	std::optional<double> rms() const
	{
		return count_ ? std::optional<double>(std::sqrt(sum_sq_ / static_cast<double>(count_))) : std::nullopt;
	}
	std::optional<double> max() const { return count_ ? std::optional<double>(max_) : std::nullopt; }

   private:
	double sum_sq_ = 0;
	double max_ = 0;
	std::size_t count_ = 0;
};

}  // namespace esif
