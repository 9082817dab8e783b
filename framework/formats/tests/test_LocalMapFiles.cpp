#include <EsifTestSupport.h>

#include <esif/core/Errors.h>
#include <esif/formats/LocalMapFiles.h>
#include <esif/localmaps/LocalMapBuild.h>

#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>
#include <unistd.h>

namespace
{
using namespace esif;
namespace fs = std::filesystem;

// ------------------------------------------------------------------ helpers

/// An exactly symmetric, well-conditioned n x n matrix with "long" entries
/// (so %.17g has every digit to keep), different for each `seed`.
Eigen::MatrixXd spdMatrix(int n, int seed)
{
	Eigen::MatrixXd m(n, n);
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j)
			m(i, j) = i == j ? 10.0 + i + 1.0 / (3 + seed) : std::sin(1.0 + seed + i + j) / (1.0 + i + j);
	return m;
}

LocalMap makeMap(std::size_t k, const std::vector<std::pair<LandmarkId, Eigen::Vector2d>>& features)
{
	LocalMap map;
	map.index = k;
	map.end_pose = Pose2(1.0 / 3.0 * k, -std::sqrt(2.0) * k, 0.1 * M_PI * k - 1.0);
	for (const auto& [id, p] : features) map.features.push_back({id, p, false});
	map.information = spdMatrix(static_cast<int>(map.stateDim()), static_cast<int>(k));
	return map;
}

LocalMapFolder makeFolder()
{
	LocalMapFolder folder;
	folder.maps.push_back(makeMap(1, {{4, {1.0 / 7.0, 2.5e-17}}, {9, {-3.25, 1e10 / 3.0}}}));
	folder.maps.push_back(makeMap(2, {{9, {0.1, 0.2}}, {4, {M_PI, -M_E}}, {12, {5.0, -6.0 / 11.0}}}));
	folder.maps.push_back(makeMap(3, {{12, {7.0, 8.0}}, {13, {-1e-300, 1e300}}}));
	OdometryIncrement link;
	link.delta = Pose2(0.3, -0.02, 1.0 / 9.0);
	link.cov << 0.01, 1e-4 / 3, 0, 1e-4 / 3, 0.02, -1e-5, 0, -1e-5, 0.003;
	folder.maps[1].link = link;
	folder.truth_landmarks = std::map<LandmarkId, Eigen::Vector2d>{{4, {0.125, 1.0 / 3}}, {9, {2, -2}}, {77, {M_PI, 0}}};
	folder.truth_end_poses = std::map<std::size_t, Pose2>{{1, Pose2(1, 2, 0.5)}, {3, Pose2(-1, 1.0 / 7, 7.5)}};
	return folder;
}

void expectSameMaps(const LocalMapFolder& a, const LocalMapFolder& b)
{
	ASSERT_EQ(a.maps.size(), b.maps.size());
	for (std::size_t i = 0; i < a.maps.size(); ++i)
	{
		const auto &x = a.maps[i], &y = b.maps[i];
		EXPECT_EQ(x.index, y.index);
		EXPECT_EQ(x.end_pose, y.end_pose) << "map " << x.index;
		ASSERT_EQ(x.features.size(), y.features.size());
		for (std::size_t f = 0; f < x.features.size(); ++f)
		{
			EXPECT_EQ(x.features[f].id, y.features[f].id);
			EXPECT_EQ(x.features[f].position, y.features[f].position) << "map " << x.index << " feature " << f;
		}
		EXPECT_EQ(x.information, y.information) << "map " << x.index;
		ASSERT_EQ(x.link.has_value(), y.link.has_value());
		if (x.link)
		{
			EXPECT_EQ(x.link->delta, y.link->delta);
			EXPECT_EQ(x.link->cov, y.link->cov);
		}
	}
}

/// Expects `action` to throw one-line InputError naming `file:line` and `phrase`.
void expectErrorAt(const std::function<void()>& action, const std::string& file_line, const std::string& phrase)
{
	try
	{
		action();
		ADD_FAILURE() << "no error; expected " << file_line;
	}
	catch (const InputError& e)
	{
		const std::string what = e.what();
		EXPECT_NE(what.find(file_line + ":"), std::string::npos) << what;
		EXPECT_NE(what.find(phrase), std::string::npos) << what;
		EXPECT_EQ(what.find('\n'), std::string::npos) << what;
	}
}

