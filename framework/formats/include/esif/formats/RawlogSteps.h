#pragma once
/// \file RawlogSteps.h
/// The steps of a rawlog read again from the file a Rawlog came from, one
/// at a time, when the first read did not keep them (RawlogReadOptions::
/// keep_steps or keep_frames off): a replay then holds one step, and a map
/// writer one sensory frame, instead of the whole log.
///
/// Only the file that was read is read again: its identity (RawlogSource) is
/// compared before the pass, since MRPT's deserialisers trust what they read
/// and only the first read was checked in a sandbox (RawlogReader.h), and
/// the checksum of its steps once the last one is given (finish()).

#include <esif/formats/RawlogReader.h>

#include <mrpt/obs/CSensoryFrame.h>

#include <memory>

namespace esif
{
/// One step as read again: as the first read gave it (index set, times
/// normalised as in Rawlog::steps), the landmark IDs of its measurements as
/// stored, and its sensory frame (null for an odometry-only step).
struct RawlogStep
{
	StepInput input;
	std::vector<std::optional<LandmarkId>> ids;
	mrpt::obs::CSensoryFrame::Ptr frame;
};

class RawlogStepStream
{
   public:
	/// Opens the file again; InputError naming it when it was replaced or
	/// modified since it was read. `why` ends that message ("map.simplemap
	/// needs its sensory frames").
	RawlogStepStream(const RawlogSource& source, std::string why);
	~RawlogStepStream();
	RawlogStepStream(const RawlogStepStream&) = delete;
	RawlogStepStream& operator=(const RawlogStepStream&) = delete;

	/// Steps given so far; the next one has this index.
	std::size_t given() const;
	/// The next step (given() < source.steps), valid until the next call.
	/// InputError naming the file when it holds fewer steps than it did.
	RawlogStep& next();
	/// After the last step: InputError naming the file when its steps are
	/// not those the first read gave.
	void finish();

   private:
	struct Pass;
	std::unique_ptr<Pass> pass_;
};

}  // namespace esif
