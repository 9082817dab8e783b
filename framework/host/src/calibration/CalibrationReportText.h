#pragma once
/// \file CalibrationReportText.h
/// The text `esif calibrate` prints and writes as the calibration file's
/// comment: the fitted values beside the rawlog's, the innovation figures
/// and the checks against the reference.

#include <esif/calibration/Calibration.h>

#include <string>

namespace esif
{
std::string calibrationReportText(const CalibrationReport& report, const NoiseFitSettings& settings);
}
