/// \file LocalMapFiles.cpp
/// The authors' local-map text format (LocalMapFiles.h), read strictly: every
/// line is checked for its token count, every token is parsed whole, and the
/// first problem is reported as one InputError "file:line: what is wrong", so
/// a damaged or hand-edited map is never joined with a silent shift.

#include <esif/core/Errors.h>
#include <esif/core/InputBounds.h>
#include <esif/core/NumberToken.h>
#include <esif/core/TextInput.h>
#include <esif/formats/LocalMapFiles.h>
#include <esif/safeio/AtomicFile.h>
#include "NumberRow.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <new>
#include <set>
#include <string_view>
#include <system_error>

namespace fs = std::filesystem;

namespace esif
{
namespace
{
/// Largest asymmetry |M(i,j) - M(j,i)| accepted, relative to the largest
/// |entry| of the matrix; also LocalMap::validate's default. Far above the
/// published maps' round-off, yet it catches real damage (a transposed or
/// mistyped entry, a wrong row): docs/local-maps.md, "Symmetry tolerance".
constexpr double kSymmetryTolerance = 1e-9;

const char* const kLinksFile = "links.txt";
const char* const kTruthLandmarksFile = "ground_truth_landmarks.txt";
const char* const kTruthPosesFile = "ground_truth_end_poses.txt";

std::string mapFileName(std::size_t k) { return "localmap_" + std::to_string(k) + ".txt"; }

std::string formatted(const char* format, double v)
{
	char buf[40];
	std::snprintf(buf, sizeof(buf), format, v);
	return buf;
}
/// Every digit of `v`: %.17g reads back to the same double.
std::string number17(double v) { return formatted("%.17g", v); }
/// `v` for a message, where three digits say enough.
std::string short3(double v) { return formatted("%.3g", v); }

/// A text file's lines (TextLineReader's rules), read by line number: a
/// local map's line count is checked before any of its rows. Trailing
/// blank lines (a final newline too many) are dropped; any other blank line
/// is data and is reported where a row is expected.
class FileLines
{
   public:
	FileLines(std::string path, const std::string& what) : path_(std::move(path))
	{
		TextLineReader in(path_, what);
		for (std::string line; in.next(line);) lines_.push_back(line);
		while (!lines_.empty() && lines_.back().find_first_not_of(" \t\r") == std::string::npos) lines_.pop_back();
	}

	std::size_t lineCount() const { return lines_.size(); }

	/// Line `lineno` (1-based) as a row of `columns`.
	NumberRow row(std::size_t lineno, const NumberRow::Columns& columns) const
	{
		return NumberRow(lines_.at(lineno - 1), columns, where(lineno));
	}

	/// Throws InputError "FILE:LINE: problem".
	[[noreturn]] void fail(std::size_t lineno, const std::string& problem) const
	{
		throw InputError(where(lineno) + ": " + problem);
	}

   private:
	std::string where(std::size_t lineno) const { return path_ + ":" + std::to_string(lineno); }

