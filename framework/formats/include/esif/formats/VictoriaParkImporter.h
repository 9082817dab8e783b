#pragma once
/// \file VictoriaParkImporter.h
/// Converts the pre-processed Victoria Park text dataset (GTSAM's copy: lines
/// `ODOMETRY i j dx dy dtheta c11 c12 c13 c22 c23 c33` and
/// `LANDMARK i l x y c11 c12 c22`, see shared/data/victoria_park/README.md)
/// into an MRPT actions/sensory-frames rawlog. Book Sec. 3.6.2, 4.7, 5.6.

#include <string>

namespace esif
{
struct VictoriaParkImportOptions
{
	bool keep_ids = true;  ///< keep the landmark IDs (known data association)
	/// The file's x-y covariance (0.4 m^2) poorly models the laser tree
	/// detector; range-bearing noise is set here instead.
	double std_range_m = 0.5;
	double std_bearing_deg = 2.0;
	double max_range_m = 30.0;	///< sensor range stored in the observations (longest record: 20.7 m)
	double fov_deg = 180.0;	 ///< field of view stored in the observations
	double dt_s = 0.2;	///< nominal time between poses (the file has no timestamps)
};

struct VictoriaParkImportSummary
{
	std::size_t poses = 0;
	std::size_t measurements = 0;
	std::size_t landmark_ids = 0;
};

/// Reads `in_path` and writes `out_rawlog` atomically. Throws InputError
/// naming the file and line for a malformed or out-of-order record.
VictoriaParkImportSummary importVictoriaPark(
	const std::string& in_path, const std::string& out_rawlog, const VictoriaParkImportOptions& options);

}  // namespace esif
