/// \file TrajectoryWriter.cpp
/// trajectory.tum: the filtered path in the TUM RGB-D format
/// (`timestamp x y z qx qy qz qw`), which evo and most SLAM benchmarks read.
/// MRPT 2.5.8 has no TUM writer (saveToTextFile_TUM came in 2.11).

#include <esif/formats/MapWriter.h>
#include <esif/safeio/AtomicFile.h>

#include <esif/formats/NumberText.h>

#include <cmath>
#include <string>

namespace esif
{
void writeTrajectoryTum(const std::vector<TrajectoryPoint>& trajectory, const std::string& path)
{
	// '#' lines are comments for the TUM tools and for evo.
	std::string text = "# esif trajectory (TUM): timestamp x y z qx qy qz qw\n";
	text.reserve(text.size() + 96 * trajectory.size());
	for (const TrajectoryPoint& p : trajectory)
	{
		// Planar pose: rotation about z only, q = (0, 0, sin(yaw/2), cos(yaw/2)).
		// The yaw is wrapped first so that qw >= 0, the usual sign choice.
		const double yaw = std::atan2(std::sin(p.pose.mean(2)), std::cos(p.pose.mean(2)));
		const double values[] = {p.time_s, p.pose.mean.x(), p.pose.mean.y(), 0.0, 0.0, 0.0, std::sin(0.5 * yaw),
								 std::cos(0.5 * yaw)};
		bool first = true;
		for (const double v : values)
		{
			if (!first) text += ' ';
			first = false;
			number_text::append(text, v);
		}
		text += '\n';
	}
	writeTextAtomically(path, text);
}

}  // namespace esif
