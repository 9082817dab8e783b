#include <esif/core/Errors.h>
#include <esif/core/TextInput.h>
#include <esif/formats/NumberText.h>
#include <esif/formats/RawlogReader.h>
#include <esif/models/Se2.h>

#include "GzipInflate.h"
#include "RawlogDigest.h"
#include "WholeReadStream.h"
#include <esif/safeio/FileSet.h>
#include <esif/safeio/Sandbox.h>

#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/system/datetime.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <type_traits>

namespace esif
{
namespace
{
using mrpt::obs::CObservationBearingRange;

/// No range-bearing sensor measures beyond this; a larger range (e.g. 3e38
/// from a corrupt byte) is a broken entry, not a far landmark [m].
constexpr double kMaxRangeM = 1e4;
/// No odometry increment between two steps moves further [m].
constexpr double kMaxIncrementM = 1e4;

/// Throws InputError naming `what` unless `cov` is a finite symmetric
/// positive-semidefinite 3x3 covariance (round-off tolerated).
void checkOdometryCovariance(const Eigen::Matrix3d& cov, const std::string& what)
{
	if (!cov.allFinite()) throw InputError(what + ": odometry covariance is not finite");
	const double scale = std::max(cov.cwiseAbs().maxCoeff(), 1e-300);
	if ((cov - cov.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
		throw InputError(what + ": odometry covariance is not symmetric");
	const double smallest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov, Eigen::EigenvaluesOnly).eigenvalues()(0);
	if (smallest < -1e-9 * scale)
		throw InputError(what + ": odometry covariance is not positive semidefinite (eigenvalue " +
						 number_text::text(smallest) + ")");
}

/// Throws InputError naming `what` unless the pose is finite and moves at
/// most kMaxIncrementM.
void checkOdometryPose(const Pose2& p, const std::string& what, const char* kind, double max_xy)
{
	if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p(2)))
		throw InputError(what + ": " + kind + " is not finite");
	if (std::abs(p.x()) > max_xy || std::abs(p.y()) > max_xy)
		throw InputError(what + ": " + kind + " (" + number_text::text(p.x()) + ", " + number_text::text(p.y()) + ") is beyond " +
						 number_text::text(max_xy) + " m");
}

/// MRPT reads the validCovariances flag as a raw byte into a bool: any value
/// but 0 or 1 is a corrupt entry (and reading it as a bool would be undefined).
bool covariancesFlagOf(const CObservationBearingRange& obs, const std::string& what)
{
	unsigned char raw = 0;
	static_assert(sizeof(obs.validCovariances) == 1);
	std::memcpy(&raw, &obs.validCovariances, 1);
	if (raw > 1) throw InputError(what + ": validCovariances flag is corrupt (byte " + std::to_string(raw) + ")");
	return raw == 1;
}

/// Accumulates rawlog entries into steps: odometry opens a step, a scan
/// closes it (see RawlogReader.h).
class StepBuilder
{
   public:
	StepBuilder(Rawlog& out, const RawlogReadOptions& options) : out_(out), options_(options) {}

	void onOdometry(const OdometryIncrement& inc, double t)
	{
		flushPending();
		pending_ = StepInput{};
		pending_->odometry = inc;
		pending_->time_s = t;
		out_.has_odometry = true;
	}

	/// Absolute odometry reading (CObservationOdometry): the increment is the
	/// difference of consecutive readings; the first reading only anchors.
	void onAbsoluteOdometry(const mrpt::poses::CPose2D& reading, double t, const std::string& where)
	{
		// Readings are absolute: bounded by the largest plausible world, not one step's motion.
		const Pose2 now = toPose2(reading.asTPose());
		checkOdometryPose(now, where, "odometry reading", 1e7);
		out_.has_odometry = true;
		if (last_reading_)
		{
			OdometryIncrement inc;
			inc.delta = inverseCompose(*last_reading_, now);
			inc.cov.diagonal() << std::pow(options_.odometry_obs_std_xy_m, 2),
				std::pow(options_.odometry_obs_std_xy_m, 2), std::pow(options_.odometry_obs_std_phi_rad, 2);
			onOdometry(inc, t);
		}
		last_reading_ = now;
	}

