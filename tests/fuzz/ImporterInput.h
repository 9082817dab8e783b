#pragma once
/// \file ImporterInput.h
/// Fuzz inputs for the dataset importers. Victoria Park: the input is the
/// dataset file. MRCLAM: a valid synthetic recording of robot 1 is kept (two
/// landmarks, a robot, an unknown barcode, ten seconds of commands); the
/// first input byte picks which of its five files the rest replaces, so each
/// reader is reached with the others readable. Either the import writes its
/// rawlog and ground truth, or it fails with one line naming the file.
/// Used by fuzz_vicpark_importer, fuzz_mrclam_importer and test_FuzzRegressions.

#include "FuzzSupport.h"

#include <esif/formats/MrclamImporter.h>
#include <esif/formats/VictoriaParkImporter.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace esif::fuzz
{
inline Verdict victoriaParkVerdict(const std::string& input)
{
	const std::string path = fileIn("vp.txt");
	writeFile(path, input.data(), input.size());
	return verdictOf(path, [&] { importVictoriaPark(path, fileIn("vp.rawlog"), {}); });
}

namespace mrclam_input
{
/// The valid recording's files, by name in the recording folder.
inline const std::vector<std::pair<std::string, std::string>>& validFiles()
{
	static const std::vector<std::pair<std::string, std::string>> files = {
		{"Barcodes.dat", "# Subject # Barcode #\n1 5\n2 14\n6 63\n7 81\n"},
		{"Landmark_Groundtruth.dat", "# Subject # x y std_x std_y\n6 1.0 2.0 0.001 0.001\n7 3.0 -1.0 0.001 0.001\n"},
		{"Robot1_Odometry.dat", "# Time v w\n100.0 0.1 0.0\n102.0 0.1 0.05\n104.0 0.1 0.0\n106.0 0.0 0.0\n"},
		{"Robot1_Measurement.dat",
		 "# Time barcode range bearing\n101.0 63 2.0 0.5\n101.0 81 3.0 -0.2\n101.0 14 1.5 0.0\n103.0 43 2.0 0.0\n"
		 "104.0 63 1.5 0.6\n"},
		{"Robot1_Groundtruth.dat", "# Time x y theta\n99.0 0.0 0.0 0.0\n107.0 0.7 0.1 0.05\n"},
	};
	return files;
}

inline std::string folder() { return fileIn("mrclam"); }

inline void restore(const std::pair<std::string, std::string>& file)
{
	writeFile(folder() + "/" + file.first, file.second.data(), file.second.size());
}

inline void setUp()
{
	static const bool done = [] {
		std::filesystem::create_directories(folder());
		for (const auto& f : validFiles()) restore(f);
		return true;
	}();
	(void)done;
}
}  // namespace mrclam_input

inline Verdict mrclamVerdict(const std::string& input)
{
	using namespace mrclam_input;
	if (input.empty()) return {};
	setUp();
	const auto& target = validFiles()[static_cast<unsigned char>(input[0]) % validFiles().size()];
	const std::string path = folder() + "/" + target.first;
	writeFile(path, input.data() + 1, input.size() - 1);
	// One line naming a file of the recording (the one replaced, or another
	// that no longer agrees with it), or an import.
	const Verdict verdict = verdictOf(folder(), [&] { importMrclam(folder(), fileIn("mrclam.rawlog"), {}); });
	restore(target);
	return verdict;
}
}  // namespace esif::fuzz
