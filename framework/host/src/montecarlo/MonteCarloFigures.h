#pragma once
/// \file MonteCarloFigures.h
/// The figures of a Monte Carlo campaign, drawn with the host's line
/// charts (FigureWriter.h), each written atomically:
///   anees_pose.png      pose ANEES over steps, one line per config, log scale,
///                       the 95% chi-square bounds shaded (Bailey et al. 2006, Fig. 3)
///   rmse.png            position and heading RMSE over runs per step, with
///                       one config the 10-90 % spread of its position error shaded
///   landmark_anees.png  final ANEES of each landmark (by ID), log scale, bounds shaded

#include <esif/eval/MonteCarloStatistics.h>

#include <string>
#include <vector>

namespace esif
{
void writeMonteCarloFigures(
	const std::vector<ConfigStatistics>& configs, const std::string& title, const std::string& dir, int width_px);

}  // namespace esif
