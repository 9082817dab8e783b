/// \file make_seeds.cpp
/// Writes the rawlog fuzz target's seed corpus: one small inflated rawlog in
/// each form the reader accepts, so fuzzing starts from every entry kind.
///   make_seeds <folder>   (scripts/fuzz.sh copies tests/fuzz/seeds/rawlog)

#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <iostream>
#include <string>

namespace
{
using namespace mrpt::obs;

/// Odometry as MRPT's grabbers write it (emOdometry: the PDF is rebuilt from
/// the motion model) or with an explicit Gaussian (emScan2DMatching).
CActionCollection action(int k, bool motion_model)
{
	CActionRobotMovement2D mv;
	const mrpt::poses::CPose2D delta(0.2, 0.01 * k, 0.05);
	if (motion_model)
		mv.computeFromOdometry(delta, CActionRobotMovement2D::TMotionModelOptions());
	else
	{
		mv.estimationMethod = CActionRobotMovement2D::emScan2DMatching;
		mrpt::math::CMatrixDouble33 cov;
		cov.setDiagonal(std::vector<double>{1e-4, 1e-4, 1e-5});
		mv.poseChange = mrpt::poses::CPosePDFGaussian::Create(delta, cov);
	}
	CActionCollection acts;
	acts.insert(mv);
	return acts;
}

CObservationBearingRange::Ptr scan(int k, bool with_ids, bool with_covariances)
{
	auto obs = CObservationBearingRange::Create();
	obs->sensor_std_range = 0.1f;
	obs->sensor_std_yaw = 0.01f;
	obs->maxSensorDistance = 5;
	obs->fieldOfView_yaw = static_cast<float>(M_PI);
	obs->validCovariances = with_covariances;
	for (int i = 0; i < 3; ++i)
	{
		CObservationBearingRange::TMeasurement m;
		m.range = 1.0f + 0.5f * static_cast<float>(i + k % 3);
		m.yaw = -0.5f + 0.4f * static_cast<float>(i);
		m.pitch = 0;
		m.landmarkID = with_ids ? i + k % 4 : INVALID_LANDMARK_ID;
		m.covariance.setDiagonal(std::vector<double>{0.01, 1e-4, 1e-4});
		obs->sensedData.push_back(m);
	}
	return obs;
}

CSensoryFrame frameOf(const CObservation::Ptr& o)
{
	CSensoryFrame sf;
	sf.insert(o);
	return sf;
}

void writeActionsAndFrames(const std::string& path, bool motion_model, bool ids, bool covariances)
{
	mrpt::io::CFileOutputStream f(path);
	auto ar = mrpt::serialization::archiveFrom(f);
	for (int k = 0; k < 4; ++k) ar << action(k, motion_model) << frameOf(scan(k, ids, covariances));
}

void writeObservationsOnly(const std::string& path)
{
	mrpt::io::CFileOutputStream f(path);
	auto ar = mrpt::serialization::archiveFrom(f);
	for (int k = 0; k < 4; ++k)
	{
		CObservationOdometry odo;
		odo.odometry = mrpt::poses::CPose2D(0.2 * k, 0, 0.05 * k);
		ar << odo << *scan(k, true, false);
	}
}

/// Old-style file: one serialized CRawlog holding every entry.
void writeOneRawlogObject(const std::string& path)
{
	CRawlog log;
	for (int k = 0; k < 3; ++k)
	{
		auto acts = action(k, false);
		auto frame = frameOf(scan(k, true, false));
		log.insert(acts);
		log.insert(frame);
	}
	mrpt::io::CFileOutputStream f(path);
	auto ar = mrpt::serialization::archiveFrom(f);
	ar << log;
}
}  // namespace

int main(int argc, char** argv)
{
	if (argc != 2)
	{
		std::cerr << "usage: make_seeds <folder>\n";
		return 2;
	}
	const std::string dir = argv[1];
	writeActionsAndFrames(dir + "/motion_model_ids.rawlog", true, true, false);
	writeActionsAndFrames(dir + "/gaussian_no_ids_covariances.rawlog", false, false, true);
	writeObservationsOnly(dir + "/observations_only.rawlog");
	writeOneRawlogObject(dir + "/one_crawlog_object.rawlog");
	return 0;
}