/// The names in `dir` (to spot temporaries a failed write left behind).
std::vector<std::string> entriesOf(const std::string& dir)
{
	std::vector<std::string> out;
	for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
	return out;
}

void writeLines(const std::string& path, const std::vector<std::string>& lines)
{
	std::ofstream out(path);
	for (const auto& l : lines) out << l << "\n";
}

std::string g17(double v)
{
	char buf[32];
	std::snprintf(buf, sizeof(buf), "%.17g", v);
	return buf;
}

/// A valid localmap_2.txt as lines: 1 = Ref, 2 = N (7), 3-5 end pose,
/// 6-7 feature 5, 8-9 feature 9, 10-16 the matrix rows 1-7.
std::vector<std::string> goodMapLines()
{
	std::vector<std::string> l = {"1", "7", "-2 1.5", "-2 -0.25", "-2 0.75", "5 3.5", "5 4.5", "9 -1", "9 2"};
	const Eigen::MatrixXd m = spdMatrix(7, 2);
	for (int r = 0; r < 7; ++r)
	{
		std::string row;
		for (int c = 0; c < 7; ++c) row += (c ? " " : "") + g17(m(r, c));
		l.push_back(row);
	}
	return l;
}

/// Writes goodMapLines() changed by `edit` into a fresh folder and reads it as map 2.
void expectMapErrorAt(
	const std::function<void(std::vector<std::string>&)>& edit, int line, const std::string& phrase)
{
	test::TempDir dir;
	auto lines = goodMapLines();
	edit(lines);
	writeLines(dir.file("localmap_2.txt"), lines);
	SCOPED_TRACE("expected line " + std::to_string(line) + ": " + phrase);
	expectErrorAt(
		[&] { readLocalMapFile(dir.file("localmap_2.txt"), 2); }, "localmap_2.txt:" + std::to_string(line), phrase);
}

/// Sets the entry (r, c) (1-based) of the matrix rows of goodMapLines().
void setEntry(std::vector<std::string>& lines, int r, int c, const std::string& value)
{
	std::istringstream ss(lines[static_cast<std::size_t>(9 + r - 1)]);
	std::vector<std::string> toks;
	for (std::string t; ss >> t;) toks.push_back(t);
	toks[static_cast<std::size_t>(c - 1)] = value;
	std::string row;
	for (std::size_t i = 0; i < toks.size(); ++i) row += (i ? " " : "") + toks[i];
	lines[static_cast<std::size_t>(9 + r - 1)] = row;
}

/// A folder of two good maps (written by the writer) plus extra files.
std::string goodFolder(const test::TempDir& dir)
{
	LocalMapFolder folder;
	folder.maps.push_back(makeMap(1, {{4, {1, 2}}, {9, {3, 4}}}));
	folder.maps.push_back(makeMap(2, {{9, {1, 2}}, {4, {3, 4}}}));
	writeLocalMapFolder(folder, dir.file("maps"));
	return dir.file("maps");
}

// ------------------------------------------------------------------ round trip

