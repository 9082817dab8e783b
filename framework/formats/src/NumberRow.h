#pragma once
/// \file NumberRow.h
/// One data line of a whitespace-separated text file whose columns are all
/// numbers (ground truth, dataset files), each column known by name so an
/// error reads "FILE:LINE: column K (NAME) = VALUE: rule". Every value is a
/// finite number; the accessors add the bounds of InputBounds.h or the
/// caller's own.

#include <esif/core/StepInput.h>

#include <string>
#include <vector>

namespace esif
{
class NumberRow
{
   public:
	/// Parses `line`, which must hold exactly one number per name in `names`
	/// (kept by reference: pass a long-lived list); `where` is "FILE:LINE".
	NumberRow(const std::string& line, const std::vector<const char*>& names, std::string where);

	/// Column `i` as it is (finite).
	double number(std::size_t i) const { return values_[i]; }
	/// Column `i` within [lo, hi]; `unit` and `why` say what the bound is.
	double bounded(std::size_t i, double lo, double hi, const std::string& unit, const std::string& why) const;
	/// Column `i` as a coordinate [m], within +-kMaxCoordinate_m.
	double coordinate(std::size_t i) const;
	/// Column `i` as a heading [rad], within +-kMaxHeading_rad.
	double heading(std::size_t i) const;
	/// Column `i` as a whole number in [lo, hi].
	long integer(std::size_t i, long lo, long hi) const;
	/// Column `i` as a landmark ID: an integer in [0, kMaxLandmarkId].
	LandmarkId landmarkId(std::size_t i) const;

	/// "FILE:LINE" of the row.
	const std::string& where() const { return where_; }

	/// Throws InputError "FILE:LINE: column K (NAME) = VALUE: rule".
	[[noreturn]] void fail(std::size_t i, const std::string& rule) const;

   private:
	const std::vector<const char*>& names_;
	std::string where_;
	std::vector<std::string> tokens_;
	std::vector<double> values_;
};

}  // namespace esif
