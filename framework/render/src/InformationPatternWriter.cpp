/// \file InformationPatternWriter.cpp
/// info_matrix.png (book Fig. 3.12-3.13, 4.13, 5.10): where the information
/// matrix and its Cholesky factor are non-zero, black on white.

#include <esif/render/FigureWriter.h>

#include "PlotScript.h"

#include <algorithm>
#include <string>
#include <vector>

namespace esif
{
namespace
{
using Sparse = Eigen::SparseMatrix<double>;

/// A matrix is shown in at most size_px / kPixelsPerCell cells a side: every
/// cell is then at least 4 pixels of the plot (its centre pixel is all its
/// own, whatever the antialiasing), no entry vanishes, and a figure holds at
/// most a few ten thousand boxes however large the matrix.
constexpr int kPixelsPerCell = 6;

long long cellsFor(long long n, int size_px) { return std::min<long long>(n, size_px / kPixelsPerCell); }

long long squareSize(const Sparse& m) { return std::max<long long>(m.rows(), m.cols()); }

/// Entries != 0 (a NaN counts: it is a non-zero gone wrong).
std::size_t nonZeroCount(const Sparse& m)
{
	std::size_t nz = 0;
	for (Eigen::Index k = 0; k < m.outerSize(); ++k)
		for (Sparse::InnerIterator it(m, k); it; ++it) nz += it.value() != 0.0;
	return nz;
}

std::string informationTitle(const Sparse& m)
{
	return "information matrix " + std::to_string(m.rows()) + "x" + std::to_string(m.cols()) +
		   ", nz = " + std::to_string(nonZeroCount(m));
}

/// The factor's own name when its order names it (e.g. "incomplete
/// Cholesky preconditioner, ..."), else "Cholesky factor (<order>)".
std::string factorTitle(const InformationPattern& p)
{
	const std::string nz = ", nz = " + std::to_string(nonZeroCount(p.factor));
	if (p.factor_order.find("Cholesky") != std::string::npos) return p.factor_order + nz;
	return "Cholesky factor" + (p.factor_order.empty() ? "" : " (" + p.factor_order + ")") + nz;
}

/// The cells (row, column) of `m` in cells x cells that hold a non-zero
/// entry, one row each. Only those are drawn (as filled boxes): gnuplot's
/// "matrix with image" of every cell costs half a second for two panels.
plot::DataBlock occupiedCells(const Sparse& m, long long cells)
{
	const long long n = squareSize(m);
	std::vector<char> full(static_cast<std::size_t>(cells * cells), 0);
	for (Eigen::Index k = 0; k < m.outerSize(); ++k)
		for (Sparse::InnerIterator it(m, k); it; ++it)
			if (it.value() != 0.0)
				full[static_cast<std::size_t>(it.row() * cells / n * cells + it.col() * cells / n)] = 1;
	plot::DataBlock block;
	for (long long i = 0; i < cells; ++i)
		for (long long j = 0; j < cells; ++j)
			if (full[static_cast<std::size_t>(i * cells + j)]) block.row({double(i), double(j)});
	return block;
}

/// One matrix as an image in matrix coordinates (row 0 at the top).
void addMatrixPanel(plot::Figure& fig, const Sparse& m, const std::string& title, int size_px)
{
	const long long n = squareSize(m);
	fig.command("set title " + plot::quoted(title));
	if (n == 0)
	{
		fig.command("set xrange [0:1]\nset yrange [1:0]\nset label 1 'empty' at graph 0.5,0.5 center\nplot 2 notitle\nunset label 1");
		return;
	}
	const long long cells = cellsFor(n, size_px);
	const double scale = static_cast<double>(n) / static_cast<double>(cells);
	fig.command("set xrange [0:" + std::to_string(n) + "]\nset yrange [" + std::to_string(n) + ":0]");
	const plot::DataBlock occupied = occupiedCells(m, cells);
	// Cell (i, j) covers columns [j, j + 1) * scale and rows [i, i + 1) * scale.
	const std::string s = plot::number(scale);
	std::vector<std::string> clauses;
	if (!occupied.empty())
		clauses.push_back(fig.add(occupied) + " using (($2+0.5)*" + s + "):(($1+0.5)*" + s + "):($2*" + s + "):(($2+1)*" +
						  s + "):($1*" + s + "):(($1+1)*" + s + ") with boxxy fs solid 1.0 noborder lc rgb 'black' notitle");
	fig.command(plot::plotCommand(clauses));
}
}  // namespace

void writeInformationPatternImage(const InformationPattern& p, const std::string& path, int size_px)
{
	plot::validateWidth(size_px, "image_size_px");
	const bool with_factor = p.factor.size() > 0;
	plot::Figure fig(size_px * (with_factor ? 2 : 1), size_px);
	fig.command(plot::textDefaults());
	fig.command("set border 15 lc rgb '#808080'");
	fig.command("set size ratio -1\nset tics out nomirror\nset xtics format '%.0f'\nset ytics format '%.0f'");
	fig.command(plot::multiplotTitle(plot::withBookFigure("non-zeros", "Fig. 3.12-3.13, 4.13, 5.10"),
		with_factor ? "1,2" : "1,1"));
	addMatrixPanel(fig, p.information, informationTitle(p.information), size_px);
	if (with_factor) addMatrixPanel(fig, p.factor, factorTitle(p), size_px);
	plot::writeFigure(fig, path);
}

}  // namespace esif
