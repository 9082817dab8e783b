#include <esif/core/Errors.h>
#include <esif/formats/RawlogWriter.h>
#include <esif/models/Se2.h>

#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <set>

namespace esif
{
namespace
{
mrpt::obs::CActionCollection odometryAction(const StepInput& step, mrpt::Clock::time_point stamp)
{
	using mrpt::obs::CActionRobotMovement2D;
	const OdometryIncrement odo = step.odometry.value_or(OdometryIncrement{});
	// MRPT stores one triangle of the covariance: make it exactly symmetric so
	// what a reader gets back is bit-identical to what was written.
	const Eigen::Matrix3d cov = 0.5 * (odo.cov + odo.cov.transpose());
	CActionRobotMovement2D move;
	const mrpt::poses::CPose2D mean(toTPose2D(odo.delta));
	move.poseChange = mrpt::poses::CPosePDFGaussian::Create(mean, mrpt::math::CMatrixDouble33(cov));
	move.rawOdometryIncrementReading = mean;
	// Not emOdometry: for that method MRPT serializes only the raw increment
	// and its own motion-model settings, and rebuilds poseChange from them
	// when reading (CActionRobotMovement2D::serializeFrom), so our covariance
	// would be replaced by MRPT's default model. Any other method stores the
	// PDF itself; readers take poseChange (getBestMovementEstimation()).
	move.estimationMethod = CActionRobotMovement2D::emScan2DMatching;
	move.timestamp = stamp;
	mrpt::obs::CActionCollection acts;
	acts.insert(move);
	return acts;
}

mrpt::obs::CSensoryFrame scanFrame(const StepInput& step, const SensorNoise& noise, mrpt::Clock::time_point stamp)
{
	using mrpt::obs::CObservationBearingRange;
	const Scan scan = step.scan.value_or(Scan{});
	auto obs = CObservationBearingRange::Create();
	obs->timestamp = stamp;
	obs->sensorLabel = "RANGE_BEARING";
	obs->setSensorPose(mrpt::poses::CPose3D(mrpt::poses::CPose2D(toTPose2D(scan.sensor_on_robot))));
	obs->minSensorDistance = 0;
	obs->maxSensorDistance = static_cast<float>(scan.max_range_m);
	obs->fieldOfView_yaw = static_cast<float>(scan.fov_rad);
	obs->fieldOfView_pitch = 0;
	obs->validCovariances = false;
	obs->sensor_std_range = static_cast<float>(noise.std_range_m);
	obs->sensor_std_yaw = static_cast<float>(noise.std_bearing_rad);
	obs->sensor_std_pitch = 0;
	obs->sensedData.reserve(scan.measurements.size());
	std::set<LandmarkId> ids;
	for (const RangeBearing& m : scan.measurements)
	{
		// MRPT refuses to serialise a scan that measures a landmark twice, in
		// an exception naming neither step nor file: the readers of datasets
		// refuse such input at its line, and this says which step it was.
		if (m.id && !ids.insert(*m.id).second)
			throw InputError(
				"step " + std::to_string(step.index) + ": landmark ID " + std::to_string(*m.id) +
				" is measured twice in one scan (a rawlog scan holds each landmark once)");
		CObservationBearingRange::TMeasurement t;
		t.range = static_cast<float>(m.range_m);
		t.yaw = static_cast<float>(m.bearing_rad);
		t.pitch = 0;
		t.landmarkID = m.id ? static_cast<int32_t>(*m.id) : mrpt::obs::INVALID_LANDMARK_ID;
		t.covariance.setZero();
		obs->sensedData.push_back(t);
	}
	mrpt::obs::CSensoryFrame sf;
	sf.insert(obs);
	return sf;
}
}  // namespace

void appendStep(mrpt::serialization::CArchive& archive, const StepInput& step, const SensorNoise& noise)
{
	const auto stamp = mrpt::Clock::fromDouble(step.time_s);
	archive << odometryAction(step, stamp) << scanFrame(step, noise, stamp);
}

}  // namespace esif