	void onScan(const CObservationBearingRange& obs, const mrpt::obs::CSensoryFrame::Ptr& frame, double t,
				const std::string& where)
	{
		StepInput step = pending_ ? *pending_ : StepInput{};
		pending_.reset();
		step.time_s = t;
		Scan scan;
		scan.sensor_on_robot = toPose2(mrpt::poses::CPose2D(obs.sensorLocationOnRobot).asTPose());
		if (!std::isfinite(scan.sensor_on_robot.x()) || !std::isfinite(scan.sensor_on_robot.y()) ||
			!std::isfinite(scan.sensor_on_robot(2)))
			throw InputError(where + ": sensor pose on the robot is not finite");
		scan.max_range_m = obs.maxSensorDistance;
		scan.fov_rad = obs.fieldOfView_yaw;
		if (obs.sensedData.size() > options_.max_measurements_per_scan)
			throw InputError(where + ": one scan holds " + std::to_string(obs.sensedData.size()) +
							 " measurements, more than max_measurements_per_scan = " +
							 std::to_string(options_.max_measurements_per_scan));
		std::vector<std::optional<LandmarkId>> ids;
		for (std::size_t i = 0; i < obs.sensedData.size(); ++i)
		{
			const auto& m = obs.sensedData[i];
			const std::string what = where + ", measurement " + std::to_string(i);
			if (!std::isfinite(m.range) || m.range < 0 || m.range > kMaxRangeM)
				throw InputError(what + ": range = " + number_text::text(m.range) + ": must be finite, >= 0 and <= " +
								 number_text::text(kMaxRangeM) + " m");
			if (!std::isfinite(m.yaw)) throw InputError(what + ": bearing is not finite");
			RangeBearing rb;
			rb.range_m = m.range;
			rb.bearing_rad = wrapAngle(m.yaw);
			rb.cov = measurementCovariance(obs, m, what);
			if (m.landmarkID < 0 && m.landmarkID != mrpt::obs::INVALID_LANDMARK_ID)
				throw InputError(what + ": landmark ID " + std::to_string(m.landmarkID) +
								 " is negative (IDs are >= 0; " + std::to_string(mrpt::obs::INVALID_LANDMARK_ID) +
								 " means none)");
			if (m.landmarkID != mrpt::obs::INVALID_LANDMARK_ID)
			{
				ids.emplace_back(m.landmarkID);
				if (!options_.hide_landmark_ids) rb.id = m.landmarkID;
			}
			else
				ids.emplace_back();
			scan.measurements.push_back(rb);
		}
		out_.measurement_count += scan.measurements.size();
		step.scan = std::move(scan);
		push(std::move(step), frame, std::move(ids));
	}

	void finish() { flushPending(); }

   private:
	Eigen::Matrix2d measurementCovariance(
		const CObservationBearingRange& obs, const CObservationBearingRange::TMeasurement& m,
		const std::string& what) const
	{
		Eigen::Matrix2d cov;
		if (covariancesFlagOf(obs, what))
			cov = m.covariance.asEigen().topLeftCorner<2, 2>();
		else
			cov = Eigen::Vector2d(std::pow(obs.sensor_std_range, 2), std::pow(obs.sensor_std_yaw, 2)).asDiagonal();
		// Each override replaces its own variance; a range-bearing correlation
		// in the rawlog no longer holds once one side's noise is replaced.
		const bool range_set = options_.sensor_std_range_m > 0, bearing_set = options_.sensor_std_bearing_rad > 0;
		if (range_set || bearing_set) cov(0, 1) = cov(1, 0) = 0;
		if (range_set) cov(0, 0) = std::pow(options_.sensor_std_range_m, 2);
		if (bearing_set) cov(1, 1) = std::pow(options_.sensor_std_bearing_rad, 2);
		if (!cov.allFinite() || Eigen::LLT<Eigen::Matrix2d>(cov).info() != Eigen::Success || cov(0, 0) <= 0 ||
			cov(1, 1) <= 0)
			throw InputError(
				what + ": sensor noise is zero or invalid (set [esif] sensor_std_range_m and sensor_std_bearing_deg)");
		return cov;
	}

	void flushPending()
	{
		if (pending_) push(std::move(*pending_), nullptr, {});
		pending_.reset();
	}