TEST(LocalMapFiles, FolderRoundTripIsExact)
{
	test::TempDir dir;
	const auto folder = makeFolder();
	writeLocalMapFolder(folder, dir.file("maps"));
	EXPECT_EQ(entriesOf(dir.path()), std::vector<std::string>{"maps"});	 // no temporaries left

	const auto back = readLocalMapFolder(dir.file("maps"));
	expectSameMaps(folder, back);
	EXPECT_FALSE(back.maps[0].link);
	EXPECT_FALSE(back.maps[1].covariance);
	// in_earlier_maps from the earlier maps' ids: 9, 4 in map 2; 12 in map 3.
	EXPECT_EQ(back.maps[0].featuresInEarlierMaps(), 0u);
	EXPECT_EQ(back.maps[1].featuresInEarlierMaps(), 2u);
	EXPECT_FALSE(back.maps[1].features[2].in_earlier_maps);
	EXPECT_TRUE(back.maps[2].features[0].in_earlier_maps);
	EXPECT_FALSE(back.maps[2].features[1].in_earlier_maps);
	ASSERT_TRUE(back.truth_landmarks && back.truth_end_poses);
	EXPECT_EQ(*back.truth_landmarks, *folder.truth_landmarks);
	EXPECT_EQ(*back.truth_end_poses, *folder.truth_end_poses);

	// The authors' layout: Ref, N, "id value" lines, N rows of N numbers.
	std::istringstream text(test::readText(dir.file("maps/localmap_2.txt")));
	std::vector<std::string> lines;
	for (std::string l; std::getline(text, l);) lines.push_back(l);
	ASSERT_EQ(lines.size(), 2u + 2 * 9);
	EXPECT_EQ(lines[0], "1");
	EXPECT_EQ(lines[1], "9");
	EXPECT_EQ(lines[2], "-2 " + g17(folder.maps[1].end_pose.x()));
	EXPECT_EQ(lines[7], "4 " + g17(M_PI));
	EXPECT_EQ(lines[8], "4 " + g17(-M_E));
	EXPECT_EQ(test::readText(dir.file("maps/links.txt")).substr(0, 2), "2 ");
}

TEST(LocalMapFiles, SubnormalValuesRoundTrip)
{
	// %.17g writes them, so the reader must take them back (it refused them
	// once as "not a finite number").
	test::TempDir dir;
	auto folder = makeFolder();
	folder.maps[0].features[0].position.x() = std::numeric_limits<double>::denorm_min();
	folder.maps[0].information(0, 1) = folder.maps[0].information(1, 0) = 1e-310;
	folder.truth_landmarks->at(4).y() = -1e-320;
	writeLocalMapFolder(folder, dir.file("maps"));
	const auto back = readLocalMapFolder(dir.file("maps"));
	expectSameMaps(folder, back);
	EXPECT_EQ(*back.truth_landmarks, *folder.truth_landmarks);
}

TEST(LocalMapFiles, RewriteReplacesTheWholeFolder)
{
	test::TempDir dir;
	writeLocalMapFolder(makeFolder(), dir.file("maps"));
	LocalMapFolder smaller;
	smaller.maps.push_back(makeMap(1, {{4, {1, 2}}}));
	writeLocalMapFolder(smaller, dir.file("maps") + "/");  // trailing separator: same folder
	const auto back = readLocalMapFolder(dir.file("maps"));
	EXPECT_EQ(back.maps.size(), 1u);
	EXPECT_FALSE(back.truth_landmarks);
	EXPECT_FALSE(back.truth_end_poses);
	EXPECT_FALSE(fs::exists(dir.file("maps/links.txt")));
	EXPECT_EQ(entriesOf(dir.path()), std::vector<std::string>{"maps"});
}

TEST(LocalMapFiles, RoundOffAsymmetryIsAveragedAndPhiWrapped)
{
	test::TempDir dir;
	auto lines = goodMapLines();
	const Eigen::MatrixXd m = spdMatrix(7, 2);
	const double other = m(0, 2) * (1 + 1e-13);	// MATLAB-like round-off
	setEntry(lines, 1, 3, g17(other));
	lines[4] = "-2 " + g17(0.75 + 2 * M_PI);
	writeLines(dir.file("localmap_2.txt"), lines);
	const auto map = readLocalMapFile(dir.file("localmap_2.txt"), 2);
	EXPECT_EQ(map.information(0, 2), 0.5 * (other + m(2, 0)));
	EXPECT_EQ(map.information(2, 0), map.information(0, 2));
	EXPECT_NEAR(map.end_pose.z(), 0.75, 1e-15);
	EXPECT_EQ(map.end_pose.x(), 1.5);
	ASSERT_EQ(map.features.size(), 2u);
	EXPECT_EQ(map.features[1].id, 9);
	EXPECT_EQ(map.features[1].position, Eigen::Vector2d(-1, 2));
	EXPECT_FALSE(map.features[1].in_earlier_maps);
}

// ------------------------------------------------------------------ bad local-map files

