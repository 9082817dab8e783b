/// \file RawlogFrames.cpp
/// See RawlogFrames.h.

#include <esif/core/Errors.h>
#include <esif/formats/RawlogFrames.h>

#include "GzipReadStream.h"
#include "RawlogDigest.h"
#include "RawlogEntries.h"

#include <mrpt/serialization/CArchive.h>

namespace esif
{
namespace
{
std::string changed(const RawlogSource& source, const std::string& how)
{
	return source.path + ": " + how + " since esif read it; map.simplemap needs its sensory frames: run again";
}
}  // namespace

void readFramesAgain(const RawlogSource& source, const std::vector<std::size_t>& steps, const FrameVisitor& each)
{
	if (!steps.empty() && steps.back() >= source.steps)
		throw InputError(source.path + ": step " + std::to_string(steps.back()) + " asked for, the log has " +
						 std::to_string(source.steps));
	if (!(identityOf(source.path) == source.identity)) throw InputError(changed(source, "replaced or modified"));

	GzipReadStream stream(source.path);
	auto archive = mrpt::serialization::archiveFrom(stream);
	StepsDigest digest;
	std::size_t k = 0, next = 0;
	rawlog_entries::StepBuilder builder(source.options, [&](rawlog_entries::BuiltStep&& built) {
		if (k >= source.steps) return;	// past the steps the first read kept (a cut file's last odometry)
		built.step.index = k;
		digest.add(built.step, built.ids);
		if (next < steps.size() && steps[next] == k)
		{
			if (!built.frame) throw InputError(source.path + ": step " + std::to_string(k) + " has no sensory frame");
			each(k, built.frame);
			++next;
		}
		++k;
	});
	rawlog_entries::EntryVisitor visitor(builder, source.path);
	for (std::size_t entry = 0; k < source.steps; ++entry)
	{
		mrpt::serialization::CSerializable::Ptr obj;
		try
		{
			obj = archive.ReadObject();
		}
		catch (const std::exception&)
		{
			break;	// the end of the data: the first read ended there too, or the counts below differ
		}
		visitor.visit(obj, entry);
	}
	if (k < source.steps) builder.finish();
	if (k < source.steps || digest.value() != source.steps_digest) throw InputError(changed(source, "its steps changed"));
}

}  // namespace esif