	std::string path_;
	std::vector<std::string> lines_;
};

// ---------------------------------------------------------------- matrices

/// Index of the first row whose Cholesky pivot is not positive, or -1 when
/// `a` (symmetric) is positive definite. A hand loop rather than Eigen::LLT
/// because LLT reports only failure, not where: the row names the line to
/// fix. Same test as LLT (pivot <= 0, or NaN); O(N^3 / 3) is nothing at the
/// N <= 100 of local maps.
Eigen::Index failingPivot(Eigen::MatrixXd a)
{
	const Eigen::Index n = a.rows();
	for (Eigen::Index j = 0; j < n; ++j)
	{
		const double d = a(j, j) - a.row(j).head(j).squaredNorm();
		if (!(d > 0)) return j;
		a(j, j) = std::sqrt(d);
		for (Eigen::Index i = j + 1; i < n; ++i)
			a(i, j) = (a(i, j) - a.row(i).head(j).dot(a.row(j).head(j))) / a(j, j);
	}
	return -1;
}

/// Throws at the line of the row holding the largest asymmetry when it
/// exceeds kSymmetryTolerance relative to the largest entry.
void checkSymmetric(const FileLines& f, const Eigen::MatrixXd& m, std::size_t first_line)
{
	const double scale = m.cwiseAbs().maxCoeff();
	double worst = 0;
	Eigen::Index wi = 0, wj = 0;
	for (Eigen::Index i = 0; i < m.rows(); ++i)
		for (Eigen::Index j = i + 1; j < m.cols(); ++j)
			if (const double d = std::abs(m(i, j) - m(j, i)); d > worst)
			{
				worst = d;
				wi = i;
				wj = j;
			}
	if (worst <= kSymmetryTolerance * scale) return;
	f.fail(
		first_line + wi, "information matrix not symmetric: entry (" + std::to_string(wi + 1) + "," +
							 std::to_string(wj + 1) + ") = " + number17(m(wi, wj)) + " but (" + std::to_string(wj + 1) +
							 "," + std::to_string(wi + 1) + ") on line " + std::to_string(first_line + wj) + " = " +
							 number17(m(wj, wi)) + ": difference " + short3(worst) + " against entries up to " +
							 short3(scale) + " (tolerance " + short3(kSymmetryTolerance) + " relative)");
}

// ---------------------------------------------------------------- one map

// Ref, N and the id of a state line are integers written as such ("7", not "7.0").
const NumberRow::Columns kRefColumn({"Ref"}, 1);
const NumberRow::Columns kNColumn({"N"}, 1);
const NumberRow::Columns kStateColumns({"id", "value"}, 1);

/// Checks lines 1-2 (Ref, N) and the line count; returns N.
std::size_t readHeader(const FileLines& f, std::size_t k)
{
	if (f.lineCount() < 2) f.fail(f.lineCount() + 1, "file ends early: expected 'Ref' on line 1 and 'N' on line 2");
	const long ref = f.row(1, kRefColumn).integer(0);
	// LocalMap has no field for another reference pose (map k is expressed
	// in pose k-1 by construction), so a map expressed in any other pose would be
	// joined in the wrong frame: reject it instead of misplacing it.
	if (ref != static_cast<long>(k) - 1)
		f.fail(1, "Ref " + std::to_string(ref) + ", expected " + std::to_string(k - 1) + " (map " + std::to_string(k) +
					  " must be expressed in pose k-1)");
	const long n = f.row(2, kNColumn).integer(0);
	if (n < 3 || n % 2 == 0)
		f.fail(2, "N = " + std::to_string(n) + " is not a state dimension 3 + 2 * features (odd, at least 3)");
	const std::size_t expected = 2 + 2 * static_cast<std::size_t>(n);
	if (f.lineCount() < expected)
		f.fail(f.lineCount() + 1, "file ends early: N = " + std::to_string(n) + " needs " + std::to_string(expected) +
									  " lines, found " + std::to_string(f.lineCount()));
	if (f.lineCount() > expected)
		f.fail(expected + 1, "too many lines: N = " + std::to_string(n) + " needs " + std::to_string(expected) +
								 " lines, found " + std::to_string(f.lineCount()));
	return static_cast<std::size_t>(n);
}

/// Lines 3 .. N+2: `id value`, the end pose (id -k) then feature pairs.
void readState(const FileLines& f, std::size_t n, LocalMap& map)
{
	const long pose_id = -static_cast<long>(map.index);
	std::map<long, std::size_t> first_line_of;	// feature id -> its line
	for (std::size_t i = 0; i < n; ++i)
	{
		const std::size_t line = 3 + i;
		const NumberRow row = f.row(line, kStateColumns);
		const long id = row.integer(0);
		const double value = row.number(1);
		const std::string& written_id = row.token(0);
		if (i < 3)
		{
			if (id != pose_id)
				f.fail(line, "id " + written_id + ", expected " + std::to_string(pose_id) + " (the end pose of map " +
								 std::to_string(map.index) + " comes first: x, y, phi)");
			map.end_pose(static_cast<Eigen::Index>(i)) = i == 2 ? wrapAngle(value) : value;
		}
		else if ((i - 3) % 2 == 0)
		{
			if (id <= 0) f.fail(line, "feature id " + written_id + " is not positive");
			if (const auto [it, fresh] = first_line_of.emplace(id, line); !fresh)
				f.fail(
					line, "feature id " + written_id + " appears twice (first on line " + std::to_string(it->second) + ")");
			map.features.push_back({id, Eigen::Vector2d(value, 0), false});
		}
		else
		{
			if (id != map.features.back().id)
				f.fail(line, "id " + written_id + ", expected " + std::to_string(map.features.back().id) +
								 " (a feature's y line follows its x line with the same id)");
			map.features.back().position.y() = value;
		}
	}
}

/// Lines N+3 .. 2N+2: the N x N information matrix, row-major.
Eigen::MatrixXd readMatrix(const FileLines& f, std::size_t n)
{
	Eigen::MatrixXd m(n, n);
	const std::string what = std::to_string(n) + " numbers (a row of the N x N information matrix)";
	for (std::size_t r = 0; r < n; ++r)
	{
		// Entries are named only for a message: no string is built for a good one.
		const NumberRow::Columns columns(n, what, [r](std::size_t c) {
			return "matrix entry (" + std::to_string(r + 1) + "," + std::to_string(c + 1) + ")";
		});
		const NumberRow row = f.row(3 + n + r, columns);
		for (std::size_t c = 0; c < n; ++c) m(r, c) = row.number(c);
	}
	return m;
}

/// LocalMap::validate as the last check. The reader has checked everything
/// it tests, so this only fires if the two disagree (e.g. a pivot on the
/// edge of zero); its message then gets the file:line of the matrix.
void validateRead(const LocalMap& map, const std::string& path, std::size_t matrix_line)
{
	try
	{
		map.validate(path, kSymmetryTolerance);
	}
	catch (const NumericalError& e)
	{
		std::string what = e.what();
		if (what.rfind(path + ": ", 0) == 0) what.erase(0, path.size() + 2);
		throw InputError(path + ":" + std::to_string(matrix_line) + ": " + what);
	}
}

// ---------------------------------------------------------------- row files

// The first column, an ID or a map index, is an integer written as such.
const NumberRow::Columns kPointColumns({"id", "x", "y"}, 1);
const NumberRow::Columns kPoseColumns({"k", "x", "y", "phi"}, 1);
const NumberRow::Columns kLinkColumns({"k", "dx", "dy", "dphi", "c11", "c12", "c13", "c22", "c23", "c33"}, 1);

/// Calls `row(row, line)` for every line of a file of `columns` rows.
void forEachRow(
	const FileLines& f, const NumberRow::Columns& columns,
	const std::function<void(const NumberRow&, std::size_t)>& row)
{
	for (std::size_t line = 1; line <= f.lineCount(); ++line) row(f.row(line, columns), line);
}

/// Column 0 of `row`: a positive id / map index not seen before in this file.
long freshPositive(
	const FileLines& f, std::size_t line, const NumberRow& row, const std::string& what,
	std::map<long, std::size_t>& seen)
{
	const long v = row.integer(0);
	if (v <= 0) f.fail(line, what + " " + row.token(0) + " is not positive");
	if (const auto [it, fresh] = seen.emplace(v, line); !fresh)
		f.fail(line, "duplicate " + what + " " + row.token(0) + " (first on line " + std::to_string(it->second) + ")");
	return v;
}

/// `id x y` rows (ground truth landmarks, the reference's feature.txt).
std::map<LandmarkId, Eigen::Vector2d> readPointRows(const std::string& path, const std::string& what)
{
	const FileLines f(path, what);
	std::map<LandmarkId, Eigen::Vector2d> out;
	std::map<long, std::size_t> seen;
	forEachRow(f, kPointColumns, [&](const NumberRow& row, std::size_t line) {
		const long id = freshPositive(f, line, row, "id", seen);
		if (id > kMaxLandmarkId)
			f.fail(
				line, "id " + row.token(0) + " is beyond " + std::to_string(kMaxLandmarkId) + " (MRPT's landmark IDs)");
		out[id] = {row.coordinate(1), row.coordinate(2)};
	});
	return out;
}

/// `k x y phi` rows (ground truth end poses, the reference's pose.txt); phi
/// is kept as written (the authors' pose.txt holds unwrapped headings).
/// `last_map`: largest k accepted (0: any).
std::map<std::size_t, Pose2> readPoseRows(const std::string& path, const std::string& what, std::size_t last_map)
{
	const FileLines f(path, what);
	std::map<std::size_t, Pose2> out;
	std::map<long, std::size_t> seen;
	forEachRow(f, kPoseColumns, [&](const NumberRow& row, std::size_t line) {
		const long k = freshPositive(f, line, row, "map index", seen);
		if (last_map && static_cast<std::size_t>(k) > last_map)
			f.fail(line, "map index " + row.token(0) + " but the folder has maps 1.." + std::to_string(last_map));
		out[static_cast<std::size_t>(k)] = {row.coordinate(1), row.coordinate(2), row.heading(3)};
	});
	return out;
}

/// links.txt: `k dx dy dphi c11 c12 c13 c22 c23 c33` into maps[k-1].link.
void readLinks(const std::string& path, std::vector<LocalMap>& maps)
{
	const FileLines f(path, "local-map links");
	std::map<long, std::size_t> seen;
	forEachRow(f, kLinkColumns, [&](const NumberRow& row, std::size_t line) {
		const long k = freshPositive(f, line, row, "map index", seen);
		if (static_cast<std::size_t>(k) > maps.size())
			f.fail(line, "map index " + row.token(0) + " but the folder has maps 1.." + std::to_string(maps.size()));
		const double dx = row.coordinate(1), dy = row.coordinate(2), dphi = row.heading(3);
		OdometryIncrement link;
		link.delta = Pose2(dx, dy, dphi);
		const auto c = [&](std::size_t i) { return row.number(i); };  // c11 c12 c13 c22 c23 c33: columns 4..9
		link.cov << c(4), c(5), c(6), c(5), c(7), c(8), c(6), c(8), c(9);
		if (failingPivot(link.cov) >= 0) f.fail(line, "link covariance is not positive definite");
		maps[static_cast<std::size_t>(k) - 1].link = link;
	});
}

/// Largest k of the files named exactly localmap_<k>.txt in `dir` (0: none).
std::size_t lastMapIndex(const std::string& dir)
{
	std::size_t last = 0;
	std::error_code ec;
	for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
	{
		const auto& entry = *it;
		const std::string name = entry.path().filename().string();
		const std::string prefix = "localmap_", suffix = ".txt";
		if (name.size() <= prefix.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
			name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
			continue;
		const auto k = integerToken<long>(
			std::string_view(name).substr(prefix.size(), name.size() - prefix.size() - suffix.size()));
		// Only canonical names count ("localmap_07.txt" is not map 7).
		if (k && *k > 0 && mapFileName(static_cast<std::size_t>(*k)) == name)
			last = std::max(last, static_cast<std::size_t>(*k));
	}
	if (ec) throw InputError(dir + ": cannot list the folder: " + ec.message());
	return last;
}

// ---------------------------------------------------------------- writing

/// Every problem that would make the file unreadable, as one message.
void checkWritable(const LocalMap& map, const std::string& path)
{
	try
	{
		map.validate(path, kSymmetryTolerance);
	}
	catch (const NumericalError& e)
	{
		throw InputError(std::string(e.what()) + " (not written)");
	}
	for (const auto& f : map.features)
		if (f.id <= 0)
			throw InputError(
				path + ": local map " + std::to_string(map.index) + ": feature id " + std::to_string(f.id) +
				" is not positive (the format keeps ids <= 0 for poses; not written)");
}

std::string mapText(const LocalMap& map)
{
	std::string out = std::to_string(map.index - 1) + "\n" + std::to_string(map.stateDim()) + "\n";
	const std::string pose_id = "-" + std::to_string(map.index);
	for (int i = 0; i < 3; ++i) out += pose_id + " " + number17(map.end_pose(i)) + "\n";
	for (const auto& f : map.features)
		for (int i = 0; i < 2; ++i) out += std::to_string(f.id) + " " + number17(f.position(i)) + "\n";
	for (Eigen::Index r = 0; r < map.information.rows(); ++r)
	{
		for (Eigen::Index c = 0; c < map.information.cols(); ++c)
			out += (c ? " " : "") + number17(map.information(r, c));
		out += "\n";
	}
	return out;
}

std::string linksText(const std::vector<LocalMap>& maps)
{
	std::string out;
	for (const auto& m : maps)
	{
		if (!m.link) continue;
		const auto& d = m.link->delta;
		const auto& c = m.link->cov;
		out += std::to_string(m.index);
		for (const double v : {d.x(), d.y(), d(2), c(0, 0), c(0, 1), c(0, 2), c(1, 1), c(1, 2), c(2, 2)})
			out += " " + number17(v);
		out += "\n";
	}
	return out;
}

std::string truthLandmarksText(const std::map<LandmarkId, Eigen::Vector2d>& truth)
{
	std::string out;
	for (const auto& [id, p] : truth) out += std::to_string(id) + " " + number17(p.x()) + " " + number17(p.y()) + "\n";
	return out;
}

std::string truthPosesText(const std::map<std::size_t, Pose2>& truth)
{
	std::string out;
	for (const auto& [k, p] : truth)
		out += std::to_string(k) + " " + number17(p.x()) + " " + number17(p.y()) + " " + number17(p.z()) + "\n";
	return out;
}

/// Runs `write(dir/name)`; a failure names the file.
void writeInto(const fs::path& dir, const std::string& name, const std::function<void(const std::string&)>& write)
{
	const std::string path = (dir / name).string();
	try
	{
		write(path);
	}
	catch (const std::bad_alloc&)
	{
		throw;
	}
	catch (const std::exception& e)
	{
		const std::string what = e.what();
		if (what.rfind(path + ": ", 0) == 0) throw;
		throw InputError(path + ": " + what);
	}
}

void writeContents(const LocalMapFolder& folder, const fs::path& dir)
{
	for (std::size_t i = 0; i < folder.maps.size(); ++i)
	{
		const std::string name = mapFileName(i + 1);
		if (folder.maps[i].index != i + 1)
			throw InputError(
				(dir / name).string() + ": map at position " + std::to_string(i + 1) + " has index " +
				std::to_string(folder.maps[i].index) + " (maps must be numbered 1..K in order; not written)");
		writeInto(dir, name, [&](const std::string& p) { writeLocalMapFile(folder.maps[i], p); });
	}
	const std::string links = linksText(folder.maps);
	if (!links.empty()) writeInto(dir, kLinksFile, [&](const std::string& p) { writeTextAtomically(p, links); });
	if (folder.truth_landmarks)
		writeInto(dir, kTruthLandmarksFile, [&](const std::string& p) {
			writeTextAtomically(p, truthLandmarksText(*folder.truth_landmarks));
		});
	if (folder.truth_end_poses)
		writeInto(dir, kTruthPosesFile, [&](const std::string& p) {
			writeTextAtomically(p, truthPosesText(*folder.truth_end_poses));
		});
}

}  // namespace

LocalMap readLocalMapFile(const std::string& path, std::size_t k)
{
	if (k == 0) throw InputError(path + ": local map index 0 (maps are numbered from 1)");
	const FileLines f(path, "local map");
	LocalMap map;
	map.index = k;
	const std::size_t n = readHeader(f, k);
	readState(f, n, map);
	const Eigen::MatrixXd m = readMatrix(f, n);
	const std::size_t matrix_line = 3 + n;
	checkSymmetric(f, m, matrix_line);
	map.information = 0.5 * (m + m.transpose());
	if (const Eigen::Index r = failingPivot(map.information); r >= 0)
		f.fail(
			matrix_line + static_cast<std::size_t>(r),
			"information matrix not positive definite: the Cholesky pivot of row " + std::to_string(r + 1) +
				" is not positive (after symmetrising)");
	validateRead(map, path, matrix_line);
	return map;
}

LocalMapFolder readLocalMapFolder(const std::string& dir)
{
	std::error_code ec;
	if (!fs::is_directory(dir, ec)) throw InputError(dir + ": no such folder");
	const std::size_t last = lastMapIndex(dir);
	if (last == 0 || !pathPresent((fs::path(dir) / mapFileName(1)).string()))
		throw InputError(dir + ": no " + mapFileName(1) + " (not a local-map folder)");
	LocalMapFolder folder;
	std::set<LandmarkId> earlier;
	for (std::size_t k = 1; k <= last; ++k)
	{
		const std::string path = (fs::path(dir) / mapFileName(k)).string();
		if (!pathPresent(path))
			throw InputError(
				path + ": missing (the folder holds maps up to " + mapFileName(last) + "; the sequence must have no gap)");
		LocalMap map = readLocalMapFile(path, k);
		for (auto& f : map.features) f.in_earlier_maps = earlier.count(f.id) > 0;
		for (const auto& f : map.features) earlier.insert(f.id);
		folder.maps.push_back(std::move(map));
	}
	if (const auto p = (fs::path(dir) / kLinksFile).string(); pathPresent(p)) readLinks(p, folder.maps);
	if (const auto p = (fs::path(dir) / kTruthLandmarksFile).string(); pathPresent(p))
		folder.truth_landmarks = readPointRows(p, "ground-truth landmarks");
	if (const auto p = (fs::path(dir) / kTruthPosesFile).string(); pathPresent(p))
		folder.truth_end_poses = readPoseRows(p, "ground-truth end poses", folder.maps.size());
	return folder;
}

void writeLocalMapFile(const LocalMap& map, const std::string& path)
{
	checkWritable(map, path);
	writeTextAtomically(path, mapText(map));
}

void writeLocalMapFiles(const LocalMapFolder& folder, const std::string& dir)
{
	if (folder.maps.empty()) throw InputError(dir + ": no local maps to write");
	writeContents(folder, dir);
}

ReferenceResult readReferenceResult(const std::string& dir, std::size_t maps)
{
	std::error_code ec;
	if (!fs::is_directory(dir, ec)) throw InputError(dir + ": no such folder");
	ReferenceResult out;
	out.features = readPointRows((fs::path(dir) / "feature.txt").string(), "reference features");
	out.end_poses = readPoseRows((fs::path(dir) / "pose.txt").string(), "reference end poses", maps);
	return out;
}

}  // namespace esif