TEST(LocalMapFiles, BadHeaderAndCounts)
{
	expectMapErrorAt([](auto& l) { l[0] = "3"; }, 1, "Ref 3, expected 1");
	expectMapErrorAt([](auto& l) { l[0] = "one"; }, 1, "not an integer");
	expectMapErrorAt([](auto& l) { l[0] = "1 2"; }, 1, "extra values");
	expectMapErrorAt([](auto& l) { l[1] = "7.0"; }, 2, "not an integer");
	expectMapErrorAt([](auto& l) { l[1] = "6"; }, 2, "N = 6");
	expectMapErrorAt([](auto& l) { l[1] = "9"; }, 17, "file ends early");
	expectMapErrorAt([](auto& l) { l[1] = "5"; }, 13, "too many lines");
	expectMapErrorAt([](auto& l) { l.pop_back(); }, 16, "file ends early");
	expectMapErrorAt([](auto& l) { l.push_back("0"); }, 17, "too many lines");
	expectMapErrorAt([](auto& l) { l.resize(1); }, 2, "file ends early");
	expectMapErrorAt([](auto& l) { l.clear(); }, 1, "file ends early");
}

TEST(LocalMapFiles, BadStateLines)
{
	expectMapErrorAt([](auto& l) { l[3] = "-2 abc"; }, 4, "column 2 (value) = 'abc': not a number");
	expectMapErrorAt([](auto& l) { l[3] = "-2 nan"; }, 4, "not a finite number");
	expectMapErrorAt([](auto& l) { l[3] = "-2 1e999"; }, 4, "not a finite number");
	expectMapErrorAt([](auto& l) { l[3] = "-2.0 1"; }, 4, "not an integer");
	expectMapErrorAt([](auto& l) { l[5] = "5 1.0 2.0"; }, 6, "extra values");
	expectMapErrorAt([](auto& l) { l[5] = ""; }, 6, "empty line");
	expectMapErrorAt([](auto& l) { l[4] = "-3 0.1"; }, 5, "expected -2");
	expectMapErrorAt([](auto& l) { l[6] = "6 4.5"; }, 7, "expected 5");
	expectMapErrorAt([](auto& l) { l[7] = "0 1"; }, 8, "not positive");
	expectMapErrorAt([](auto& l) {
			l[7] = "5 -1";
			l[8] = "5 2";
		}, 8, "appears twice (first on line 6)");
}

TEST(LocalMapFiles, BadMatrix)
{
	expectMapErrorAt(
		[](auto& l) { l[11] = l[11].substr(0, l[11].rfind(' ')); }, 12,
		"too few values: expected 7 numbers (a row of the N x N information matrix), found 6");
	expectMapErrorAt(
		[](auto& l) { setEntry(l, 2, 4, "inf"); }, 11, "column 4 (matrix entry (2,4)) = 'inf': not a finite number");
	expectMapErrorAt([](auto& l) { setEntry(l, 3, 5, "x"); }, 12, "matrix entry (3,5)");
	// Two asymmetries: the worst, entry (6,2) against (2,6), names row 2 (line 11).
	expectMapErrorAt(
		[](auto& l) {
			setEntry(l, 4, 5, "0.5");
			setEntry(l, 6, 2, "3");
		},
		11, "not symmetric: entry (2,6)");
	// Symmetric but indefinite: row 6's pivot fails (1 - 2^2/1 < 0 with unit rows 5, 6).
	expectMapErrorAt(
		[](auto& l) {
			for (int r = 1; r <= 7; ++r)
				for (int c = 1; c <= 7; ++c) setEntry(l, r, c, r == c ? "1" : "0");
			setEntry(l, 5, 6, "2");
			setEntry(l, 6, 5, "2");
		},
		15, "not positive definite");
}

// ------------------------------------------------------------------ bad folders and row files