	void push(StepInput step, const mrpt::obs::CSensoryFrame::Ptr& frame, std::vector<std::optional<LandmarkId>> ids)
	{
		step.index = out_.steps.size();
		out_.steps.push_back(std::move(step));
		out_.frames.push_back(frame);
		out_.true_ids.push_back(std::move(ids));
	}

	Rawlog& out_;
	const RawlogReadOptions& options_;
	std::optional<StepInput> pending_;
	std::optional<Pose2> last_reading_;
};

double toSeconds(mrpt::Clock::time_point t)
{
	return t == INVALID_TIMESTAMP ? std::nan("") : mrpt::Clock::toDouble(t);
}

/// The raw value of an enum field MRPT deserialised from a (signed) integer
/// without checking it: read as bytes, since an enum holding a value outside
/// its enumerators must not be used as one.
template <class Enum>
std::int64_t rawEnumValue(const Enum& field)
{
	std::make_signed_t<std::underlying_type_t<Enum>> raw{};
	static_assert(sizeof(raw) == sizeof(field));
	std::memcpy(&raw, &field, sizeof(raw));
	return static_cast<std::int64_t>(raw);
}

/// Throws InputError naming `what` unless the enum fields of the odometry
/// action hold one of their defined values (a corrupt entry otherwise).
void checkMovementEnums(const mrpt::obs::CActionRobotMovement2D& act, const std::string& what)
{
	using Action = mrpt::obs::CActionRobotMovement2D;
	const auto method = rawEnumValue(act.estimationMethod);
	if (method != Action::emOdometry && method != Action::emScan2DMatching)
		throw InputError(what + ": odometry estimationMethod = " + std::to_string(method) +
						 " is none of MRPT's (0 odometry, 1 scan matching): a corrupt entry");
	const auto model = rawEnumValue(act.motionModelConfiguration.modelSelection);
	if (model != Action::mmGaussian && model != Action::mmThrun)
		throw InputError(what + ": odometry motion model = " + std::to_string(model) +
						 " is none of MRPT's (0 Gaussian, 1 Thrun): a corrupt entry");
}

OdometryIncrement incrementOf(const mrpt::obs::CActionRobotMovement2D& act, const std::string& where)
{
	if (!act.poseChange) throw InputError(where + ": odometry action without pose change");
	checkMovementEnums(act, where);
	const auto [cov, mean] = act.poseChange->getCovarianceAndMean();
	OdometryIncrement inc;
	inc.delta = toPose2(mean.asTPose());
	inc.cov = cov.asEigen();
	checkOdometryPose(inc.delta, where, "odometry increment", kMaxIncrementM);
	checkOdometryCovariance(inc.cov, where);
	return inc;
}

class EntryVisitor
{
   public:
	EntryVisitor(StepBuilder& builder, std::string path) : builder_(builder), path_(std::move(path)) {}

	void visit(const mrpt::serialization::CSerializable::Ptr& obj, std::size_t entry)
	{
		using namespace mrpt::obs;
		const std::string where = path_ + ": entry " + std::to_string(entry);
		if (auto acts = std::dynamic_pointer_cast<CActionCollection>(obj))
		{
			if (auto mv = acts->getBestMovementEstimation())
				builder_.onOdometry(incrementOf(*mv, where), toSeconds(mv->timestamp));
		}
		else if (auto sf = std::dynamic_pointer_cast<CSensoryFrame>(obj))
		{
			for (const auto& o : *sf) visitObservation(o, sf, where);
		}
		else if (auto o = std::dynamic_pointer_cast<CObservation>(obj))
		{
			auto frame = CSensoryFrame::Create();
			frame->insert(o);
			visitObservation(o, frame, where);
		}
		else if (auto log = std::dynamic_pointer_cast<CRawlog>(obj))
		{
			// Old-style files hold one serialized CRawlog with every entry inside.
			for (std::size_t i = 0; i < log->size(); ++i) visit(log->getAsGeneric(i), i);
		}
		else
			// A map or any other MRPT object: say what the file is instead of
			// reading on to "holds no odometry".
			throw InputError(
				where + ": " + (obj ? std::string(obj->GetRuntimeClass()->className) : std::string("a null object")) +
				" is not a rawlog entry (a rawlog holds CActionCollection, CSensoryFrame and CObservation objects)");
	}

