#pragma once
/// \file PlotScript.h
/// The small layer between esif's figures and gnuplot: a figure is gnuplot
/// commands over inline data blocks, drawn once to PNG (pngcairo) and once
/// to SVG (gnuplot's svg) by one gnuplot process, each file written atomically.
/// Axes, ticks, legends, log scales, bands and fonts are gnuplot's.

#include <array>
#include <cstddef>
#include <initializer_list>
#include <string>
#include <vector>

namespace esif::plot
{
/// Smallest and largest accepted figure width [px].
constexpr int kMinWidthPx = 200;
constexpr int kMaxWidthPx = 16384;

/// Throws ConfigError naming `what` when width_px is outside [200, 16384].
void validateWidth(int width_px, const std::string& what);

/// Twelve colours that stay apart on white paper and screens ("#rrggbb"):
/// the twelve darkest of Sasha Trubetskoy's 20 distinct colours, so a chart
/// of up to twelve runs or configs gives each its own.
const std::array<const char*, 12>& seriesColours();

/// Series i's colour (the twelve repeat from the 13th).
const char* seriesColour(std::size_t i);

/// `text` as a gnuplot single-quoted string (no escapes are interpreted
/// inside; a quote is doubled), control characters replaced by spaces, so a
/// run name or a path cannot end the string or inject a command.
std::string quoted(const std::string& text);

/// A number as gnuplot reads it: "%.9g", or NaN for a non-finite value (a
/// point gnuplot leaves out).
std::string number(double v);

/// Rows of numbers for one inline data block ($name << EOD ... EOD).
class DataBlock
{
   public:
	void row(std::initializer_list<double> values);
	/// The line drawn through the block breaks before the next row (a blank
	/// line); nothing when no row came yet or the line is already broken.
	void breakLine() { broken_ = rows_ > 0; }
	bool empty() const { return rows_ == 0; }
	std::size_t rows() const { return rows_; }
	const std::string& text() const { return text_; }

   private:
	std::string text_;
	std::size_t rows_ = 0;
	bool broken_ = false;
};

/// One figure: its size, its data blocks and the commands that draw it.
class Figure
{
   public:
	Figure(int width_px, int height_px);

	/// Adds `block` and returns its name ("$d0", "$d1", ...) for plot commands.
	std::string add(const DataBlock& block);

	/// Appends one or more commands (a newline is added).
	void command(const std::string& commands);


	/// The whole gnuplot script: the data blocks once, then the commands
	/// drawn to `png_path` and again to `svg_path`.
	std::string script(const std::string& png_path, const std::string& svg_path) const;

   private:
	int width_px_;
	int height_px_;
	std::string data_;
	std::string commands_;
	std::size_t blocks_ = 0;
};

/// "plot <clause>, <clause>, ..."; with no clause a plot that draws nothing
/// (the axes and titles set so far stay).
std::string plotCommand(const std::vector<std::string>& clauses);

/// The vector twin of a figure's PNG: the same path with ".svg".
std::string vectorPathOf(const std::string& png_path);

/// Draws `figure` into `png_path` and vectorPathOf(png_path), each written
/// atomically (nothing is left behind on failure). Throws InputError naming
/// the PNG when gnuplot is missing or fails, or a file cannot be written.
void writeFigure(const Figure& figure, const std::string& png_path);

}  // namespace esif::plot

namespace esif::plot
{
/// Every text of a figure is this dark grey, never pure black: black marks
/// data (the non-zeros of info_matrix.png, the reference of maps_overlay.png).
inline constexpr const char* kTextColour = "#262626";

/// Titles, axis labels, tick labels and legend in kTextColour.
std::string textDefaults();

/// "set multiplot [layout <layout>] title '<title>'" in kTextColour.
std::string multiplotTitle(const std::string& title, const std::string& layout = "");

/// The look every chart shares (textDefaults() included): light grid, grey frame, legend in a box
/// at the top right of each panel.
std::string chartDefaults();

/// A light tint of "#rrggbb" (mixed `amount` of the way to white), for bands
/// under the lines of the same colour.
std::string tint(const std::string& colour, double amount);

/// `title` with the book figure it corresponds to, e.g. "... (cf. book Fig. 3.20)".
std::string withBookFigure(const std::string& title, const std::string& book_figure);

/// A gnuplot string expression of two lines: `first`, a line break, `second`
/// (each quoted()), for a title with a subtitle under it.
std::string twoLines(const std::string& first, const std::string& second);

}  // namespace esif::plot