TEST(LocalMapFiles, FolderSequenceErrors)
{
	test::TempDir dir;
	expectErrorAt([&] { readLocalMapFolder(dir.file("nowhere")); }, dir.file("nowhere"), "no such folder");
	expectErrorAt([&] { readLocalMapFolder(dir.path()); }, dir.path(), "no localmap_1.txt");
	const auto maps = goodFolder(dir);
	fs::copy_file(maps + "/localmap_2.txt", maps + "/localmap_4.txt");
	expectErrorAt([&] { readLocalMapFolder(maps); }, maps + "/localmap_3.txt", "missing");
	fs::remove(maps + "/localmap_4.txt");
	fs::copy_file(maps + "/localmap_2.txt", maps + "/localmap_3.txt");	// Ref 1 in map 3
	expectErrorAt([&] { readLocalMapFolder(maps); }, maps + "/localmap_3.txt:1", "Ref 1, expected 2");
	fs::remove(maps + "/localmap_3.txt");
	// An error in a later map names that map's file and line.
	writeLines(maps + "/localmap_2.txt", {"1", "3", "-2 0", "-2 0", "-1 0", "1 0 0", "0 1 0", "0 0 1"});
	expectErrorAt([&] { readLocalMapFolder(maps); }, maps + "/localmap_2.txt:5", "expected -2");
}

TEST(LocalMapFiles, BadLinksAndGroundTruth)
{
	test::TempDir dir;
	const auto maps = goodFolder(dir);
	const std::string link = " 0.1 0 0 1 0 0 1 0 1";
	const auto expectLinks = [&](const std::vector<std::string>& rows, int line, const std::string& phrase) {
		writeLines(maps + "/links.txt", rows);
		expectErrorAt([&] { readLocalMapFolder(maps); }, "links.txt:" + std::to_string(line), phrase);
	};
	expectLinks(
		{"2" + link, "1 0.1 0 0 1 0 0 1 0"}, 2,
		"too few values: expected 10 columns 'k dx dy dphi c11 c12 c13 c22 c23 c33', found 9");
	expectLinks({"2" + link, "2" + link}, 2, "duplicate map index 2 (first on line 1)");
	expectLinks({"3" + link}, 1, "maps 1..2");
	expectLinks({"0" + link}, 1, "not positive");
	expectLinks({"1 0.1 0 0 1 2 0 1 0 1"}, 1, "not positive definite");
	expectLinks({"1 0.1 0 zero 1 0 0 1 0 1"}, 1, "column 4 (dphi) = 'zero': not a number");
	writeLines(maps + "/links.txt", {"2" + link});
	const auto with_link = readLocalMapFolder(maps);
	ASSERT_TRUE(with_link.maps[1].link);
	EXPECT_EQ(with_link.maps[1].link->delta.x(), 0.1);
	EXPECT_EQ(with_link.maps[1].link->cov, Eigen::Matrix3d::Identity());
	fs::remove(maps + "/links.txt");

	writeLines(maps + "/ground_truth_landmarks.txt", {"1 0 0", "2 0 0", "1 5 5"});
	expectErrorAt([&] { readLocalMapFolder(maps); }, "ground_truth_landmarks.txt:3", "duplicate id 1");
	writeLines(maps + "/ground_truth_landmarks.txt", {"1 0 0", "2 0"});
	expectErrorAt(
		[&] { readLocalMapFolder(maps); }, "ground_truth_landmarks.txt:2",
		"too few values: expected 3 columns 'id x y', found 2");
	fs::remove(maps + "/ground_truth_landmarks.txt");
	writeLines(maps + "/ground_truth_end_poses.txt", {"1 0 0 0", "2 0 0 0 0"});
	expectErrorAt([&] { readLocalMapFolder(maps); }, "ground_truth_end_poses.txt:2", "extra values");
	writeLines(maps + "/ground_truth_end_poses.txt", {"1 0 0 0", "5 0 0 0"});
	expectErrorAt([&] { readLocalMapFolder(maps); }, "ground_truth_end_poses.txt:2", "maps 1..2");
}

