/// \file mrpt_kf_replay.cpp
/// Times the bare MRPT EKF SLAM filter over a rawlog (see MrptKfSlamReplay.h)
/// and optionally writes its final landmarks as `id x y` lines.
///
/// usage: mrpt_kf_replay RAWLOG STD_RANGE_M [LANDMARKS_OUT] [STD_BEARING_DEG]

#include "MrptKfSlamReplay.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>

int main(int argc, char** argv)
{
	if (argc < 3)
	{
		std::cerr << "usage: mrpt_kf_replay RAWLOG STD_RANGE_M [LANDMARKS_OUT] [STD_BEARING_DEG]\n";
		return 2;
	}
	const float std_bearing_deg = argc > 4 ? std::strtof(argv[4], nullptr) : 1.0f;
	const auto r = esif::bench::replayMrptKfSlam(argv[1], std::strtof(argv[2], nullptr), mrpt::DEG2RAD(std_bearing_deg));
	std::printf("steps %zu landmarks %zu filter_wall_s %.6f\n", r.steps, r.landmarks.size(), r.filter_wall_s);
	if (argc > 3)
	{
		std::ofstream out(argv[3]);
		out.precision(17);
		for (const auto& [id, p] : r.landmarks) out << id << " " << p.x() << " " << p.y() << "\n";
	}
	return 0;
}
