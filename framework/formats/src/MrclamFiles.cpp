/// \file MrclamFiles.cpp
/// The MRCLAM files read strictly; see MrclamFiles.h.

#include "MrclamFiles.h"

#include <esif/core/Errors.h>
#include <esif/core/TextInput.h>
#include "NumberRow.h"

#include <cmath>
#include <map>
#include <set>

namespace esif::mrclam
{
namespace
{
// Plausibility bounds. The recording's own extremes are far inside them
// (iRobot Create robots below 0.5 m/s and 2 rad/s, a 15 m x 8 m room, Unix
// times of 2009), so a value beyond is a corrupt or mis-scaled file.
constexpr double kMinTime_s = 0, kMaxTime_s = 1e10;  // Unix seconds up to the year 2286
constexpr double kMaxSpeed_mps = 10;
constexpr double kMaxTurnRate_radps = 20;
constexpr double kMaxRange_m = 100;	 // a camera reading barcodes
constexpr long kMaxBarcode = 1000000;

bool isBlankOrComment(const std::string& line)
{
	const auto first = line.find_first_not_of(" \t\r");
	return first == std::string::npos || line[first] == '#';
}

/// Calls `row(NumberRow)` for every data line of `path` (`what` names the file's kind).
template <class OnRow>
void forEachRow(const std::string& path, const std::string& what, const NumberRow::Columns& columns, OnRow&& row)
{
	TextLineReader in(path, what);
	for (std::string line; in.next(line);)
		if (!isBlankOrComment(line)) row(NumberRow(line, columns, in.where()));
}

/// Column 0 of `row` as a time that does not go back from `previous` (updated).
double timeOf(const NumberRow& row, double& previous)
{
	const double t = row.bounded(0, kMinTime_s, kMaxTime_s, "s", "Unix seconds");
	if (t < previous) row.fail(0, "goes back in time (the line before has " + std::to_string(previous) + ")");
	previous = t;
	return t;
}

const NumberRow::Columns kBarcodeColumns({"subject", "barcode"});
const NumberRow::Columns kLandmarkColumns({"subject", "x", "y", "std_x", "std_y"});
const NumberRow::Columns kOdometryColumns({"time", "v", "w"});
const NumberRow::Columns kMeasurementColumns({"time", "barcode", "range", "bearing"});
const NumberRow::Columns kTruthColumns({"time", "x", "y", "theta"});

std::string robotFile(const std::string& dir, int robot, const char* kind)
{
	return dir + "/Robot" + std::to_string(robot) + "_" + kind + ".dat";
}
}  // namespace

std::map<long, long> readBarcodes(const std::string& path)
{
	std::map<long, long> subject_of;
	std::set<long> subjects;
	forEachRow(path, "MRCLAM barcode table", kBarcodeColumns, [&](const NumberRow& row) {
		const long subject = row.wholeNumber(0, 1, kLastSubject);
		const long barcode = row.wholeNumber(1, 0, kMaxBarcode);
		if (!subjects.insert(subject).second) row.fail(0, "subject listed twice");
		if (!subject_of.emplace(barcode, subject).second) row.fail(1, "barcode listed twice");
	});
	if (subject_of.empty()) throw InputError(path + ": no barcode");
	return subject_of;
}

std::vector<TrueLandmark> readLandmarkTruth(const std::string& path)
{
	std::vector<TrueLandmark> out;
	std::set<long> seen;
	forEachRow(path, "MRCLAM landmark ground truth", kLandmarkColumns, [&](const NumberRow& row) {
		const long subject = row.wholeNumber(0, kFirstLandmarkSubject, kLastSubject);
		if (!seen.insert(subject).second) row.fail(0, "landmark listed twice");
		out.push_back({subject, row.coordinate(1), row.coordinate(2)});
	});
	if (out.empty()) throw InputError(path + ": no landmark");
	return out;
}

std::vector<VelocityCommand> readOdometry(const std::string& path)
{
	std::vector<VelocityCommand> out;
	double previous = kMinTime_s;
	forEachRow(path, "MRCLAM odometry", kOdometryColumns, [&](const NumberRow& row) {
		out.push_back({timeOf(row, previous),
					   row.bounded(1, -kMaxSpeed_mps, kMaxSpeed_mps, "m/s", "a ground robot's speed"),
					   row.bounded(2, -kMaxTurnRate_radps, kMaxTurnRate_radps, "rad/s", "a ground robot's turn rate")});
	});
	if (out.empty()) throw InputError(path + ": no velocity command");
	return out;
}

std::vector<BarcodeMeasurement> readMeasurements(const std::string& path)
{
	std::vector<BarcodeMeasurement> out;
	double previous = kMinTime_s;
	// The barcodes read at the current time, with where each was: one image
	// shows a barcode once, and a scan cannot hold one landmark twice.
	std::map<long, std::string> read_now;
	forEachRow(path, "MRCLAM measurements", kMeasurementColumns, [&](const NumberRow& row) {
		const double before = previous;
		const double t = timeOf(row, previous);
		if (t != before) read_now.clear();
		const long barcode = row.wholeNumber(1, 0, kMaxBarcode);
		if (const auto [first, fresh] = read_now.emplace(barcode, row.where()); !fresh)
			row.fail(1, "read twice at the same time (first on line " + first->second.substr(first->second.rfind(':') + 1) +
							"): a repeated line");
		out.push_back({t, barcode,
					   row.bounded(2, 1e-3, kMaxRange_m, "m", "a camera's range; at 0 the bearing is undefined"),
					   row.bounded(3, -M_PI, M_PI, "rad", "a bearing")});
	});
	return out;
}

std::vector<TruePose> readRobotTruth(const std::string& path)
{
	std::vector<TruePose> out;
	double previous = kMinTime_s;
	forEachRow(path, "MRCLAM robot ground truth", kTruthColumns, [&](const NumberRow& row) {
		const double t = timeOf(row, previous);
		out.push_back({t, row.coordinate(1), row.coordinate(2), row.heading(3)});
	});
	if (out.empty()) throw InputError(path + ": no ground-truth pose");
	return out;
}

std::string odometryFile(const std::string& dir, int robot) { return robotFile(dir, robot, "Odometry"); }
std::string measurementFile(const std::string& dir, int robot) { return robotFile(dir, robot, "Measurement"); }
std::string robotTruthFile(const std::string& dir, int robot) { return robotFile(dir, robot, "Groundtruth"); }
std::string barcodesFile(const std::string& dir) { return dir + "/Barcodes.dat"; }
std::string landmarkTruthFile(const std::string& dir) { return dir + "/Landmark_Groundtruth.dat"; }

}  // namespace esif::mrclam
