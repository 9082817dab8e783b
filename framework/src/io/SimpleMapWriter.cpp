/// \file SimpleMapWriter.cpp
/// map.simplemap: the run's keyframes as an mrpt::maps::CSimpleMap, readable
/// by MRPT's own tools (e.g. simplemap-viewer, map building from keyframes).

#include <esif/core/Errors.h>
#include <esif/io/AtomicFile.h>
#include <esif/io/MapWriter.h>

#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPosePDFGaussian.h>

namespace esif
{
void writeSimpleMap(const RunRecord& run, const std::string& path)
{
	mrpt::maps::CSimpleMap map;
	for (const Keyframe& kf : run.keyframes)
	{
		auto pdf = mrpt::poses::CPosePDFGaussian::Create(
			mrpt::poses::CPose2D(kf.pose.mean), mrpt::math::CMatrixDouble33(kf.pose.cov));
		// A null frame would be serialized as a null object that some readers
		// dereference; an empty frame keeps every pair well-formed.
		auto frame = kf.frame ? kf.frame : mrpt::obs::CSensoryFrame::Create();
		// The 2-D overload converts the PDF to a CPose3DPDFGaussian, which is
		// what CSimpleMap stores and what its readers expect.
		map.insert(mrpt::poses::CPosePDF::Ptr(pdf), frame);
	}

	writeAtomically(path, [&](const std::string& tmp) {
		// CSimpleMap::saveToFile always writes through CFileGZOutputStream,
		// whatever the extension, and loadFromFile reads gz, so the temporary
		// name's ".tmp" suffix does not change the format of the final file.
		if (!map.saveToFile(tmp)) throw InputError(path + ": cannot write simple map");
	});
}

}  // namespace esif
