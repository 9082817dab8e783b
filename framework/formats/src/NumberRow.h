#pragma once
/// \file NumberRow.h
/// One data line of a whitespace-separated text file whose columns are all
/// numbers (ground truth, dataset files, local maps), each column known by
/// name so an error reads "FILE:LINE: column K (NAME) = VALUE: rule". Every
/// value is a finite number (integer columns: an integer as written); the
/// accessors add the bounds of InputBounds.h or the caller's own.

#include <esif/core/StepInput.h>

#include <functional>
#include <string>
#include <vector>

namespace esif
{
class NumberRow
{
   public:
	/// The columns a row must have, named for messages.
	class Columns
	{
	   public:
		/// Columns called `names` ("3 columns 'id x y'" in a message); the
		/// first `integers` of them hold integers written as such ("7", not
		/// "7.0" or "7e0"), the others any finite numbers.
		explicit Columns(std::vector<std::string> names, std::size_t integers = 0);
		/// `count` number columns, column i called `name(i)`; `what` says
		/// what a row holds ("7 numbers (a row of ...)") when it has not.
		Columns(std::size_t count, std::string what, std::function<std::string(std::size_t)> name);

		std::size_t size() const { return count_; }
		std::string name(std::size_t i) const { return name_(i); }
		bool isInteger(std::size_t i) const { return i < integers_; }
		/// What a row must hold, for the message of a wrong count.
		const std::string& what() const { return what_; }

	   private:
		std::size_t count_;
		std::size_t integers_ = 0;
		std::string what_;
		std::function<std::string(std::size_t)> name_;
	};

	/// Parses `line`, which must hold exactly one number per column of
	/// `columns` (kept by reference: pass a long-lived one); `where` is
	/// "FILE:LINE".
	NumberRow(const std::string& line, const Columns& columns, std::string where);

	/// Column `i` as it is (finite).
	double number(std::size_t i) const { return values_[i]; }
	/// Column `i` within [lo, hi]; `unit` and `why` say what the bound is.
	double bounded(std::size_t i, double lo, double hi, const std::string& unit, const std::string& why) const;
	/// Column `i` as a coordinate [m], within +-kMaxCoordinate_m.
	double coordinate(std::size_t i) const;
	/// Column `i` as a heading [rad], within +-kMaxHeading_rad.
	double heading(std::size_t i) const;
	/// Column `i` holding a whole number in [lo, hi] ("7.0" is 7).
	long wholeNumber(std::size_t i, long lo, long hi) const;
	/// Column `i` as a landmark ID: a whole number in [0, kMaxLandmarkId].
	LandmarkId landmarkId(std::size_t i) const;
	/// Column `i`, one of the integer columns.
	long integer(std::size_t i) const { return integers_[i]; }
	/// Column `i` as written, for messages.
	const std::string& token(std::size_t i) const { return tokens_[i]; }

	/// "FILE:LINE" of the row.
	const std::string& where() const { return where_; }

	/// Throws InputError "FILE:LINE: column K (NAME) = VALUE: rule".
	[[noreturn]] void fail(std::size_t i, const std::string& rule) const;

   private:
	void requireCount() const;
	void read(std::size_t i);

	const Columns& columns_;
	std::string where_;
	std::vector<std::string> tokens_;
	std::vector<long> integers_;  // the integer columns, as written
	std::vector<double> values_;  // every column read so far
};

}  // namespace esif
