// A test-only plugin whose run fails: FakePlugin's dead reckoning and ID
// matching, then a
// NumericalError (esif exit code 3) at a configured step, as a filter whose
// covariance stops being positive definite would. Built into the tests'
// own plugin folder (never listed by `esif plugins`) for `esif compare`'s
// handling of failed runs; configured as `plugin = test::FailingFilter`.

#include "FakePlugin.h"

#include <esif/core/Errors.h>

#include <mrpt/core/initializer.h>

#include <string>

namespace esif::test
{
struct FailingFilterParams
{
	int fail_at_step = 5;  ///< step index at which processStep() throws

	void declare(ParamBinder& b)
	{
		b.integer("fail_at_step", fail_at_step, "step at which the run fails", Bounds::nonNegative());
	}
};

class FailingFilter : public FakePlugin
{
	DEFINE_MRPT_OBJECT(FailingFilter, esif::test)

   public:
	std::string sectionName() const override { return "failing"; }
	void configure(const ConfigSection& section) override { loadParams(params_, section); }
	std::vector<ParamInfo> parameters() const override { return describeParams(params_); }
	StepReport processStep(const StepInput& step) override
	{
		if (step.index >= static_cast<std::size_t>(params_.fail_at_step))
			throw NumericalError("test::FailingFilter fails here on purpose (fail_at_step)");  // the host adds the step
		return FakePlugin::processStep(step);
	}

   private:
	FailingFilterParams params_;
};

IMPLEMENTS_MRPT_OBJECT(FailingFilter, FakePlugin, esif::test)

}  // namespace esif::test

MRPT_INITIALIZER(esif_register_failing_filter)
{
	mrpt::rtti::registerClass(CLASS_ID_NAMESPACE(FailingFilter, esif::test));
}