TEST(LocalMapFiles, BadReferenceResult)
{
	test::TempDir dir;
	const auto read = [&] { return readReferenceResult(dir.path(), 2); };
	expectErrorAt(read, dir.file("feature.txt"), "reference features not found");
	writeLines(dir.file("feature.txt"), {"1  19.5  -12.4", "2  29.0  -15.0"});
	// The poses are part of a reference: without them refres_pose_* would be null unnoticed.
	expectErrorAt(read, dir.file("pose.txt"), "reference end poses not found");
	writeLines(dir.file("pose.txt"), {"1 1 2 16.9", "2 1 2 -4.75 7"});
	expectErrorAt(read, "pose.txt:2", "extra values");
	writeLines(dir.file("pose.txt"), {"1 1 2 16.9"});
	const auto ok = read();
	EXPECT_EQ(ok.features.size(), 2u);
	EXPECT_EQ(ok.features.at(2), Eigen::Vector2d(29.0, -15.0));
	EXPECT_EQ(ok.end_poses.at(1), Pose2(1, 2, 16.9));  // phi kept unwrapped
	// A pose of a map the folder does not have, a feature ID no rawlog can carry: refused, not dropped.
	writeLines(dir.file("pose.txt"), {"1 1 2 16.9", "3 0 0 0"});
	expectErrorAt(read, "pose.txt:2", "maps 1..2");
	writeLines(dir.file("pose.txt"), {"1 1 2 16.9"});
	writeLines(dir.file("feature.txt"), {"1 0 0", "99999999999 0 0"});
	expectErrorAt(read, "feature.txt:2", "id 99999999999 is beyond 2147483647");
	writeLines(dir.file("feature.txt"), {"1 0 0", "1 0 0"});
	expectErrorAt(read, "feature.txt:2", "duplicate id 1");
}

// ------------------------------------------------------------------ failed writes

TEST(LocalMapFiles, FailedWriteLeavesNothingHalfWritten)
{
	test::TempDir dir;
	// The target's parent is a file.
	std::ofstream(dir.file("plain")) << "x\n";
	expectErrorAt([&] { writeLocalMapFolder(makeFolder(), dir.file("plain") + "/maps"); }, dir.file("plain/maps"),
				  "cannot create the folder");
	EXPECT_EQ(test::readText(dir.file("plain")), "x\n");
	// The target is a file: not replaced.
	expectErrorAt([&] { writeLocalMapFolder(makeFolder(), dir.file("plain")); }, dir.file("plain"), "not a folder");
	EXPECT_EQ(test::readText(dir.file("plain")), "x\n");

	// A bad map in the middle: the previous folder stays as it was.
	writeLocalMapFolder(makeFolder(), dir.file("maps"));
	auto bad = makeFolder();
	bad.maps[1].information.conservativeResize(5, 5);
	expectErrorAt([&] { writeLocalMapFolder(bad, dir.file("maps")); }, dir.file("maps/localmap_2.txt"), "5x5");
	auto zero_id = makeFolder();
	zero_id.maps[2].features[0].id = 0;
	expectErrorAt([&] { writeLocalMapFolder(zero_id, dir.file("maps")); }, dir.file("maps/localmap_3.txt"), "not positive");
	expectSameMaps(makeFolder(), readLocalMapFolder(dir.file("maps")));
	auto entries = entriesOf(dir.path());
	std::sort(entries.begin(), entries.end());
	EXPECT_EQ(entries, (std::vector<std::string>{"maps", "plain"}));

	// A single file is not written at all when the map is invalid.
	expectErrorAt([&] { writeLocalMapFile(bad.maps[1], dir.file("one.txt")); }, dir.file("one.txt"), "not written");
	EXPECT_FALSE(fs::exists(dir.file("one.txt")));
}

