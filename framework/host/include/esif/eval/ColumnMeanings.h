#pragma once
/// \file ColumnMeanings.h
/// What the columns of esif's tables mean, written once: comparison.md's
/// and comparison.html's rows (comparisonColumnMeanings) and summary.md's
/// and summary.html's columns (monteCarloSummaryColumns). The tables of
/// docs/outputs.md repeat them word for word (checked by test_report).

#include <string>
#include <vector>

namespace esif
{
/// One explanation: the columns (or rows) it covers, when they are shown
/// (empty: always) and what they mean. Text may mark names as `code`.
struct ColumnMeaning
{
	std::vector<std::string> columns;
	std::string when;
	std::string meaning;
};

/// The rows of comparison.md by stats key: comparisonKeys() and the
/// optional ones (state NEES, map joining, base_*, ref_*, refres_*).
const std::vector<ColumnMeaning>& comparisonColumnMeanings();

/// The columns of summary.md, in order, by their headings.
const std::vector<ColumnMeaning>& monteCarloSummaryColumns();

/// Every column heading of `meanings`, in order.
std::vector<std::string> columnHeadings(const std::vector<ColumnMeaning>& meanings);

/// The entry covering `column`, or null.
const ColumnMeaning* meaningOf(const std::vector<ColumnMeaning>& meanings, const std::string& column);

/// The entries covering at least one of `shown`, in the order of `meanings`.
std::vector<const ColumnMeaning*> meaningsShown(
	const std::vector<ColumnMeaning>& meanings, const std::vector<std::string>& shown);

/// The explanation with "when: " before it when it has a condition; `code` marks kept.
std::string fullMeaning(const ColumnMeaning& m);

/// The same as plain text (a title attribute): `code` marks become double quotes.
std::string plainMeaning(const ColumnMeaning& m);

/// The columns it covers, comma-separated.
std::string columnList(const ColumnMeaning& m);

}  // namespace esif
