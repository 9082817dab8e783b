#pragma once
/// \file BookTable.h
/// The runs of `esif compare` in the layout of the book's Table 5.1
/// (performance of the exactly sparse information filters, Sec. 5.5): one
/// column per estimator - full SLAM, D-SLAM, D-SLAM local map joining filter,
/// SLSJF, each filled from the first run of that stats "formulation" or
/// `not available` - then one column per further run (e.g. EKF SLAM), by
/// label; rows: information non-zeros, features, poses in the state, state
/// dimension. Integers carry thousands separators.

#include <esif/formats/StatsJson.h>

#include <string>
#include <vector>

namespace esif
{
/// The table's title line (without newline).
const std::string& bookTable51Title();

/// The table as rows of cells: row 0 the column headings (its first cell
/// empty), then one row per book row, its heading first.
std::vector<std::vector<std::string>> bookTable51Grid(const std::vector<Stats>& runs);

/// Aligned text for the terminal: the title, a header row and the four rows.
std::string bookTable51Text(const std::vector<Stats>& runs);

/// The same as a Markdown section for comparison.md.
std::string bookTable51Markdown(const std::vector<Stats>& runs);

}  // namespace esif
