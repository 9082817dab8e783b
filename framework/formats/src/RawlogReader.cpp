#include <esif/core/Errors.h>
#include <esif/core/TextInput.h>
#include <esif/formats/RawlogReader.h>

#include "GzipInflate.h"
#include "RawlogEntries.h"
#include "RawlogDigest.h"
#include "WholeReadStream.h"
#include <esif/safeio/FileSet.h>
#include <esif/safeio/Sandbox.h>

#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cerrno>
#include <cstring>
#include <sys/stat.h>
#include <filesystem>

namespace esif
{
namespace
{
using rawlog_entries::BuiltStep;
using rawlog_entries::EntryVisitor;
using rawlog_entries::StepBuilder;

/// Timestamps are used when present and strictly increasing; otherwise (e.g.
/// simul-landmarks stamps every entry with the generation wall time) the
/// step index stands in for time. Watched one step at a time.
class TimeCheck
{
   public:
	void add(double t)
	{
		usable_ = usable_ && std::isfinite(t) && (first_ || t > last_);
		first_ = false;
		last_ = t;
	}
	bool usable() const { return usable_; }

   private:
	bool usable_ = true, first_ = true;
	double last_ = 0;
};

/// What one read collects from its steps, kept or not.
struct StepAccumulator
{
	StepAccumulator(Rawlog& out_, const RawlogReadOptions& options_) : out(out_), options(options_) {}

	Rawlog& out;
	const RawlogReadOptions& options;
	StepsDigest digest;
	TimeCheck times;
	std::size_t count = 0;
	bool any_scan = false;

