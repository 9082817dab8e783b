// A test-only plugin that runs out of memory: it dead-reckons, maps every
// measured landmark ID (New on its first sighting, Matched after), then
// throws std::bad_alloc at a configured step, or in finish() as a batch
// optimiser would. For the host's handling of memory exhaustion (an error
// line naming the step, the plugin and its landmark count, exit code 3);
// configured as `plugin = test::OutOfMemoryFilter`.

#include "FakePlugin.h"

#include <mrpt/core/initializer.h>

#include <new>
#include <string>

namespace esif::test
{
struct OutOfMemoryFilterParams
{
	int fail_at_step = 5;  ///< step index at which processStep() throws (fail_in = step)
	std::string fail_in = "step";

	void declare(ParamBinder& b)
	{
		b.integer("fail_at_step", fail_at_step, "step at which the run runs out of memory", Bounds::nonNegative());
		b.choice("fail_in", fail_in, {"step", "finish"}, "where std::bad_alloc is thrown: processStep() or finish()");
	}
};

/// FakePlugin's dead reckoning and ID matching, with a failure on top.
class OutOfMemoryFilter : public FakePlugin
{
	DEFINE_MRPT_OBJECT(OutOfMemoryFilter, esif::test)

   public:
	std::string sectionName() const override { return "out_of_memory"; }
	void configure(const ConfigSection& section) override { loadParams(params_, section); }
	std::vector<ParamInfo> parameters() const override { return describeParams(params_); }
	StepReport processStep(const StepInput& step) override
	{
		if (params_.fail_in == "step" && step.index >= static_cast<std::size_t>(params_.fail_at_step))
			throw std::bad_alloc();
		return FakePlugin::processStep(step);
	}
	void finish() override
	{
		if (params_.fail_in == "finish") throw std::bad_alloc();
		FakePlugin::finish();
	}

   private:
	OutOfMemoryFilterParams params_;
};

IMPLEMENTS_MRPT_OBJECT(OutOfMemoryFilter, FakePlugin, esif::test)

}  // namespace esif::test

MRPT_INITIALIZER(esif_register_out_of_memory_filter)
{
	mrpt::rtti::registerClass(CLASS_ID_NAMESPACE(OutOfMemoryFilter, esif::test));
}
