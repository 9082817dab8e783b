/// \file RawlogFrames.cpp
/// See RawlogFrames.h.

#include <esif/core/Errors.h>
#include <esif/formats/RawlogFrames.h>
#include <esif/formats/RawlogSteps.h>

namespace esif
{
void readFramesAgain(const RawlogSource& source, const std::vector<std::size_t>& steps, const FrameVisitor& each)
{
	if (!steps.empty() && steps.back() >= source.steps)
		throw InputError(source.path + ": step " + std::to_string(steps.back()) + " asked for, the log has " +
						 std::to_string(source.steps));
	RawlogStepStream stream(source, "map.simplemap needs its sensory frames");
	std::size_t next = 0;
	while (stream.given() < source.steps)
	{
		RawlogStep& step = stream.next();
		if (next < steps.size() && steps[next] == step.input.index)
		{
			if (!step.frame)
				throw InputError(source.path + ": step " + std::to_string(step.input.index) + " has no sensory frame");
			each(step.input.index, step.frame);
			++next;
		}
	}
	stream.finish();
}

}  // namespace esif