	void accept(BuiltStep&& built)
	{
		built.step.index = count++;
		digest.add(built.step, built.ids);
		times.add(built.step.time_s);
		if (built.step.scan)
		{
			any_scan = true;
			for (const auto& m : built.step.scan->measurements) out.any_landmark_id |= m.id.has_value();
		}
		out.true_ids.push_back(std::move(built.ids));
		if (!options.keep_steps) return;
		out.steps.push_back(std::move(built.step));
		out.frames.push_back(options.keep_frames ? std::move(built.frame) : nullptr);
	}
};

/// Reads every entry of an inflated rawlog into steps. `progress` tells a
/// sandbox which entry is being read when MRPT's deserialiser fails on it.
Rawlog parseRawlog(const std::string& path, const InflatedFile& file, const RawlogReadOptions& options,
				   SandboxProgress* progress)
{
	WholeReadStream stream;
	stream.assignMemoryNotOwn(file.bytes.data(), file.bytes.size());
	auto archive = mrpt::serialization::archiveFrom(stream);

	Rawlog out;
	out.path = path;
	StepAccumulator steps(out, options);
	// Each step is taken in when the next one is built: a cut at the very
	// end may leave a final odometry without its scan, kept only if the file
	// ended cleanly.
	std::optional<BuiltStep> last;
	StepBuilder builder(options, [&](BuiltStep&& built) {
		if (last) steps.accept(std::move(*last));
		last = std::move(built);
	});
	EntryVisitor visitor(builder, path);
	for (std::size_t entry = 0;; ++entry)
	{
		if (progress) progress->position = entry;
		const auto before = stream.getPosition();
		if (before == file.bytes.size()) break;	 // clean end between entries
		mrpt::serialization::CSerializable::Ptr obj;
		try
		{
			obj = archive.ReadObject();
		}
		catch (const mrpt::serialization::CExceptionEOF&)
		{
			if (entry == 0) throw InputError(path + ": not an MRPT rawlog (empty or unreadable first entry)");
			out.truncation_warning = path + ": file ends inside entry " + std::to_string(entry) +
				"; read up to step " + std::to_string(steps.count + (last ? 1 : 0));
			break;
		}
		catch (const std::bad_alloc&)
		{
			throw;	// the sandbox reports it as a declared size beyond the file
		}
		catch (const std::exception& e)
		{
			if (entry == 0) throw InputError(path + ": not an MRPT rawlog (first entry is not a serialized MRPT object)");
			// MRPT wraps an end of data met inside a nested object in its own
			// exception: a failure that consumed every byte left is a cut file,
			// one that stopped before the end is a corrupt entry.
			if (stream.getPosition() < file.bytes.size() && !stream.endedInsideValue())
				throw InputError(path + ": entry " + std::to_string(entry) + " is corrupt: " + oneLineReason(e.what()));
			out.truncation_warning = path + ": file ends inside entry " + std::to_string(entry) +
				"; read up to step " + std::to_string(steps.count + (last ? 1 : 0));
			break;
		}
		visitor.visit(obj, entry);
	}
	builder.finish();
	out.has_odometry = builder.hasOdometry();
	out.measurement_count = builder.measurementCount();
	if (file.stream_truncated && !out.truncation_warning)
		out.truncation_warning = path + ": gzip stream is cut after entry " + std::to_string(steps.count + (last ? 1 : 0));
	if (last && !(out.truncation_warning && !last->step.scan)) steps.accept(std::move(*last));

	if (steps.count == 0) throw InputError(path + ": rawlog holds no odometry and no range-bearing observation");
	if (!out.has_odometry) throw InputError(path + ": rawlog holds no odometry (CActionRobotMovement2D or CObservationOdometry)");
	if (out.measurement_count == 0 && !steps.any_scan)
		throw InputError(path + ": rawlog holds no range-bearing observations (CObservationBearingRange)");
	// The digest is of the steps as the file gives them, before the times
	// are normalised: a second read (RawlogSteps.h) checks the same.
	out.source = RawlogSource{path, {}, options, steps.count, steps.digest.value(), !steps.times.usable()};
	if (!steps.times.usable())
		for (auto& s : out.steps) s.time_s = static_cast<double>(s.index);
	return out;
}

/// Memory a rawlog's entries may take while read: a fixed allowance plus a
/// multiple of the inflated size. Reading may keep every entry twice (as MRPT
/// objects for the maps, RawlogReadOptions::keep_frames, and as plugin
/// input); grid1225_large, 9.5 MB
/// inflated, takes about 110 MB (12 bytes per file byte). An allocation
/// beyond the budget is a count the file cannot back.
constexpr std::size_t kReadAllowanceBytes = std::size_t{256} << 20;
constexpr std::size_t kReadBytesPerFileByte = 64;
/// CPU time allowed for reading: MRPT reads well over 10 MB/s, so this is
/// reached only by a corrupt count that keeps its reader looping.
constexpr unsigned kReadCpuSeconds = 60;
constexpr unsigned kReadCpuSecondsPerMiB = 2;

SandboxLimits readLimitsFor(std::size_t bytes)
{
	SandboxLimits limits;
	limits.address_space_bytes = kReadAllowanceBytes + kReadBytesPerFileByte * bytes;
	limits.cpu_seconds = kReadCpuSeconds + kReadCpuSecondsPerMiB * static_cast<unsigned>(bytes >> 20);
	return limits;
}

/// Reads the rawlog once in a sandboxed child. A fault there becomes one
/// line naming the entry; success proves the same bytes read safely here,
/// and returns the digest (RawlogDigest.h) of what the child read.
std::uint32_t checkInSandbox(const std::string& path, const InflatedFile& file, const RawlogReadOptions& options)
{
	const SandboxLimits limits = readLimitsFor(file.bytes.size());
	const SandboxOutcome outcome = runInSandbox(
		[&](SandboxProgress& progress) { progress.result = digestOf(parseRawlog(path, file, options, &progress)); },
		limits);
	const std::string entry = path + ": entry " + std::to_string(outcome.position);
	switch (outcome.kind)
	{
		case SandboxOutcome::Kind::kSucceeded:
			return static_cast<std::uint32_t>(outcome.result);
		case SandboxOutcome::Kind::kFailed:
			throw InputError(oneLineReason(outcome.message));
		case SandboxOutcome::Kind::kOutOfMemory:
			// Under a limit the process was started with, a corrupt count and
			// a file too large for the limit look alike.
			if (outcome.address_space_cap > 0)
				throw InputError(entry + " declares more data than the file holds, or the file needs more than the " +
								 std::to_string(outcome.address_space_cap >> 20) +
								 " MiB of address space this process may use (RLIMIT_AS)");
			throw InputError(entry + " declares more data than the file holds: reading it needs over " +
							 std::to_string(limits.address_space_bytes >> 20) + " MiB, the limit for " +
							 std::to_string(file.bytes.size()) + " bytes of rawlog");
		case SandboxOutcome::Kind::kCpuLimit:
			throw InputError(entry + " is corrupt: reading it took over " + std::to_string(limits.cpu_seconds) +
							 " s of CPU");
		case SandboxOutcome::Kind::kInterrupted:
			throw InputError(path + ": reading stopped by " + strsignal(outcome.signal_number));
		case SandboxOutcome::Kind::kCrashed:
			break;
	}
	throw InputError(entry + " is corrupt: MRPT's deserialiser crashed on it (" +
					 (outcome.signal_number ? std::string(strsignal(outcome.signal_number)) : outcome.message) + ")");
}

/// The read the sandboxed child vouched for, done again here: both must
/// come to the same (the child decides what the file holds), or the file is
/// refused rather than read one way here and another way there.
Rawlog readVouchedFor(const std::string& path, const InflatedFile& file, const RawlogReadOptions& options)
{
	const std::uint32_t vouched = checkInSandbox(path, file, options);
	Rawlog log = parseRawlog(path, file, options, nullptr);
	if (digestOf(log) != vouched)
		throw InputError(
			path + ": read two different ways (MRPT took a value from memory it had not read into): a corrupt entry");
	return log;
}
}  // namespace

FileIdentity identityOf(const std::string& path)
{
	struct stat st{};
	if (::stat(path.c_str(), &st) != 0) throw InputError(path + ": cannot read the file's status: " + std::strerror(errno));
	return {static_cast<std::uintmax_t>(st.st_dev), static_cast<std::uintmax_t>(st.st_ino),
			static_cast<std::uintmax_t>(st.st_size),
			static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec};
}

Rawlog readRawlogFromMemory(const std::string& name, std::string bytes, const RawlogReadOptions& options)
{
	if (bytes.empty()) throw InputError(name + ": file holds no data");
	RawlogReadOptions kept = options;
	kept.keep_steps = true;	 // no file to read them again from
	Rawlog log = readVouchedFor(name, InflatedFile{std::move(bytes), false}, kept);
	log.source.reset();	 // no file to read again
	return log;
}

Rawlog readRawlog(const std::string& path, const RawlogReadOptions& options)
{
	requireRegularFile(path, "rawlog file");
	// A rawlog whose replacement (with its ground truth) was cut in two by a
	// kill is not read beside a ground truth that is not its own.
	requireCompleteFileSet(path);
	const FileIdentity identity = identityOf(path);
	Rawlog log = readVouchedFor(path, inflateFile(path), options);
	log.source->identity = identity;
	return log;
}

}  // namespace esif