TEST(LocalMapFiles, ReadOnlyParentIsReported)
{
	if (::geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders";
	test::TempDir dir;
	fs::create_directory(dir.file("locked"));
	fs::permissions(dir.file("locked"), fs::perms::owner_read | fs::perms::owner_exec);
	expectErrorAt([&] { writeLocalMapFolder(makeFolder(), dir.file("locked/maps")); }, dir.file("locked/maps"), "cannot");
	fs::permissions(dir.file("locked"), fs::perms::owner_all);
	EXPECT_TRUE(entriesOf(dir.file("locked")).empty());
}

// ------------------------------------------------------------------ the authors' data sets

TEST(LocalMapFiles, VictoriaParkLocalMaps)
{
	const std::string path = test::sourcePath("../shared/data/localmaps/vicpark_200");
	if (!fs::is_directory(path)) GTEST_SKIP() << path << " not present";
	const auto folder = readLocalMapFolder(path);
	ASSERT_EQ(folder.maps.size(), 200u);
	std::size_t entries = 0, min_dim = 1000, max_dim = 0;
	std::set<LandmarkId> ids;
	std::vector<std::size_t> fewer_than_two;
	std::size_t min_shared_elsewhere = 1000;
	for (const auto& m : folder.maps)
	{
		entries += m.features.size();
		min_dim = std::min(min_dim, m.stateDim());
		max_dim = std::max(max_dim, m.stateDim());
		for (const auto& f : m.features) ids.insert(f.id);
		if (m.index < 2) continue;
		if (m.featuresInEarlierMaps() < 2) fewer_than_two.push_back(m.index);
		else min_shared_elsewhere = std::min(min_shared_elsewhere, m.featuresInEarlierMaps());
		EXPECT_FALSE(m.link);
		EXPECT_FALSE(m.covariance);
	}
	EXPECT_EQ(entries, 3889u);
	EXPECT_EQ(ids.size(), 299u);
	EXPECT_EQ(*ids.begin(), 1);
	EXPECT_EQ(*ids.rbegin(), 873);
	EXPECT_EQ(min_dim, 13u);
	EXPECT_EQ(max_dim, 75u);
	EXPECT_EQ(fewer_than_two, std::vector<std::size_t>{132});
	EXPECT_EQ(folder.maps[131].featuresInEarlierMaps(), 1u);
	std::cout << "vicpark_200: fewest features in earlier maps, maps 2..200 except 132: " << min_shared_elsewhere
			  << "\n";
	EXPECT_EQ(folder.maps[1].end_pose.x(), 9.058080766467171);	 // the example in ../shared/data/localmaps/README.md
	EXPECT_FALSE(folder.truth_landmarks);

	const auto ref = readReferenceResult(path + "/linear_slam_result", folder.maps.size());
	EXPECT_EQ(ref.features.size(), 299u);
	ASSERT_EQ(ref.end_poses.size(), 200u);
	std::set<LandmarkId> ref_ids;
	for (const auto& [id, p] : ref.features) ref_ids.insert(id);
	EXPECT_EQ(ref_ids, ids);
	// Map 1 is in the frame of pose 0, like the result: its end pose is the joined one, up to noise.
	EXPECT_LT((folder.maps[0].end_pose.head<2>() - ref.end_poses.at(1).head<2>()).norm(), 0.5);
}

TEST(LocalMapFiles, SimulatedMapsWithTruth)
{
	const std::string path = test::sourcePath("../shared/data/localmaps/sim5_with_truth");
	if (!fs::is_directory(path)) GTEST_SKIP() << path << " not present";
	const auto folder = readLocalMapFolder(path);
	ASSERT_EQ(folder.maps.size(), 5u);
	std::set<LandmarkId> ids;
	std::size_t entries = 0;
	for (const auto& m : folder.maps)
	{
		entries += m.features.size();
		for (const auto& f : m.features) ids.insert(f.id);
	}
	EXPECT_EQ(ids.size(), 37u);
	EXPECT_EQ(entries, 49u);
	ASSERT_TRUE(folder.truth_landmarks);
	EXPECT_EQ(folder.truth_landmarks->size(), 196u);  // every true landmark, observed or not
	for (const LandmarkId id : ids) EXPECT_EQ(folder.truth_landmarks->count(id), 1u) << "feature " << id;
	EXPECT_FALSE(folder.truth_end_poses);
	// Map 1 is in the frame of pose 0, the truth's frame: its features sit near the true ones.
	double worst = 0;
	for (const auto& f : folder.maps[0].features)
		worst = std::max(worst, (f.position - folder.truth_landmarks->at(f.id)).norm());
	std::cout << "sim5_with_truth: map 1 largest feature error " << worst << " m\n";
	EXPECT_LT(worst, 0.5);
}

}  // namespace
