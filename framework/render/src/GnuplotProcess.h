#pragma once
/// \file GnuplotProcess.h
/// Runs gnuplot on a script: the one place esif's figures leave the process.
/// gnuplot (Debian's gnuplot-nox) draws every figure: the PNG with its cairo
/// terminal, the SVG with its own writer, from one script.

#include <string>
#include <vector>

namespace esif::plot
{
/// Where a script sends its output file `index` (0, 1, ...): gnuplot writes
/// it into memory that runGnuplot() hands back, and esif writes the file
/// itself, checked and atomically like every other output.
std::string gnuplotOutput(int index);

/// Runs `gnuplot -d` (no user init file: a ~/.gnuplot must not change our
/// figures) with `script` on its standard input, waits for it and returns
/// the bytes of each of its `outputs` output files. Throws InputError naming
/// `figure_path` with gnuplot's first error line when it cannot be started,
/// does not exit with 0, or leaves an output empty. Safe to call from
/// several threads at once.
std::vector<std::string> runGnuplot(const std::string& script, int outputs, const std::string& figure_path);

}  // namespace esif::plot
