/// \file RunOutputReader.cpp
/// trajectory.tum and landmarks.txt read back, strictly: every token must
/// read whole as a number (NumberToken.h; NaN and infinities too: a diverged
/// run writes them), so a damaged file is reported at its line, never misread.

#include <esif/core/Errors.h>
#include <esif/core/InputBounds.h>
#include <esif/core/NumberToken.h>
#include <esif/core/TextInput.h>
#include <esif/formats/NumberText.h>
#include <esif/formats/RunOutputReader.h>
#include <esif/models/Se2.h>

#include <Eigen/Geometry>

#include <cmath>
#include <filesystem>
#include <map>
#include <optional>

namespace esif
{
namespace
{
/// Whitespace-separated tokens of a line; empty for blank and '#' comment lines.
std::vector<std::string> tokens(const std::string& line)
{
	auto out = whitespaceTokens(line);
	if (!out.empty() && out[0][0] == '#') return {};
	return out;
}

/// "file:line: problem", the one-line error of a bad row.
[[noreturn]] void failAt(const std::string& path, std::size_t lineno, const std::string& problem)
{
	throw InputError(path + ":" + std::to_string(lineno) + ": " + problem);
}

/// Parses `toks` as exactly `count` numbers, naming `columns` in errors.
std::vector<double> numbersOf(
	const std::vector<std::string>& toks, std::size_t first, std::size_t count, const std::string& path,
	std::size_t lineno, const std::string& columns)
{
	if (toks.size() != first + count)
		failAt(path, lineno, "expected " + columns + ", found " + std::to_string(toks.size()) + " values");
	std::vector<double> v;
	for (std::size_t k = first; k < toks.size(); ++k)
	{
		const auto x = doubleToken(toks[k], NonFinite::accepted);
		if (!x) failAt(path, lineno, "'" + toks[k] + "' is not a number (expected " + columns + ")");
		v.push_back(*x);
	}
	return v;
}

/// Yaw [rad] of the rotation (qx, qy, qz, qw) about the vertical axis; NaN
/// when a component is not finite.
double yawOf(double qx, double qy, double qz, double qw, const std::string& path, std::size_t lineno)
{
	const Eigen::Quaterniond q(qw, qx, qy, qz);
	if (!q.coeffs().allFinite()) return std::nan("");
	if (q.norm() < 1e-9) failAt(path, lineno, "quaternion (qx qy qz qw) = (0, 0, 0, 0) is not a rotation");
	const Eigen::Matrix3d r = q.normalized().toRotationMatrix();
	return wrapAngle(std::atan2(r(1, 0), r(0, 0)));
}
/// For a reference: (x, y) finite and within kMaxCoordinate_m.
void requireBoundedPosition(double x, double y, const std::string& path, std::size_t lineno)
{
	for (const double v : {x, y})
		if (!std::isfinite(v) || std::abs(v) > kMaxCoordinate_m)
			failAt(
				path, lineno,
				"position (" + number_text::text(x) + ", " + number_text::text(y) + ") is not finite or beyond " +
					number_text::text(kMaxCoordinate_m) + " m (a reference must be a run that did not diverge)");
}
}  // namespace

std::vector<TimedPose2D> readTrajectoryTum(const std::string& path, RunRole role)
{
	static const std::string kColumns = "8 numbers 'timestamp x y z qx qy qz qw'";
	TextLineReader in(path, "trajectory");
	std::vector<TimedPose2D> out;
	for (std::string line; in.next(line);)
	{
		const std::size_t lineno = in.lineNumber();
		const auto toks = tokens(line);
		if (toks.empty()) continue;
		const auto v = numbersOf(toks, 0, 8, path, lineno, kColumns);
		if (!std::isfinite(v[0])) failAt(path, lineno, "timestamp " + toks[0] + " is not finite");
		if (!out.empty() && !(v[0] > out.back().time_s))
			failAt(
				path, lineno,
				"timestamp " + toks[0] + " is not after the previous one (" + number_text::text(out.back().time_s) +
					"): times must increase");
		TimedPose2D p;
		p.time_s = v[0];
		p.pose = mrpt::math::TPose2D(v[1], v[2], yawOf(v[4], v[5], v[6], v[7], path, lineno));
		if (role == RunRole::Reference)
		{
			requireBoundedPosition(p.pose.x, p.pose.y, path, lineno);
			if (!std::isfinite(p.pose.phi)) failAt(path, lineno, "the rotation (qx qy qz qw) is not finite");
		}
		out.push_back(p);
	}
	return out;
}

std::vector<LandmarkEstimate> readLandmarksTxt(const std::string& path, RunRole role)
{
	static const std::string kColumns = "'id x y cxx cxy cyy' (an integer ID and 5 numbers)";
	TextLineReader in(path, "landmark map");
	std::vector<LandmarkEstimate> out;
	std::map<LandmarkId, std::size_t> line_of_id;
	for (std::string line; in.next(line);)
	{
		const std::size_t lineno = in.lineNumber();
		const auto toks = tokens(line);
		if (toks.empty()) continue;
		const auto v = numbersOf(toks, 1, 5, path, lineno, kColumns);
		LandmarkEstimate lm;
		const std::string& id = toks[0];
		const auto parsed_id = integerToken<LandmarkId>(id);
		if (!parsed_id) failAt(path, lineno, "landmark ID '" + id + "' is not an integer (expected " + kColumns + ")");
		lm.id = *parsed_id;
		if (const auto [it, added] = line_of_id.emplace(lm.id, lineno); !added)
			failAt(
				path, lineno,
				"duplicate landmark ID " + std::to_string(lm.id) + " (first on line " + std::to_string(it->second) +
					")");
		lm.mean << v[0], v[1];
		lm.cov << v[2], v[3], v[3], v[4];
		if (role == RunRole::Reference)
		{
			if (lm.id < 0 || lm.id > kMaxLandmarkId)
				failAt(path, lineno, "landmark ID " + id + " is outside 0.." + std::to_string(kMaxLandmarkId) +
										 " (MRPT's landmark IDs)");
			requireBoundedPosition(v[0], v[1], path, lineno);
		}
		out.push_back(lm);
	}
	return out;
}

namespace
{
/// The identities of a run folder, which must cover landmarks.txt row for row.
LandmarkIdentities identitiesOfMap(const std::string& path, const std::vector<LandmarkEstimate>& landmarks)
{
	LandmarkIdentities identities = readLandmarkIdentityFile(path);
	std::map<LandmarkId, bool> listed;
	for (const auto& row : identities.landmarks) listed[row.landmark] = false;
	for (const auto& lm : landmarks)
	{
		const auto it = listed.find(lm.id);
		if (it == listed.end())
			throw InputError(path + ": no row for landmark " + std::to_string(lm.id) + " of landmarks.txt");
		it->second = true;
	}
	for (const auto& [id, in_map] : listed)
		if (!in_map) throw InputError(path + ": landmark " + std::to_string(id) + " is not in landmarks.txt");
	return identities;
}
}  // namespace

RunOutputs readRunOutputs(const std::string& dir)
{
	const std::filesystem::path d(dir);
	RunOutputs out;
	out.trajectory = readTrajectoryTum((d / "trajectory.tum").string());
	out.landmarks = readLandmarksTxt((d / "landmarks.txt").string());
	const std::string identities = (d / kLandmarkIdentityFileName).string();
	if (pathPresent(identities)) out.identities = identitiesOfMap(identities, out.landmarks);
	return out;
}

RunOutputs readReferenceRun(const std::string& dir, std::optional<std::size_t> steps)
{
	const std::string trajectory = (std::filesystem::path(dir) / "trajectory.tum").string();
	RunOutputs out;
	out.trajectory = readTrajectoryTum(trajectory, RunRole::Reference);
	out.landmarks = readLandmarksTxt((std::filesystem::path(dir) / "landmarks.txt").string(), RunRole::Reference);
	if (steps && out.trajectory.size() != *steps)
		throw InputError(
			trajectory + ": " + std::to_string(out.trajectory.size()) + " rows, the rawlog has " +
			std::to_string(*steps) + " steps (a reference run must be of the same rawlog, whole)");
	const std::string identities = (std::filesystem::path(dir) / kLandmarkIdentityFileName).string();
	if (pathPresent(identities)) out.identities = identitiesOfMap(identities, out.landmarks);
	return out;
}

GroundTruth runAsGroundTruth(const RunOutputs& run)
{
	GroundTruth truth;
	for (const LandmarkEstimate& l : run.landmarks) truth.landmarks[l.id] = l.mean;
	for (const TimedPose2D& row : run.trajectory) truth.path.emplace_back(row.pose.x, row.pose.y, row.pose.phi);
	return truth;
}

}  // namespace esif
