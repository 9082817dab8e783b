#pragma once
/// \file AssociationFile.h
/// associations.txt: what a run's plugin did with every measurement, so that
/// another run can reuse that data association (`[esif] associations_from`),
/// e.g. a full-SLAM optimizer, which cannot associate on its own, fed the
/// decisions of an EKF that could.
///
/// Format: '#' comment lines, one of which is `# steps N` (the rawlog's step
/// count, as steps without measurements have no rows), then one row per
/// measurement in step order:
///
///     step measurement kind landmark_id
///
/// with `kind` one of new | matched | rejected and landmark_id -1 for
/// rejected measurements.

#include <esif/core/Estimate.h>
#include <esif/formats/RawlogReader.h>

#include <string>
#include <vector>

namespace esif
{
/// A run's data association as read back from associations.txt.
struct RecordedAssociations
{
	/// One report per step of the recorded run (index k = step k).
	std::vector<StepReport> steps;
};

/// The text of associations.txt for `reports` (one per step); `plugin` and
/// `rawlog` only go into the header comment.
std::string associationFileText(
	const std::vector<StepReport>& reports, const std::string& plugin, const std::string& rawlog);

/// Writes associationFileText() to `path` atomically.
void writeAssociationFile(
	const std::string& path, const std::vector<StepReport>& reports, const std::string& plugin,
	const std::string& rawlog);

/// Reads associations.txt recorded on a rawlog of `rawlog_steps` steps.
/// Throws InputError naming the file (missing, unreadable, no `# steps N`
/// line) or "file:line" (N other than `rawlog_steps`, checked before
/// anything is allocated; a malformed row, a row out of order, a step
/// beyond N, an unknown kind, a landmark_id outside MRPT's [0, 2^31 - 1], a
/// rejected row whose landmark_id is not -1).
RecordedAssociations readAssociationFile(const std::string& path, std::size_t rawlog_steps);

/// Makes `log`'s measurement IDs those of the recorded run: the landmark ID
/// of a new or matched measurement, none for a rejected one, and
/// `log.any_landmark_id` says whether any is left. `log.true_ids` stay as
/// they are (scoring still uses the rawlog's own IDs). Throws
/// InputError naming `path` when the recorded run saw another number of steps,
/// or another number of measurements at some step, than `log` holds.
void applyAssociations(Rawlog& log, const RecordedAssociations& recorded, const std::string& path);

/// The check of applyAssociations alone, for a log whose steps are applied
/// one at a time (applyRecordedStep) as they are read again: the measurements
/// of each step are counted by `log.true_ids`.
void checkAssociationsFit(const Rawlog& log, const RecordedAssociations& recorded, const std::string& path);

/// Makes `step`'s measurement IDs those of its report in the recorded run
/// (checked to fit by checkAssociationsFit).
void applyRecordedStep(StepInput& step, const StepReport& recorded);

/// Whether the recorded run gives any measurement a landmark ID (it did not
/// reject them all).
bool anyIdGiven(const RecordedAssociations& recorded);

}  // namespace esif
