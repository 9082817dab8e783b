#include "FakePlugin.h"

#include <esif/models/Se2.h>

IMPLEMENTS_MRPT_OBJECT(FakePlugin, FilterPlugin, esif::test)

namespace esif::test
{
StepReport FakePlugin::processStep(const StepInput& step)
{
	// MRPT's TPose2D composition, as this fake has always integrated odometry.
	if (step.odometry) pose_.mean = toPose2(toTPose2D(pose_.mean) + toTPose2D(step.odometry->delta));
	StepReport report;
	if (!step.scan) return report;
	for (const auto& m : step.scan->measurements)
	{
		if (!m.id)
			report.associations.push_back({Association::Kind::Rejected, -1});
		else
			report.associations.push_back(
				{seen_.insert(*m.id).second ? Association::Kind::New : Association::Kind::Matched, *m.id});
	}
	return report;
}

}  // namespace esif::test
