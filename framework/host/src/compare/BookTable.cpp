#include <esif/compare/BaselineComparison.h>
#include <esif/compare/BookTable.h>
#include <esif/formats/Markdown.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

namespace esif
{
namespace
{
/// The book's columns, in its order, with the formulation that fills each.
struct BookColumn
{
	const char* heading;
	const char* formulation;
};
constexpr BookColumn kBookColumns[] = {
	{"full SLAM", "full_slam"},
	{"D-SLAM", "dslam"},
	{"D-SLAM local map joining filter", "dslam_local_map_joining"},
	{"SLSJF", "slsjf"},
};

/// The book's rows: heading and stats key.
constexpr std::pair<const char*, const char*> kRows[] = {
	{"Number of non-zeros", "info_nnz"},
	{"Number of features", "landmarks"},
	{"Number of poses", "poses_in_state"},
	{"State dimension", "state_dim"},
};

constexpr const char* kNotAvailable = "not available";

/// A table column: its heading and the run filling it (none: not available).
struct Column
{
	std::string heading;
	std::optional<std::size_t> run;
};

/// The four book columns, then every run not placed in one of them.
std::vector<Column> columnsOf(const std::vector<Stats>& runs)
{
	std::vector<Column> columns;
	std::vector<bool> placed(runs.size(), false);
	for (const auto& book : kBookColumns)
	{
		Column c{book.heading, std::nullopt};
		for (std::size_t i = 0; i < runs.size() && !c.run; ++i)
			if (runFormulation(runs[i]) == book.formulation) c.run = i, placed[i] = true;
		columns.push_back(c);
	}
	for (std::size_t i = 0; i < runs.size(); ++i)
		if (!placed[i]) columns.push_back({runs[i].text("label").value_or("?"), i});
	return columns;
}

/// 1234567 -> "1,234,567".
std::string withThousands(long long v)
{
	std::string digits = std::to_string(v < 0 ? -v : v);
	for (int at = static_cast<int>(digits.size()) - 3; at > 0; at -= 3) digits.insert(static_cast<std::size_t>(at), ",");
	return (v < 0 ? "-" : "") + digits;
}

/// A cell: the run's count, "-" when it has none (e.g. info_nnz of a covariance filter).
std::string cellOf(const Column& column, const std::vector<Stats>& runs, const char* key)
{
	if (!column.run) return kNotAvailable;
	const auto v = runs[*column.run].number(key);
	if (!v) return "-";
	return withThousands(std::llround(*v));
}

}  // namespace

std::vector<std::vector<std::string>> bookTable51Grid(const std::vector<Stats>& runs)
{
	const auto columns = columnsOf(runs);
	std::vector<std::vector<std::string>> rows(1, {""});
	for (const auto& c : columns) rows[0].push_back(c.heading);
	for (const auto& [heading, key] : kRows)
	{
		std::vector<std::string> row = {heading};
		for (const auto& c : columns) row.push_back(cellOf(c, runs, key));
		rows.push_back(row);
	}
	return rows;
}

const std::string& bookTable51Title()
{
	static const std::string title = "Table 5.1 layout: performance of exactly sparse information filters";
	return title;
}

std::string bookTable51Text(const std::vector<Stats>& runs)
{
	const auto rows = bookTable51Grid(runs);
	std::vector<std::size_t> width(rows[0].size(), 0);
	for (const auto& row : rows)
		for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
	std::ostringstream out;
	out << bookTable51Title() << "\n";
	for (const auto& row : rows)
	{
		// Row headings left-aligned, numbers right-aligned under their column headings.
		out << row[0] << std::string(width[0] - row[0].size(), ' ');
		for (std::size_t c = 1; c < row.size(); ++c) out << "  " << std::string(width[c] - row[c].size(), ' ') << row[c];
		out << "\n";
	}
	return out.str();
}

std::string bookTable51Markdown(const std::vector<Stats>& runs)
{
	const auto rows = bookTable51Grid(runs);
	std::ostringstream out;
	out << "## " << bookTable51Title() << "\n\n|";
	for (const auto& h : rows[0]) out << (h.empty() ? "" : " " + markdown::text(h)) << " |";
	out << "\n|---|";
	for (std::size_t c = 1; c < rows[0].size(); ++c) out << "---:|";
	out << "\n";
	for (std::size_t r = 1; r < rows.size(); ++r)
	{
		out << "|";
		for (const auto& cell : rows[r]) out << " " << markdown::text(cell) << " |";
		out << "\n";
	}
	return out.str();
}

}  // namespace esif