   private:
	void visitObservation(const mrpt::obs::CObservation::Ptr& o, const mrpt::obs::CSensoryFrame::Ptr& frame,
						  const std::string& where)
	{
		using namespace mrpt::obs;
		if (auto odo = std::dynamic_pointer_cast<CObservationOdometry>(o))
			builder_.onAbsoluteOdometry(odo->odometry, toSeconds(odo->timestamp), where);
		else if (auto rb = std::dynamic_pointer_cast<CObservationBearingRange>(o))
			builder_.onScan(*rb, frame, toSeconds(rb->timestamp), where);
	}

	StepBuilder& builder_;
	std::string path_;
};

/// Timestamps are used when present and strictly increasing; otherwise (e.g.
/// simul-landmarks stamps every entry with the generation wall time) the
/// step index stands in for time.
void normaliseTimes(std::vector<StepInput>& steps)
{
	bool usable = true;
	for (std::size_t k = 0; k < steps.size() && usable; ++k)
		usable = std::isfinite(steps[k].time_s) && (k == 0 || steps[k].time_s > steps[k - 1].time_s);
	if (!usable)
		for (auto& s : steps) s.time_s = static_cast<double>(s.index);
}
/// Reads every entry of an inflated rawlog into steps. `progress` tells a
/// sandbox which entry is being read when MRPT's deserialiser fails on it.
Rawlog parseRawlog(const std::string& path, const InflatedFile& file, const RawlogReadOptions& options,
				   SandboxProgress* progress)
{
	WholeReadStream stream;
	stream.assignMemoryNotOwn(file.bytes.data(), file.bytes.size());
	auto archive = mrpt::serialization::archiveFrom(stream);

	Rawlog out;
	out.path = path;
	StepBuilder builder(out, options);
	EntryVisitor visitor(builder, path);
	for (std::size_t entry = 0;; ++entry)
	{
		if (progress) progress->position = entry;
		const auto before = stream.getPosition();
		if (before == file.bytes.size()) break;	 // clean end between entries
		mrpt::serialization::CSerializable::Ptr obj;
		try
		{
			obj = archive.ReadObject();
		}
		catch (const mrpt::serialization::CExceptionEOF&)
		{
			if (entry == 0) throw InputError(path + ": not an MRPT rawlog (empty or unreadable first entry)");
			out.truncation_warning = path + ": file ends inside entry " + std::to_string(entry) +
				"; read up to step " + std::to_string(out.steps.size());
			break;
		}
		catch (const std::bad_alloc&)
		{
			throw;	// the sandbox reports it as a declared size beyond the file
		}
		catch (const std::exception& e)
		{
			if (entry == 0) throw InputError(path + ": not an MRPT rawlog (first entry is not a serialized MRPT object)");
			// MRPT wraps an end of data met inside a nested object in its own
			// exception: a failure that consumed every byte left is a cut file,
			// one that stopped before the end is a corrupt entry.
			if (stream.getPosition() < file.bytes.size() && !stream.endedInsideValue())
				throw InputError(path + ": entry " + std::to_string(entry) + " is corrupt: " + oneLineReason(e.what()));
			out.truncation_warning = path + ": file ends inside entry " + std::to_string(entry) +
				"; read up to step " + std::to_string(out.steps.size());
			break;
		}
		visitor.visit(obj, entry);
	}
	builder.finish();
	if (file.stream_truncated && !out.truncation_warning)
		out.truncation_warning = path + ": gzip stream is cut after entry " + std::to_string(out.steps.size());
	// A cut at the very end may leave a final odometry without its scan: keep
	// it only if the file ended cleanly.
	if (out.truncation_warning && !out.steps.empty() && !out.steps.back().scan)
	{
		out.steps.pop_back();
		out.frames.pop_back();
		out.true_ids.pop_back();
	}

	if (out.steps.empty()) throw InputError(path + ": rawlog holds no odometry and no range-bearing observation");
	if (!out.has_odometry) throw InputError(path + ": rawlog holds no odometry (CActionRobotMovement2D or CObservationOdometry)");
	if (out.measurement_count == 0 &&
		std::none_of(out.steps.begin(), out.steps.end(), [](const StepInput& s) { return s.scan.has_value(); }))
		throw InputError(path + ": rawlog holds no range-bearing observations (CObservationBearingRange)");
	normaliseTimes(out.steps);
	return out;
}

/// Memory a rawlog's entries may take while read: a fixed allowance plus a
/// multiple of the inflated size. Reading keeps every entry twice (as MRPT
/// objects for the maps and as plugin input); grid1225_large, 9.5 MB
/// inflated, takes about 110 MB (12 bytes per file byte). An allocation
/// beyond the budget is a count the file cannot back.
constexpr std::size_t kReadAllowanceBytes = std::size_t{256} << 20;
constexpr std::size_t kReadBytesPerFileByte = 64;
/// CPU time allowed for reading: MRPT reads well over 10 MB/s, so this is
/// reached only by a corrupt count that keeps its reader looping.
constexpr unsigned kReadCpuSeconds = 60;
constexpr unsigned kReadCpuSecondsPerMiB = 2;

SandboxLimits readLimitsFor(std::size_t bytes)
{
	SandboxLimits limits;
	limits.address_space_bytes = kReadAllowanceBytes + kReadBytesPerFileByte * bytes;
	limits.cpu_seconds = kReadCpuSeconds + kReadCpuSecondsPerMiB * static_cast<unsigned>(bytes >> 20);
	return limits;
}

/// Reads the rawlog once in a sandboxed child. A fault there becomes one
/// line naming the entry; success proves the same bytes read safely here,
/// and returns the digest (RawlogDigest.h) of what the child read.
std::uint32_t checkInSandbox(const std::string& path, const InflatedFile& file, const RawlogReadOptions& options)
{
	const SandboxLimits limits = readLimitsFor(file.bytes.size());
	const SandboxOutcome outcome = runInSandbox(
		[&](SandboxProgress& progress) { progress.result = digestOf(parseRawlog(path, file, options, &progress)); },
		limits);
	const std::string entry = path + ": entry " + std::to_string(outcome.position);
	switch (outcome.kind)
	{
		case SandboxOutcome::Kind::kSucceeded:
			return static_cast<std::uint32_t>(outcome.result);
		case SandboxOutcome::Kind::kFailed:
			throw InputError(oneLineReason(outcome.message));
		case SandboxOutcome::Kind::kOutOfMemory:
			throw InputError(entry + " declares more data than the file holds: reading it needs over " +
							 std::to_string(limits.address_space_bytes >> 20) + " MiB, the limit for " +
							 std::to_string(file.bytes.size()) + " bytes of rawlog");
		case SandboxOutcome::Kind::kCpuLimit:
			throw InputError(entry + " is corrupt: reading it took over " + std::to_string(limits.cpu_seconds) +
							 " s of CPU");
		case SandboxOutcome::Kind::kInterrupted:
			throw InputError(path + ": reading stopped by " + strsignal(outcome.signal_number));
		case SandboxOutcome::Kind::kCrashed:
			break;
	}
	throw InputError(entry + " is corrupt: MRPT's deserialiser crashed on it (" +
					 (outcome.signal_number ? std::string(strsignal(outcome.signal_number)) : outcome.message) + ")");
}

/// The read the sandboxed child vouched for, done again here: both must
/// come to the same (the child decides what the file holds), or the file is
/// refused rather than read one way here and another way there.
Rawlog readVouchedFor(const std::string& path, const InflatedFile& file, const RawlogReadOptions& options)
{
	const std::uint32_t vouched = checkInSandbox(path, file, options);
	Rawlog log = parseRawlog(path, file, options, nullptr);
	if (digestOf(log) != vouched)
		throw InputError(
			path + ": read two different ways (MRPT took a value from memory it had not read into): a corrupt entry");
	return log;
}
}  // namespace

Rawlog readRawlogFromMemory(const std::string& name, std::string bytes, const RawlogReadOptions& options)
{
	if (bytes.empty()) throw InputError(name + ": file holds no data");
	return readVouchedFor(name, InflatedFile{std::move(bytes), false}, options);
}

Rawlog readRawlog(const std::string& path, const RawlogReadOptions& options)
{
	requireRegularFile(path, "rawlog file");
	// A rawlog whose replacement (with its ground truth) was cut in two by a
	// kill is not read beside a ground truth that is not its own.
	requireCompleteFileSet(path);
	return readVouchedFor(path, inflateFile(path), options);
}

}  // namespace esif
