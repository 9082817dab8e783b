/// \file mrpt_kf_replay.cpp
/// The bare MRPT EKF SLAM filter (CRangeBearingKFSLAM2D, full EKF, landmark
/// IDs) over a rawlog, without the kf-slam app's per-step console and file
/// logging: the fairest competitor for the EKF plugin's filter time.
/// Prints the filter-loop wall time and writes the final landmarks as
/// `id x y` lines to the file given as 3rd argument (optional).
///
/// usage: mrpt_kf_replay RAWLOG STD_RANGE_M [LANDMARKS_OUT] [STD_BEARING_DEG]

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/slam/CRangeBearingKFSLAM2D.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <vector>

int main(int argc, char** argv)
{
	if (argc < 3)
	{
		std::cerr << "usage: mrpt_kf_replay RAWLOG STD_RANGE_M [LANDMARKS_OUT] [STD_BEARING_DEG]\n";
		return 2;
	}
	mrpt::slam::CRangeBearingKFSLAM2D kf;
	kf.options.std_sensor_range = std::strtof(argv[2], nullptr);
	kf.options.std_sensor_yaw = mrpt::DEG2RAD(argc > 4 ? std::strtof(argv[4], nullptr) : 1.0f);
	kf.KF_options.method = mrpt::bayes::kfEKFNaive;
	kf.KF_options.verbosity_level = mrpt::system::LVL_ERROR;
	kf.KF_options.enable_profiler = false;

	// Read everything first so only the filter is timed; the first sensory
	// frame before any action is processed with an empty action, as esif does.
	std::vector<std::pair<mrpt::obs::CActionCollection::Ptr, mrpt::obs::CSensoryFrame::Ptr>> pairs;
	{
		mrpt::io::CFileGZInputStream f(argv[1]);
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
	const auto t0 = std::chrono::steady_clock::now();
	for (auto& [acts, sf] : pairs) kf.processActionObservation(acts, sf);
	const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

	mrpt::poses::CPosePDFGaussian pose;
	std::vector<mrpt::math::TPoint2D> lms;
	std::map<unsigned int, mrpt::maps::CLandmark::TLandmarkID> ids;
	mrpt::math::CVectorDouble x;
	mrpt::math::CMatrixDouble P;
	kf.getCurrentState(pose, lms, ids, x, P);
	std::printf("steps %zu landmarks %zu filter_wall_s %.6f\n", pairs.size(), lms.size(), wall);
	if (argc > 3)
	{
		std::ofstream out(argv[3]);
		for (std::size_t i = 0; i < lms.size(); ++i)
			out << ids.at(i) << " " << lms[i].x << " " << lms[i].y << "\n";
	}
	return 0;
}
