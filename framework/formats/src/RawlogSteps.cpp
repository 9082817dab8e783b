/// \file RawlogSteps.cpp
/// See RawlogSteps.h.

#include <esif/core/Errors.h>
#include <esif/formats/RawlogSteps.h>

#include "GzipReadStream.h"
#include "RawlogDigest.h"
#include "RawlogEntries.h"

#include <mrpt/serialization/CArchive.h>

#include <deque>

namespace esif
{
namespace
{
/// The one line for a file that is not what the first read found.
InputError changedSinceRead(const RawlogSource& source, const std::string& how, const std::string& why)
{
	return InputError(source.path + ": " + how + " since esif read it; " + why + ": run again");
}
}  // namespace

/// One forward pass: entries are read until the builder has handed on a step.
struct RawlogStepStream::Pass
{
	Pass(const RawlogSource& source_, std::string why_)
		: source(source_),
		  why(std::move(why_)),
		  stream(source.path),
		  archive(mrpt::serialization::archiveFrom(stream)),
		  builder(source.options, [this](rawlog_entries::BuiltStep&& built) { built_steps.push_back(std::move(built)); }),
		  visitor(builder, source.path)
	{
	}

	InputError changed(const std::string& how) const { return changedSinceRead(source, how, why); }

	/// Reads entries until a step is built; false at the end of the data.
	bool readUntilAStepIsBuilt()
	{
		while (built_steps.empty() && !ended)
		{
			mrpt::serialization::CSerializable::Ptr obj;
			try
			{
				obj = archive.ReadObject();
			}
			catch (const std::exception&)
			{
				// The end of the data: the first read ended there too, or the counts differ.
				ended = true;
				builder.finish();
				break;
			}
			visitor.visit(obj, entry++);
		}
		return !built_steps.empty();
	}

	const RawlogSource source;
	const std::string why;
	GzipReadStream stream;
	mrpt::serialization::CArchiveStreamBase<GzipReadStream> archive;
	rawlog_entries::StepBuilder builder;
	rawlog_entries::EntryVisitor visitor;
	std::deque<rawlog_entries::BuiltStep> built_steps;
	std::size_t entry = 0, given = 0;
	bool ended = false;
	StepsDigest digest;
	RawlogStep current;
};

RawlogStepStream::RawlogStepStream(const RawlogSource& source, std::string why)
{
	if (!(identityOf(source.path) == source.identity))
		throw changedSinceRead(source, "replaced or modified", why);
	pass_ = std::make_unique<Pass>(source, std::move(why));
}

RawlogStepStream::~RawlogStepStream() = default;

std::size_t RawlogStepStream::given() const { return pass_->given; }

RawlogStep& RawlogStepStream::next()
{
	Pass& p = *pass_;
	if (p.given >= p.source.steps) throw std::logic_error("RawlogStepStream: asked for a step beyond the log");
	if (!p.readUntilAStepIsBuilt()) throw p.changed("its steps changed");
	rawlog_entries::BuiltStep built = std::move(p.built_steps.front());
	p.built_steps.pop_front();
	built.step.index = p.given++;
	p.digest.add(built.step, built.ids);
	if (p.source.times_are_indices) built.step.time_s = static_cast<double>(built.step.index);
	p.current = {std::move(built.step), std::move(built.ids), std::move(built.frame)};
	return p.current;
}

void RawlogStepStream::finish()
{
	// Past the steps the first read kept there may be a cut file's last odometry.
	if (pass_->given < pass_->source.steps || pass_->digest.value() != pass_->source.steps_digest)
		throw pass_->changed("its steps changed");
}

}  // namespace esif
