#pragma once
/// \file FigureCanvas.h
/// Private helpers of the figure writers (FigureWriter.cpp): MRPT bitmap
/// fonts, text, round axis ticks, size checks and the atomic PNG save.
/// Header-only, like MapGeometry.h.

#include <esif/core/Errors.h>
#include <esif/safeio/AtomicFile.h>

#include "MapGeometry.h"

#include <mrpt/img/CImage.h>
#include <mrpt/img/TColor.h>

#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

namespace esif::figure_canvas
{
using mrpt::img::TColor;

const TColor kBackground(255, 255, 255);
const TColor kInk(0, 0, 0);	 ///< matrix non-zeros, axes
const TColor kTextColor(40, 40, 40);
const TColor kMutedTextColor(110, 110, 110);
const TColor kFrameColor(170, 170, 170);
const TColor kGridColor(232, 232, 232);

/// Smallest and largest accepted figure size [px].
constexpr int kMinSizePx = 200;
constexpr int kMaxSizePx = 16384;

/// Throws ConfigError when `value` (named `what`) is outside [kMinSizePx, kMaxSizePx].
inline void validateSize(const char* what, int value)
{
	if (value < kMinSizePx || value > kMaxSizePx)
		throw ConfigError(
			std::string(what) + " = " + std::to_string(value) + ": must be in [" + std::to_string(kMinSizePx) +
			", " + std::to_string(kMaxSizePx) + "]");
}

/// One of MRPT's CCanvas bitmap fonts with its cell size.
struct Font
{
	const char* name;
	int w;	///< character cell width [px]
	int h;	///< character cell height [px]
};
constexpr Font kFontLarge{"10x20", 10, 20};
constexpr Font kFontMedium{"9x15", 9, 15};
constexpr Font kFontSmall{"6x13", 6, 13};
constexpr Font kFontTiny{"5x7", 5, 7};

inline int textWidth(const std::string& s, const Font& font) { return static_cast<int>(s.size()) * font.w; }

/// The first of `fonts` (largest first) in which `s` fits into `width_px`;
/// the last one when none does.
inline Font fittingFont(const std::string& s, int width_px, std::initializer_list<Font> fonts)
{
	for (const Font& f : fonts)
		if (textWidth(s, f) <= width_px) return f;
	return *(fonts.end() - 1);
}

/// `s` broken at spaces into lines at most `width_px` wide in `font` (a
/// word longer than that gets a line of its own).
inline std::vector<std::string> wrapText(const std::string& s, const Font& font, int width_px)
{
	std::vector<std::string> lines;
	std::string line, word;
	std::istringstream words(s);
	while (words >> word)
	{
		const std::string longer = line.empty() ? word : line + " " + word;
		if (!line.empty() && textWidth(longer, font) > width_px)
		{
			lines.push_back(line);
			line = word;
		}
		else
			line = longer;
	}
	if (!line.empty()) lines.push_back(line);
	return lines;
}

/// MRPT unpacks its bitmap fonts on the first selectTextFont() without a
/// lock (init_fonts_list in CCanvas.cpp), and figures are drawn beside other
/// outputs (host OutputJobs.h): the first unpacking happens once, here.
/// Later selections only look the font up.
inline void loadFontsOnce()
{
	static std::once_flag once;
	std::call_once(once, [] {
		mrpt::img::CImage probe(1, 1, mrpt::img::CH_RGB);
		probe.selectTextFont("9x15");
	});
}

/// Text with its top-left corner at (x, y).
inline void text(mrpt::img::CImage& img, int x, int y, const std::string& s, const Font& font, const TColor& color)
{
	loadFontsOnce();
	img.selectTextFont(font.name);
	img.textOut(x, y, s, color);
}

/// Text centred horizontally on `cx`, top at `y`.
inline void centredText(
	mrpt::img::CImage& img, int cx, int y, const std::string& s, const Font& font, const TColor& color)
{
	text(img, cx - textWidth(s, font) / 2, y, s, font, color);
}

/// A white image of the given size (CImage(w, h) is uninitialised).
inline mrpt::img::CImage blankImage(int width, int height)
{
	mrpt::img::CImage img(width, height, mrpt::img::CH_RGB);
	img.filledRectangle(0, 0, width - 1, height - 1, kBackground);
	return img;
}

/// Sets one pixel, without bounds checks beyond the caller's.
inline void putPixel(mrpt::img::CImage& img, int x, int y, const TColor& c)
{
	auto* px = img.ptr<uint8_t>(static_cast<unsigned>(x), static_cast<unsigned>(y));  // B, G, R
	px[0] = c.B;
	px[1] = c.G;
	px[2] = c.R;
}

/// Round tick values (multiples of 1, 2 or 5 times a power of ten) in [0,
/// top], about `target_count` intervals, 0 included.
inline std::vector<double> niceTicks(double top, double target_count)
{
	const double step = map_geometry::niceStep(top, target_count);
	std::vector<double> ticks;
	for (int k = 0; k <= 1000 && k * step <= top * (1 + 1e-9); ++k) ticks.push_back(k * step);
	return ticks;
}

/// A tick value as a label: "0", "0.5", "12", "1500".
inline std::string tickLabel(double v)
{
	char buf[32];
	std::snprintf(buf, sizeof(buf), "%g", std::abs(v) < 1e-12 ? 0.0 : v);
	return buf;
}

/// Saves `img` as PNG at `path` atomically; throws InputError naming `path`.
inline void savePngAtomically(const mrpt::img::CImage& img, const std::string& path)
{
	// Encoded in memory by OpenCV (what CImage::saveToFile calls with the
	// file name), then written with every step checked: imwrite leaves a
	// truncated file on a full disk without saying so.
	std::vector<uchar> png;
	if (!cv::imencode(".png", img.asCvMatRef(), png) || png.empty())
		throw InputError(path + ": cannot encode PNG image");
	writeBytesAtomically(path, std::string(png.begin(), png.end()));
}

}  // namespace esif::figure_canvas
