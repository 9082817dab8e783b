#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/io/AtomicFile.h>
#include <esif/io/GroundTruth.h>
#include <esif/io/InputBounds.h>
#include <esif/io/TextInput.h>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace esif
{
namespace
{
std::string landmarkFileOf(const std::string& prefix) { return prefix + "_ground_truth.txt"; }
std::string pathFileOf(const std::string& prefix) { return prefix + "_ground_truth_robot_path.txt"; }

bool isBlankOrComment(const std::string& line)
{
	const auto first = line.find_first_not_of(" \t\r");
	return first == std::string::npos || line[first] == '%' || line[first] == '#';
}

/// The columns of one data line, each a finite number, known by name for
/// the errors ("FILE:LINE: column K (NAME) = VALUE: rule").
class Row
{
   public:
	Row(const std::string& line, const std::vector<const char*>& names, const std::string& where)
		: names_(names), where_(where)
	{
		std::istringstream ss(line);
		std::vector<std::string> tokens;
		for (std::string t; ss >> t;) tokens.push_back(t);
		if (tokens.size() != names.size())
		{
			std::string list;
			for (const char* n : names) list += (list.empty() ? "" : " ") + std::string(n);
			throw InputError(
				where + ": expected " + std::to_string(names.size()) + " columns '" + list + "', found " +
				std::to_string(tokens.size()));
		}
		for (std::size_t i = 0; i < tokens.size(); ++i)
		{
			char* end = nullptr;
			const double v = std::strtod(tokens[i].c_str(), &end);
			if (end == tokens[i].c_str() || *end != '\0') fail(i, "'" + tokens[i] + "'", "not a number");
			if (!std::isfinite(v)) fail(i, "'" + tokens[i] + "'", "not a finite number");
			values_.push_back(v);
		}
	}

	/// Column `i` as a coordinate [m], within +-kMaxCoordinate_m.
	double coordinate(std::size_t i) const
	{
		if (std::abs(values_[i]) > kMaxCoordinate_m)
			fail(i, formatNumber(values_[i]), "must be within +-" + formatNumber(kMaxCoordinate_m) + " m");
		return values_[i];
	}

	/// Column `i` as a heading [rad], within +-kMaxHeading_rad.
	double heading(std::size_t i) const
	{
		if (std::abs(values_[i]) > kMaxHeading_rad)
			fail(i, formatNumber(values_[i]), "must be within +-" + formatNumber(kMaxHeading_rad) + " rad");
		return values_[i];
	}

	/// Column `i` as a landmark ID: an integer in [0, kMaxLandmarkId].
	LandmarkId landmarkId(std::size_t i) const
	{
		const double v = values_[i];
		if (v != std::floor(v)) fail(i, formatNumber(v), "a landmark ID must be an integer, not fractional");
		if (v < 0 || v > static_cast<double>(kMaxLandmarkId))
			fail(i, formatNumber(v), "a landmark ID must be in [0, " + std::to_string(kMaxLandmarkId) + "]");
		return static_cast<LandmarkId>(v);
	}

   private:
	[[noreturn]] void fail(std::size_t i, const std::string& value, const std::string& rule) const
	{
		throw InputError(
			where_ + ": column " + std::to_string(i + 1) + " (" + names_[i] + ") = " + value + ": " + rule);
	}

	const std::vector<const char*>& names_;
	const std::string where_;
	std::vector<double> values_;
};

// CLandmarksMap::saveToTextFile's columns, and simul-landmarks' robot path.
const std::vector<const char*> kLandmarkColumns{"x", "y", "z", "type", "seenCount", "tLastSeen", "ID"};
const std::vector<const char*> kPathColumns{"x", "y", "z", "yaw", "pitch", "roll"};

std::map<LandmarkId, Eigen::Vector2d> readLandmarks(const std::string& file)
{
	TextLineReader in(file, "ground-truth landmarks");
	std::map<LandmarkId, Eigen::Vector2d> out;
	std::map<LandmarkId, std::size_t> line_of;
	for (std::string line; in.next(line);)
	{
		if (isBlankOrComment(line)) continue;
		const std::size_t lineno = in.lineNumber();
		const std::string where = in.where();
		const Row row(line, kLandmarkColumns, where);
		const LandmarkId id = row.landmarkId(6);
		const Eigen::Vector2d p(row.coordinate(0), row.coordinate(1));
		if (const auto first = line_of.find(id); first != line_of.end())
			throw InputError(
				where + ": column 7 (ID) = " + std::to_string(id) + ": duplicate landmark ID (first on line " +
				std::to_string(first->second) + ")");
		line_of[id] = lineno;
		out.emplace(id, p);
	}
	return out;
}

std::vector<Pose2> readPath(const std::string& file)
{
	TextLineReader in(file, "ground-truth robot path");
	std::vector<Pose2> out;
	for (std::string line; in.next(line);)
	{
		if (isBlankOrComment(line)) continue;
		const Row row(line, kPathColumns, in.where());
		out.emplace_back(row.coordinate(0), row.coordinate(1), row.heading(3));
	}
	return out;
}
}  // namespace

GroundTruth GroundTruth::inInitialPoseFrame() const
{
	if (path.empty()) return *this;
	const Pose2 origin = path.front();
	GroundTruth out;
	for (const auto& [id, p] : landmarks)
		out.landmarks[id] = inverseCompose(origin, Pose2(p.x(), p.y(), 0)).head<2>();
	out.path.reserve(path.size());
	for (const auto& pose : path) out.path.push_back(inverseCompose(origin, pose));
	return out;
}

std::optional<std::string> groundTruthProblem(const GroundTruth& truth, std::size_t steps, bool log_truncated)
{
	if (truth.path.empty())
		return std::string("no robot-path ground truth (*_ground_truth_robot_path.txt): the landmarks' frame "
						   "relative to the initial pose is unknown");
	const bool one_per_step = truth.path.size() == steps || truth.path.size() + 1 == steps;
	if (!one_per_step && !(log_truncated && truth.path.size() > steps))
		return "the robot-path ground truth has " + std::to_string(truth.path.size()) + " poses for " +
			   std::to_string(steps) + " steps (one per step expected): its poses cannot be paired with the steps";
	return std::nullopt;
}

std::string groundTruthPrefixFor(const std::string& rawlog_path)
{
	std::string p = rawlog_path;
	for (const std::string ext : {".gz", ".rawlog"})
		if (p.size() > ext.size() && p.compare(p.size() - ext.size(), ext.size(), ext) == 0)
			p.erase(p.size() - ext.size());
	return p;
}

std::vector<std::string> groundTruthFilesOf(const std::string& prefix)
{
	return {landmarkFileOf(prefix), pathFileOf(prefix)};
}

std::optional<GroundTruth> loadGroundTruth(const std::string& prefix)
{
	if (!pathPresent(landmarkFileOf(prefix))) return std::nullopt;
	GroundTruth gt;
	gt.landmarks = readLandmarks(landmarkFileOf(prefix));
	if (pathPresent(pathFileOf(prefix))) gt.path = readPath(pathFileOf(prefix));
	return gt;
}

void saveGroundTruth(const GroundTruth& truth, const std::string& prefix)
{
	std::ostringstream lm;
	char buf[256];
	for (const auto& [id, p] : truth.landmarks)
	{
		// Same columns and type code (5 = beacon) as CLandmarksMap::saveToTextFile.
		std::snprintf(buf, sizeof(buf), "%10.6f %10.6f %10.6f %4d %4d %10.6f %lld \n", p.x(), p.y(), 0.0, 5, 0, 0.0,
					  static_cast<long long>(id));
		lm << buf;
	}
	writeTextAtomically(landmarkFileOf(prefix), lm.str());

	std::ostringstream path;
	path << "% Columns are: x(m) y(m) z(m) yaw(rad) pitch(rad) roll(rad)\n";
	path << "% File generated by esif\n%------------------------------------\n";
	for (const auto& p : truth.path)
	{
		std::snprintf(buf, sizeof(buf), "%.16f %.16f %.16f %.16f %.16f %.16f\n", p.x(), p.y(), 0.0, p.z(), 0.0, 0.0);
		path << buf;
	}
	writeTextAtomically(pathFileOf(prefix), path.str());
}

}  // namespace esif
