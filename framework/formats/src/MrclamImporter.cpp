/// \file MrclamImporter.cpp
/// One MRCLAM robot into a rawlog and its ground truth; see MrclamImporter.h.

#include "ImportOptions.h"
#include "MrclamFiles.h"

#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/formats/GroundTruth.h>
#include <esif/formats/GzArchive.h>
#include <esif/formats/MrclamImporter.h>
#include <esif/formats/RawlogWriter.h>
#include <esif/models/Se2.h>
#include <esif/safeio/AtomicFile.h>
#include <esif/safeio/OutputApart.h>

#include <mrpt/core/format.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

namespace esif
{
namespace
{
using namespace mrclam;

constexpr double kDeg = M_PI / 180.0;

/// The landmark measurements of one robot, one entry per distinct time.
struct TimedScans
{
	std::vector<double> times;
	std::vector<std::vector<RangeBearing>> scans;
	std::size_t robot_measurements = 0;
	std::size_t unknown_barcodes = 0;
	std::set<long> landmarks;
};

TimedScans landmarkScans(
	const std::vector<BarcodeMeasurement>& measurements, const std::map<long, long>& subject_of, bool keep_ids)
{
	TimedScans out;
	for (const auto& m : measurements)
	{
		const auto subject = subject_of.find(m.barcode);
		if (subject == subject_of.end())
		{
			++out.unknown_barcodes;	// a misread into a barcode no subject carries
			continue;
		}
		if (subject->second < kFirstLandmarkSubject)
		{
			++out.robot_measurements;
			continue;
		}
		if (out.times.empty() || m.time_s != out.times.back())
		{
			out.times.push_back(m.time_s);
			out.scans.emplace_back();
		}
		RangeBearing rb;
		rb.range_m = m.range_m;
		rb.bearing_rad = m.bearing_rad;
		if (keep_ids) rb.id = subject->second;
		out.scans.back().push_back(rb);
		out.landmarks.insert(subject->second);
	}
	return out;
}

/// The velocity commands between two times, as segments: a command holds
/// from its time until the next one's; before the first, the robot stands.
class CommandTrack
{
   public:
	explicit CommandTrack(const std::vector<VelocityCommand>& commands) : commands_(commands) {}

	/// Segments covering [t0, t1]; calls must come in increasing time.
	std::vector<VelocitySegment> between(double t0, double t1)
	{
		while (next_ < commands_.size() && commands_[next_].time_s <= t0) ++next_;
		std::vector<VelocitySegment> out;
		double from = t0;
		for (std::size_t i = next_; from < t1; ++i)
		{
			const double until = i < commands_.size() ? std::min(commands_[i].time_s, t1) : t1;
			if (until > from)
			{
				const VelocityCommand* held = i > 0 ? &commands_[i - 1] : nullptr;
				out.push_back({until - from, held ? held->v_mps : 0.0, held ? held->w_radps : 0.0});
			}
			from = until;
		}
		return out;
	}

   private:
	const std::vector<VelocityCommand>& commands_;
	std::size_t next_ = 0;
};

/// Longest time the measurements may go on past the last velocity command,
/// or start before the first [s]. The robots send a command at least every
/// 1.03 s in all of dataset 6; measurements far beyond the commands are an
/// odometry file cut short, whose last command would otherwise be driven on
/// (or the robot taken to stand) for the rest of the recording.
constexpr double kMaxUncommandedTime_s = 5.0;

/// Throws InputError naming the odometry file unless its commands cover the
/// measurement times `times` (increasing) to within kMaxUncommandedTime_s.
void requireCommandsCover(
	const std::vector<VelocityCommand>& commands, const std::vector<double>& times, const std::string& path)
{
	const double after = times.back() - commands.back().time_s, before = commands.front().time_s - times.front();
	const auto seconds = [](double s) { return mrpt::format("%.1f s", s); };
	const auto fail = [&](const std::string& what) {
		throw InputError(
			path + ": " + what + ": the file is cut short (more than " + seconds(kMaxUncommandedTime_s) +
			" without a command; a recording sends one at least every second or so)");
	};
	if (after > kMaxUncommandedTime_s)
		fail("its last velocity command is at " + formatNumber(commands.back().time_s) +
			 " s, but the measurements go on for " + seconds(after) + " more");
	if (before > kMaxUncommandedTime_s)
		fail("its first velocity command is at " + formatNumber(commands.front().time_s) + " s, " + seconds(before) +
			 " after the first measurement");
}

/// The Vicon track, linearly interpolated (the heading along the shorter arc).
class TruthTrack
{
   public:
	TruthTrack(const std::vector<TruePose>& poses, std::string path) : poses_(poses), path_(std::move(path)) {}

