#pragma once
/// \file MrclamFiles.h
/// The text files of one UTIAS MRCLAM recording (Leung et al., IJRR 2011;
/// shared/data/mrclam/README.md), read strictly: every line of the right
/// token count, every field a finite number within a plausible bound, times
/// never going back, subjects and barcodes unique. The first problem is an
/// InputError "FILE:LINE: ...". MrclamImporter.cpp turns the records into
/// rawlog steps.

#include <map>
#include <string>
#include <vector>

namespace esif::mrclam
{
/// `time v w`: commanded forward speed [m/s] and turn rate [rad/s], held
/// until the next command.
struct VelocityCommand
{
	double time_s = 0;
	double v_mps = 0;
	double w_radps = 0;
};

/// `time barcode range bearing` [s, -, m, rad].
struct BarcodeMeasurement
{
	double time_s = 0;
	long barcode = 0;
	double range_m = 0;
	double bearing_rad = 0;
};

/// `time x y theta` (Vicon) [s, m, m, rad].
struct TruePose
{
	double time_s = 0;
	double x_m = 0;
	double y_m = 0;
	double theta_rad = 0;
};

/// `subject x y std_x std_y` (Vicon) [-, m, m, m, m].
struct TrueLandmark
{
	long subject = 0;
	double x_m = 0;
	double y_m = 0;
};

/// Subjects 1-5 are the robots, 6-20 the landmarks.
constexpr long kFirstLandmarkSubject = 6;
constexpr long kLastSubject = 20;

/// Barcodes.dat: barcode -> subject.
std::map<long, long> readBarcodes(const std::string& path);
std::vector<TrueLandmark> readLandmarkTruth(const std::string& path);
std::vector<VelocityCommand> readOdometry(const std::string& path);
std::vector<BarcodeMeasurement> readMeasurements(const std::string& path);
std::vector<TruePose> readRobotTruth(const std::string& path);

/// The files of robot `robot` (1-5) in the recording folder `dir`.
std::string odometryFile(const std::string& dir, int robot);
std::string measurementFile(const std::string& dir, int robot);
std::string robotTruthFile(const std::string& dir, int robot);
std::string barcodesFile(const std::string& dir);
std::string landmarkTruthFile(const std::string& dir);

}  // namespace esif::mrclam
