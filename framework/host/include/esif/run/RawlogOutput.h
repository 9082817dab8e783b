#pragma once
/// \file RawlogOutput.h
/// What `esif simulate` and `esif import` write for --out NAME.rawlog: the
/// rawlog and the ground truth beside it (NAME_ground_truth.txt,
/// NAME_ground_truth_robot_path.txt, NAME_ground_truth_measurement_ids.txt),
/// one file set (FileSet.h): a file at any of those names is replaced only
/// when esif wrote it as part of such a set, and the files are committed
/// together, so a rawlog never stands beside another one's ground truth.
/// A writer that leaves a ground-truth file out (an importer of data without
/// truth) removes the previous set's file of that name.

#include <esif/formats/GroundTruth.h>
#include <esif/safeio/FileSet.h>
#include <esif/formats/MeasurementTruth.h>

#include <string>
#include <vector>

namespace esif
{
/// The kind of the set, as its record names it.
inline constexpr const char* kRawlogOutputKind = "a rawlog and its ground truth";

/// The set's files for --out `rawlog`, the rawlog first.
inline std::vector<std::string> rawlogOutputFiles(const std::string& rawlog)
{
	const std::string prefix = groundTruthPrefixFor(rawlog);
	std::vector<std::string> files{rawlog};
	for (const auto& f : groundTruthFilesOf(prefix)) files.push_back(f);
	files.push_back(measurementTruthFileOf(prefix));
	return files;
}

/// Writes the set: `write(staged_rawlog)` writes the rawlog at that path and
/// its ground truth beside it (groundTruthPrefixFor of that path), as the
/// simulator and importers do; none of the files may overlap `inputs`.
template <class Write>
auto writeRawlogOutput(const std::string& rawlog, const std::vector<NamedInput>& inputs, Write&& write)
{
	return writeFileSet(kRawlogOutputKind, rawlogOutputFiles(rawlog), inputs, [&](const FileSet& set) {
		return write(set.staging(rawlog));
	});
}

}  // namespace esif