	Pose2 at(double t) const
	{
		if (t < poses_.front().time_s || t > poses_.back().time_s)
			throw InputError(
				path_ + ": the ground truth covers " + formatNumber(poses_.front().time_s) + " to " +
				formatNumber(poses_.back().time_s) + " s, not the step at " + formatNumber(t) + " s");
		const auto after = std::lower_bound(
			poses_.begin(), poses_.end(), t, [](const TruePose& p, double time) { return p.time_s < time; });
		if (after == poses_.begin() || after->time_s == t) return poseOf(*after);
		const TruePose& before = *(after - 1);
		const double a = (t - before.time_s) / (after->time_s - before.time_s);
		return {before.x_m + a * (after->x_m - before.x_m), before.y_m + a * (after->y_m - before.y_m),
				wrapAngle(before.theta_rad + a * wrapAngle(after->theta_rad - before.theta_rad))};
	}

   private:
	static Pose2 poseOf(const TruePose& p) { return {p.x_m, p.y_m, wrapAngle(p.theta_rad)}; }

	const std::vector<TruePose>& poses_;
	std::string path_;
};

void validateOptions(const MrclamImportOptions& o)
{
	const std::string who = "import mrclam";
	if (o.robot < 1 || o.robot > 5)
		throw ConfigError(who + ": --robot " + std::to_string(o.robot) + ": must be 1 to 5");
	checkSensorNoise(who, o.std_range_m, o.std_bearing_deg);
	checkImportOption(who, "--max-range-m", o.max_range_m, 0, 1000.0, "farthest plausible landmark");
	checkImportOption(who, "--fov-deg", o.fov_deg, 0, 360.0, "a full circle");
	o.odometry_noise.validate(who);
}

/// The truth in the frame of the first step's true pose.
GroundTruth truthInFirstPoseFrame(
	const std::vector<TrueLandmark>& landmarks, const TruthTrack& track, const std::vector<double>& times)
{
	const Pose2 origin = track.at(times.front());
	GroundTruth truth;
	for (const auto& l : landmarks)
		truth.landmarks[l.subject] = inverseCompose(origin, Pose2(l.x_m, l.y_m, 0)).head<2>();
	truth.path.reserve(times.size());
	for (const double t : times) truth.path.push_back(inverseCompose(origin, track.at(t)));
	return truth;
}
}  // namespace

MrclamImportSummary importMrclam(
	const std::string& dataset_dir, const std::string& out_rawlog, const MrclamImportOptions& options)
{
	validateOptions(options);
	const int robot = options.robot;
	requireOutputApart(out_rawlog, {{"the MRCLAM recording", dataset_dir}});
	const auto subject_of = readBarcodes(barcodesFile(dataset_dir));
	const auto landmarks = readLandmarkTruth(landmarkTruthFile(dataset_dir));
	const auto commands = readOdometry(odometryFile(dataset_dir, robot));
	const auto measurements = readMeasurements(measurementFile(dataset_dir, robot));
	const auto vicon = readRobotTruth(robotTruthFile(dataset_dir, robot));

	const TimedScans scans = landmarkScans(measurements, subject_of, options.keep_ids);
	if (scans.times.empty())
		throw InputError(measurementFile(dataset_dir, robot) + ": no measurement of a landmark (subjects 6-20)");
	const TruthTrack track(vicon, robotTruthFile(dataset_dir, robot));
	const GroundTruth truth = truthInFirstPoseFrame(landmarks, track, scans.times);

	Scan scan_template;
	scan_template.max_range_m = options.max_range_m;
	scan_template.fov_rad = options.fov_deg * kDeg;
	requireCommandsCover(commands, scans.times, odometryFile(dataset_dir, robot));
	CommandTrack drive(commands);
	std::vector<StepInput> steps(scans.times.size());
	MrclamImportSummary summary;
	for (std::size_t k = 0; k < steps.size(); ++k)
	{
		StepInput& step = steps[k];
		step.index = k;
		step.time_s = scans.times[k];
		if (k > 0)
		{
			step.odometry = velocityOdometry(drive.between(scans.times[k - 1], scans.times[k]), options.odometry_noise);
			summary.longest_gap_s = std::max(summary.longest_gap_s, scans.times[k] - scans.times[k - 1]);
		}
		step.scan = scan_template;
		step.scan->measurements = scans.scans[k];
		summary.measurements += scans.scans[k].size();
	}

	const auto folder = std::filesystem::path(out_rawlog).parent_path();
	if (!folder.empty()) ensureDirectory(folder.string());
	const SensorNoise noise{options.std_range_m, options.std_bearing_deg * kDeg};
	writeGzArchiveAtomically(
		out_rawlog, [&](mrpt::serialization::CArchive& ar) { for (const auto& step : steps) appendStep(ar, step, noise); },
		9);
	saveGroundTruth(truth, groundTruthPrefixFor(out_rawlog));

	summary.steps = steps.size();
	summary.robot_measurements = scans.robot_measurements;
	summary.unknown_barcodes = scans.unknown_barcodes;
	summary.landmarks = scans.landmarks.size();
	summary.duration_s = scans.times.back() - scans.times.front();
	return summary;
}

}  // namespace esif
