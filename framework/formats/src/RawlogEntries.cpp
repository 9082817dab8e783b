/// \file RawlogEntries.cpp
/// See RawlogEntries.h.

#include "RawlogEntries.h"

#include <esif/core/Errors.h>
#include <esif/formats/NumberText.h>
#include <esif/models/Se2.h>

#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/system/datetime.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace esif::rawlog_entries
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

}  // namespace

StepBuilder::StepBuilder(const RawlogReadOptions& options, StepSink sink) : options_(options), sink_(std::move(sink)) {}

void StepBuilder::onOdometry(const OdometryIncrement& inc, double t)
{
	flushPending();
	pending_ = StepInput{};
	pending_->odometry = inc;
	pending_->time_s = t;
	has_odometry_ = true;
}

void StepBuilder::onAbsoluteOdometry(const mrpt::poses::CPose2D& reading, double t, const std::string& where)
{
	// Readings are absolute: bounded by the largest plausible world, not one step's motion.
	const Pose2 now = toPose2(reading.asTPose());
	checkOdometryPose(now, where, "odometry reading", 1e7);
	has_odometry_ = true;
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

void StepBuilder::onScan(const CObservationBearingRange& obs, const mrpt::obs::CSensoryFrame::Ptr& frame, double t,
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
	// Reserved: grown one by one, a scan's vectors hold up to twice their
	// measurements, and the steps of a long log are most of what a run holds.
	std::vector<std::optional<LandmarkId>> ids;
	ids.reserve(obs.sensedData.size());
	scan.measurements.reserve(obs.sensedData.size());
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
	measurement_count_ += scan.measurements.size();
	step.scan = std::move(scan);
	sink_({std::move(step), frame, std::move(ids)});
}

void StepBuilder::finish() { flushPending(); }

Eigen::Matrix2d StepBuilder::measurementCovariance(
	const CObservationBearingRange& obs, const CObservationBearingRange::TMeasurement& m, const std::string& what) const
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

void StepBuilder::flushPending()
{
	if (pending_) sink_({std::move(*pending_), nullptr, {}});
	pending_.reset();
}

void EntryVisitor::visit(const mrpt::serialization::CSerializable::Ptr& obj, std::size_t entry)
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

void EntryVisitor::visitObservation(
	const mrpt::obs::CObservation::Ptr& o, const mrpt::obs::CSensoryFrame::Ptr& frame, const std::string& where)
{
	using namespace mrpt::obs;
	if (auto odo = std::dynamic_pointer_cast<CObservationOdometry>(o))
		builder_.onAbsoluteOdometry(odo->odometry, toSeconds(odo->timestamp), where);
	else if (auto rb = std::dynamic_pointer_cast<CObservationBearingRange>(o))
		builder_.onScan(*rb, frame, toSeconds(rb->timestamp), where);
}

}  // namespace esif::rawlog_entries
