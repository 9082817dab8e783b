#pragma once
/// \file G2oExport.h
/// `esif export g2o`: a rawlog's full-SLAM problem written for g2o or GTSAM
/// (G2oFormat.h), its initial values from dead reckoning or from a run folder.

#include <esif/formats/G2oFormat.h>

#include <optional>
#include <string>

namespace esif
{
struct G2oExportRequest
{
	std::string rawlog_path;
	/// A run folder of the same rawlog: its associations.txt gives every
	/// measurement's landmark ID (as `esif run --associations-from` uses it,
	/// so the IDs are those of its landmarks.txt), and its trajectory.tum and
	/// landmarks.txt the initial values.
	std::optional<std::string> run_dir;
	std::string out_path;
	G2oLandmarkEdge landmark_edge = G2oLandmarkEdge::PointXY;
};

struct G2oExportSummary
{
	std::size_t poses = 0;
	std::size_t landmarks = 0;
	std::size_t odometry_edges = 0;
	std::size_t landmark_edges = 0;
	std::size_t measurements_without_id = 0;
};

/// Throws InputError (one line naming the file, step or measurement) for an
/// unreadable rawlog or run folder, a rawlog whose measurements carry no
/// landmark ID and no run folder to give them, or a problem g2o cannot
/// express (G2oFormat.h).
G2oExportSummary exportG2o(const G2oExportRequest& request);

}  // namespace esif
