#pragma once
/// \file MrptKfSlamReplay.h
/// MRPT's own EKF SLAM (CRangeBearingKFSLAM2D, full EKF, landmark IDs) over a
/// rawlog, without the kf-slam app's logging: the reference the EKF plugin is
/// checked against (tests) and timed against (bench). Header-only so the
/// benchmark and the test share it without a library of its own.

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/slam/CRangeBearingKFSLAM2D.h>

#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace esif::bench
{
struct MrptKfSlamResult
{
	std::map<std::int64_t, Eigen::Vector2d> landmarks;	///< final means by landmark ID
	std::size_t steps = 0;
	double filter_wall_s = 0;  ///< the filter loop only (the rawlog is read beforehand)
};

/// Sensor noise as 1-sigma range [m] and bearing [rad]; MRPT keeps both as float.
inline MrptKfSlamResult replayMrptKfSlam(const std::string& rawlog, float std_range_m, float std_bearing_rad)
{
	mrpt::slam::CRangeBearingKFSLAM2D kf;
	kf.options.std_sensor_range = std_range_m;
	kf.options.std_sensor_yaw = std_bearing_rad;
	kf.KF_options.method = mrpt::bayes::kfEKFNaive;
	kf.KF_options.verbosity_level = mrpt::system::LVL_ERROR;
	kf.KF_options.enable_profiler = false;

	// A sensory frame before any action (the first of simul-landmarks logs)
	// is processed with an empty action, as esif does, so both filters see
	// exactly the same data.
	std::vector<std::pair<mrpt::obs::CActionCollection::Ptr, mrpt::obs::CSensoryFrame::Ptr>> pairs;
	{
		mrpt::io::CFileGZInputStream f(rawlog);
		auto ar = mrpt::serialization::archiveFrom(f);
		auto acts = mrpt::obs::CActionCollection::Create();
		for (;;)
		{
			mrpt::serialization::CSerializable::Ptr obj;
			try
			{
				obj = ar.ReadObject();
			}
			catch (const mrpt::serialization::CExceptionEOF&)
			{
				break;
			}
			if (auto a = std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(obj)) acts = a;
			if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(obj))
			{
				pairs.emplace_back(acts, sf);
				acts = mrpt::obs::CActionCollection::Create();
			}
		}
	}
	MrptKfSlamResult out;
	const auto t0 = std::chrono::steady_clock::now();
	for (auto& [acts, sf] : pairs) kf.processActionObservation(acts, sf);
	out.filter_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
	out.steps = pairs.size();

	mrpt::poses::CPosePDFGaussian pose;
	std::vector<mrpt::math::TPoint2D> lms;
	std::map<unsigned int, mrpt::maps::CLandmark::TLandmarkID> ids;
	mrpt::math::CVectorDouble x;
	mrpt::math::CMatrixDouble P;
	kf.getCurrentState(pose, lms, ids, x, P);
	for (std::size_t i = 0; i < lms.size(); ++i) out.landmarks[ids.at(i)] = {lms[i].x, lms[i].y};
	return out;
}

}  // namespace esif::bench
