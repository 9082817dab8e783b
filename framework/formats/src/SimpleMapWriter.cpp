/// \file SimpleMapWriter.cpp
/// map.simplemap: the run's keyframes as an mrpt::maps::CSimpleMap, readable
/// by MRPT's own tools (e.g. simplemap-viewer, map building from keyframes).

#include <esif/core/Errors.h>
#include <esif/formats/GzArchive.h>
#include <esif/formats/MapWriter.h>
#include <esif/formats/RawlogFrames.h>
#include <esif/models/Se2.h>

#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3DPDF.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include <algorithm>
#include <exception>
#include <stdexcept>
#include <vector>

namespace esif
{
namespace
{
/// The keyframe's pose as CSimpleMap stores it: the 2-D Gaussian converted
/// to a CPose3DPDFGaussian, as CSimpleMap::insert(CPosePDF) does, which is
/// what its readers expect.
mrpt::poses::CPose3DPDF::Ptr storedPose(const Keyframe& kf)
{
	const mrpt::poses::CPosePDFGaussian pdf(
		mrpt::poses::CPose2D(toTPose2D(kf.pose.mean)), mrpt::math::CMatrixDouble33(kf.pose.cov));
	return mrpt::poses::CPose3DPDF::Ptr(mrpt::poses::CPose3DPDF::createFrom2D(pdf));
}

/// A CSimpleMap that serializes as one, byte for byte, but takes each
/// keyframe's sensory frame from the rawlog as it writes it (RawlogFrames.h):
/// only one frame is in memory at a time. Its pairs are never inserted, so
/// no other method of CSimpleMap sees them. MRPT wraps an exception thrown
/// while serializing in its own, with a backtrace: the reader's error is kept
/// in `failure` to be rethrown as it was.
class StreamedSimpleMap : public mrpt::maps::CSimpleMap
{
   public:
	StreamedSimpleMap(const RunRecord& run, std::exception_ptr& failure) : run_(run), failure_(failure) {}

   protected:
	/// CSimpleMap's layout: the number of pairs, then each pose and frame.
	void serializeTo(mrpt::serialization::CArchive& out) const override
	{
		out.WriteAs<uint32_t>(static_cast<uint32_t>(run_.keyframes.size()));
		std::vector<std::size_t> steps;
		for (const Keyframe& kf : run_.keyframes) steps.push_back(kf.step);
		std::size_t written = 0;
		try
		{
			readFramesAgain(*run_.frames_source, steps, [&](std::size_t, const mrpt::obs::CSensoryFrame::Ptr& frame) {
				out << *storedPose(run_.keyframes[written]) << *frame;
				++written;
			});
		}
		catch (const InputError&)
		{
			failure_ = std::current_exception();
			throw;
		}
		if (written != run_.keyframes.size()) throw std::logic_error("map.simplemap: a keyframe's frame was not read");
	}

   private:
	const RunRecord& run_;
	std::exception_ptr& failure_;
};

bool framesKept(const RunRecord& run)
{
	return !run.frames_source ||
		std::all_of(run.keyframes.begin(), run.keyframes.end(), [](const Keyframe& kf) { return kf.frame != nullptr; });
}
}  // namespace

void writeSimpleMap(const RunRecord& run, const std::string& path)
{
	// The gzip of the serialized object, as CSimpleMap::saveToFile writes
	// and loadFromFile reads it, but with every write checked (GzArchive.h).
	if (!framesKept(run))
	{
		std::exception_ptr failure;
		const StreamedSimpleMap map(run, failure);
		try
		{
			writeGzArchiveAtomically(path, [&](mrpt::serialization::CArchive& out) { out << map; });
		}
		catch (...)
		{
			if (failure) std::rethrow_exception(failure);
			throw;
		}
		return;
	}
	mrpt::maps::CSimpleMap map;
	for (const Keyframe& kf : run.keyframes)
		// A null frame would be serialized as a null object that some readers
		// dereference; an empty frame keeps every pair well-formed.
		map.insert(storedPose(kf), kf.frame ? kf.frame : mrpt::obs::CSensoryFrame::Create());
	writeGzArchiveAtomically(path, [&](mrpt::serialization::CArchive& out) { out << map; });
}

}  // namespace esif
