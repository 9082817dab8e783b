#pragma once
/// \file RawlogEntries.h
/// From MRPT rawlog entries to steps (RawlogReader.h says what a step is):
/// every value an entry holds is checked before it is used, and each
/// finished step is handed to a sink, so one pass over a file can keep the
/// steps (RawlogReader.cpp) or pick the sensory frames of some of them
/// without holding the rest (RawlogFrames.cpp).

#include <esif/formats/RawlogReader.h>

#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/serialization/CSerializable.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace esif::rawlog_entries
{
/// One finished step, as a sink receives it: its input (index not yet set),
/// the sensory frame behind it (null for an odometry-only step) and the
/// landmark IDs of its measurements as stored in the file.
struct BuiltStep
{
	StepInput step;
	mrpt::obs::CSensoryFrame::Ptr frame;
	std::vector<std::optional<LandmarkId>> ids;
};
using StepSink = std::function<void(BuiltStep&&)>;

/// Accumulates rawlog entries into steps: odometry opens a step, a scan
/// closes it.
class StepBuilder
{
   public:
	StepBuilder(const RawlogReadOptions& options, StepSink sink);

	void onOdometry(const OdometryIncrement& inc, double t);
	/// Absolute odometry reading (CObservationOdometry): the increment is the
	/// difference of consecutive readings; the first reading only anchors.
	void onAbsoluteOdometry(const mrpt::poses::CPose2D& reading, double t, const std::string& where);
	void onScan(const mrpt::obs::CObservationBearingRange& obs, const mrpt::obs::CSensoryFrame::Ptr& frame, double t,
				const std::string& where);
	/// Hands on the odometry still waiting for its scan, if any.
	void finish();

	bool hasOdometry() const { return has_odometry_; }
	std::size_t measurementCount() const { return measurement_count_; }

   private:
	Eigen::Matrix2d measurementCovariance(const mrpt::obs::CObservationBearingRange& obs,
										  const mrpt::obs::CObservationBearingRange::TMeasurement& m,
										  const std::string& what) const;
	void flushPending();

	const RawlogReadOptions& options_;
	StepSink sink_;
	std::optional<StepInput> pending_;
	std::optional<Pose2> last_reading_;
	bool has_odometry_ = false;
	std::size_t measurement_count_ = 0;
};

/// Hands the odometry and scans of one deserialised entry (an action
/// collection, a sensory frame, an observation, or an old-style CRawlog
/// holding them all) to a StepBuilder; anything else is an InputError
/// naming the entry.
class EntryVisitor
{
   public:
	EntryVisitor(StepBuilder& builder, std::string path) : builder_(builder), path_(std::move(path)) {}
	void visit(const mrpt::serialization::CSerializable::Ptr& obj, std::size_t entry);

   private:
	void visitObservation(const mrpt::obs::CObservation::Ptr& o, const mrpt::obs::CSensoryFrame::Ptr& frame,
						  const std::string& where);

	StepBuilder& builder_;
	std::string path_;
};

}  // namespace esif::rawlog_entries
