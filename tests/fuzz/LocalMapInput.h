#pragma once
/// \file LocalMapInput.h
/// One fuzz input for the local-map folder readers (LocalMapFiles.h). A
/// valid folder of two maps with links, ground truth and a reference result
/// is kept; the first input byte picks the file the rest of the input
/// replaces, so every reader of the format is reached from a folder that is
/// otherwise readable. The folder must read, or fail with one line naming
/// that file. Used by fuzz_localmap_reader and test_FuzzRegressions.

#include "FuzzSupport.h"

#include <esif/formats/LocalMapFiles.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace esif::fuzz
{
namespace localmap_input
{
/// Map k of one feature (ID 1), its end pose and identity information.
inline std::string mapText(int k)
{
	std::string text = std::to_string(k - 1) + "\n5\n";
	for (const char* v : {"1.5", "0.25", "0.1"}) text += "-" + std::to_string(k) + " " + v + "\n";
	text += "1 2.0\n1 -1.0\n";
	for (int r = 0; r < 5; ++r)
	{
		for (int c = 0; c < 5; ++c) text += std::string(c ? " " : "") + (r == c ? "1" : "0");
		text += "\n";
	}
	return text;
}

/// The valid files, by path relative to the private folder.
inline const std::vector<std::pair<std::string, std::string>>& validFiles()
{
	static const std::vector<std::pair<std::string, std::string>> files = {
		{"maps/localmap_1.txt", mapText(1)},
		{"maps/localmap_2.txt", mapText(2)},
		{"maps/links.txt", "2 1.5 0.25 0.1 0.01 0 0 0.01 0 0.001\n"},
		{"maps/ground_truth_landmarks.txt", "1 2 -1\n"},
		{"maps/ground_truth_end_poses.txt", "1 1.5 0.25 0.1\n2 3 0.5 0.2\n"},
		{"ref/feature.txt", "1 2 -1\n"},
		{"ref/pose.txt", "1 1.5 0.25 0.1\n2 3 0.5 7.1\n"},
	};
	return files;
}

inline void restore(const std::pair<std::string, std::string>& file)
{
	writeFile(fileIn(file.first), file.second.data(), file.second.size());
}

inline void setUp()
{
	static const bool done = [] {
		std::filesystem::create_directories(fileIn("maps"));
		std::filesystem::create_directories(fileIn("ref"));
		for (const auto& f : validFiles()) restore(f);
		return true;
	}();
	(void)done;
}
}  // namespace localmap_input

/// What the readers make of one input.
inline Verdict localMapVerdict(const std::string& input)
{
	using namespace localmap_input;
	if (input.empty()) return {};
	setUp();
	const auto& target = validFiles()[static_cast<unsigned char>(input[0]) % validFiles().size()];
	const std::string path = fileIn(target.first);
	writeFile(path, input.data() + 1, input.size() - 1);
	const bool reference = target.first.rfind("ref/", 0) == 0;
	const Verdict verdict = verdictOf(path, [&] {
		if (reference)
			readReferenceResult(fileIn("ref"), 2);
		else
			readLocalMapFolder(fileIn("maps"));
	});
	restore(target);
	return verdict;
}
}  // namespace esif::fuzz
