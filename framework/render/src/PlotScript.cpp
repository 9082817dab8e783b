/// \file PlotScript.cpp
/// See PlotScript.h.

#include "PlotScript.h"

#include "GnuplotProcess.h"

#include <esif/core/Errors.h>
#include <esif/safeio/AtomicFile.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace esif::plot
{
namespace
{
/// Text size and line width scale with the figure: tuned at 1000 px wide.
double scaleOf(int width_px) { return std::clamp(width_px / 1000.0, 0.4, 4.0); }

std::string pngTerminal(int w, int h)
{
	const double s = scaleOf(w);
	char buf[160];
	std::snprintf(buf, sizeof buf, "set terminal pngcairo size %d,%d noenhanced font 'Sans,%.1f' linewidth %.2f",
		w, h, 13.0 * s, s);
	return buf;
}

/// gnuplot's own SVG writer: the same size in px, a white background (a
/// transparent one shows as black in some viewers).
std::string svgTerminal(int w, int h)
{
	const double s = scaleOf(w);
	char buf[200];
	std::snprintf(buf, sizeof buf,
		"set terminal svg size %d,%d noenhanced font 'Sans,%.1f' linewidth %.2f background '#ffffff'", w, h,
		13.0 * s, s);
	return buf;
}
}  // namespace

void validateWidth(int width_px, const std::string& what)
{
	if (width_px < kMinWidthPx || width_px > kMaxWidthPx)
		throw ConfigError(what + " = " + std::to_string(width_px) + ": must be in [" +
						  std::to_string(kMinWidthPx) + ", " + std::to_string(kMaxWidthPx) + "]");
}

const std::array<const char*, 12>& seriesColours()
{
	static const std::array<const char*, 12> colours = {"#e6194b", "#3cb44b", "#4363d8", "#f58231",
		"#911eb4", "#42d4f4", "#f032e6", "#469990", "#9a6324", "#000075", "#808000", "#a9a9a9"};
	return colours;
}

const char* seriesColour(std::size_t i) { return seriesColours()[i % seriesColours().size()]; }

std::string quoted(const std::string& text)
{
	std::string q = "'";
	for (const char c : text)
	{
		if (c == '\'')
			q += "''";
		else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
			q += ' ';
		else
			q += c;
	}
	return q + "'";
}

std::string number(double v)
{
	if (!std::isfinite(v)) return "NaN";
	char buf[32];
	std::snprintf(buf, sizeof buf, "%.9g", v);
	return buf;
}

void DataBlock::row(std::initializer_list<double> values)
{
	if (broken_) text_ += '\n';
	broken_ = false;
	bool first = true;
	for (const double v : values)
	{
		if (!first) text_ += ' ';
		text_ += number(v);
		first = false;
	}
	text_ += '\n';
	++rows_;
}

Figure::Figure(int width_px, int height_px) : width_px_(width_px), height_px_(height_px) {}

std::string Figure::add(const DataBlock& block)
{
	const std::string name = "$d" + std::to_string(blocks_++);
	data_ += name + " << EOD\n" + block.text() + "EOD\n";
	return name;
}

void Figure::command(const std::string& commands) { commands_ += commands + "\n"; }

std::string Figure::script(const std::string& png_path, const std::string& svg_path) const
{
	std::string s = data_;
	s += pngTerminal(width_px_, height_px_) + "\nset output " + quoted(png_path) + "\n";
	s += commands_ + "unset multiplot\nunset output\nreset\n";
	s += svgTerminal(width_px_, height_px_) + "\nset output " + quoted(svg_path) + "\n";
	s += commands_ + "unset multiplot\nunset output\n";
	return s;
}

std::string plotCommand(const std::vector<std::string>& clauses)
{
	if (clauses.empty()) return "plot 1e300 notitle";
	std::string plot = "plot ";
	for (std::size_t i = 0; i < clauses.size(); ++i) plot += (i ? ", \\\n  " : "") + clauses[i];
	return plot;
}

std::string vectorPathOf(const std::string& png_path)
{
	return std::filesystem::path(png_path).replace_extension(".svg").string();
}

namespace
{
/// A PNG ends with its IEND chunk, an SVG with </svg> (and a line end): a
/// renderer that stopped half-way is caught here, not by the reader.
bool complete(const std::string& bytes, const std::string& trailer, std::size_t slack)
{
	const std::size_t at = bytes.rfind(trailer);
	return at != std::string::npos && at + trailer.size() + slack >= bytes.size();
}
}  // namespace

void writeFigure(const Figure& figure, const std::string& png_path)
{
	const std::string svg_path = vectorPathOf(png_path);
	const std::vector<std::string> files =
		runGnuplot(figure.script(gnuplotOutput(0), gnuplotOutput(1)), 2, png_path);
	if (!complete(files[0], std::string("IEND\xae\x42\x60\x82", 8), 0))
		throw InputError(png_path + ": gnuplot wrote an incomplete PNG");
	if (!complete(files[1], "</svg>", 2)) throw InputError(svg_path + ": gnuplot wrote an incomplete SVG");
	writeBytesAtomically(png_path, files[0]);
	try
	{
		writeBytesAtomically(svg_path, files[1]);
	}
	catch (...)
	{
		// Both or neither: the PNG this call just put in place is taken back.
		std::error_code ec;
		std::filesystem::remove(png_path, ec);
		throw;
	}
}

}  // namespace esif::plot

namespace esif::plot
{
std::string textDefaults()
{
	return "set title textcolor rgb '" + std::string(kTextColour) + "'\n"
		   "set xlabel textcolor rgb '" + std::string(kTextColour) + "'\n"
		   "set ylabel textcolor rgb '" + std::string(kTextColour) + "'\n"
		   "set tics textcolor rgb '" + std::string(kTextColour) + "'\n"
		   "set key textcolor rgb '" + std::string(kTextColour) + "'";
}

std::string multiplotTitle(const std::string& title, const std::string& layout)
{
	return "set multiplot " + (layout.empty() ? "" : "layout " + layout + " ") + "title " + quoted(title) +
		   " textcolor rgb '" + kTextColour + "'";
}

std::string chartDefaults()
{
	return textDefaults() + "\n"
		   "set grid xtics ytics lc rgb '#dddddd' lw 1 dt 1\n"
		   "set border 3 lc rgb '#808080'\n"
		   "set tics nomirror\n"
		   "set key top right opaque box lc rgb '#bbbbbb' samplen 2 spacing 1.1\n"
		   "set style fill transparent solid 1.0 noborder";
}

std::string tint(const std::string& colour, double amount)
{
	unsigned r = 0, g = 0, b = 0;
	if (colour.size() != 7 || std::sscanf(colour.c_str(), "#%2x%2x%2x", &r, &g, &b) != 3) return "#dddddd";
	const auto mix = [&](unsigned c) { return static_cast<unsigned>(std::lround(c + (255.0 - c) * amount)); };
	char buf[8];
	std::snprintf(buf, sizeof buf, "#%02x%02x%02x", mix(r), mix(g), mix(b));
	return buf;
}

std::string twoLines(const std::string& first, const std::string& second)
{
	return quoted(first) + ".\"\\n\"." + quoted(second);
}

std::string withBookFigure(const std::string& title, const std::string& book_figure)
{
	return book_figure.empty() ? title : title + "  (cf. book " + book_figure + ")";
}

}  // namespace esif::plot
