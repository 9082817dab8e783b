/// \file SimpleMapWriter.cpp
/// map.simplemap: the run's keyframes as an mrpt::maps::CSimpleMap, readable
/// by MRPT's own tools (e.g. simplemap-viewer, map building from keyframes).

#include <esif/core/Errors.h>
#include <esif/formats/GzArchive.h>
#include <esif/formats/MapWriter.h>
#include <esif/models/Se2.h>

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
			mrpt::poses::CPose2D(toTPose2D(kf.pose.mean)), mrpt::math::CMatrixDouble33(kf.pose.cov));
		// A null frame would be serialized as a null object that some readers
		// dereference; an empty frame keeps every pair well-formed.
		auto frame = kf.frame ? kf.frame : mrpt::obs::CSensoryFrame::Create();
		// The 2-D overload converts the PDF to a CPose3DPDFGaussian, which is
		// what CSimpleMap stores and what its readers expect.
		map.insert(mrpt::poses::CPosePDF::Ptr(pdf), frame);
	}

	// The gzip of the serialized object, as CSimpleMap::saveToFile writes
	// and loadFromFile reads it, but with every write checked (GzArchive.h).
	writeGzArchiveAtomically(path, [&](mrpt::serialization::CArchive& out) { out << map; });
}

}  // namespace esif
