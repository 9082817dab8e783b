#pragma once
/// \file GroundTruthInput.h
/// One fuzz input for the readers of a rawlog's side files. The first input
/// byte picks one, the rest is its content: the ground-truth landmarks, the
/// robot path (beside valid landmarks), the measurement IDs of a 1000-step
/// rawlog, or associations.txt of a 100-step rawlog. Each must read or fail
/// with one line naming its file. Used by fuzz_ground_truth_reader and
/// test_FuzzRegressions.

#include "FuzzSupport.h"

#include <esif/formats/AssociationFile.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/MeasurementTruth.h>

#include <string>

namespace esif::fuzz
{
inline Verdict groundTruthVerdict(const std::string& input)
{
	if (input.empty()) return {};
	const std::string content = input.substr(1);
	switch (static_cast<unsigned char>(input[0]) % 4)
	{
		case 0:
		{
			const std::string prefix = fileIn("landmarks");
			writeFile(prefix + "_ground_truth.txt", content.data(), content.size());
			return verdictOf(prefix + "_ground_truth.txt", [&] { loadGroundTruth(prefix); });
		}
		case 1:
		{
			const std::string prefix = fileIn("path");
			const std::string landmarks = "1.0 2.0 0 5 0 0 7\n";
			writeFile(prefix + "_ground_truth.txt", landmarks.data(), landmarks.size());
			writeFile(prefix + "_ground_truth_robot_path.txt", content.data(), content.size());
			return verdictOf(prefix + "_ground_truth_robot_path.txt", [&] {
				if (const auto truth = loadGroundTruth(prefix)) truth->inInitialPoseFrame();
			});
		}
		case 2:
		{
			const std::string prefix = fileIn("ids");
			writeFile(measurementTruthFileOf(prefix), content.data(), content.size());
			return verdictOf(measurementTruthFileOf(prefix), [&] { loadMeasurementTruth(prefix, 1000); });
		}
		default:
		{
			const std::string path = fileIn("associations.txt");
			writeFile(path, content.data(), content.size());
			return verdictOf(path, [&] { readAssociationFile(path, 100); });
		}
	}
}
}  // namespace esif::fuzz
