// A test-only "optimization baseline" whose optimum its own check finds
// implausible: FakePlugin's dead reckoning and ID matching; it declares the full-SLAM formulation, and
// reports the counters the Ceres plugin reports after its plausibility
// check (optimum_plausible, chi2_per_dof, degenerate_poses, written to
// stats.json as plugin_*), with values from its section. For `esif
// compare`'s remark on an implausible baseline; configured as
// `plugin = test::ImplausibleOptimum`.

#include "FakePlugin.h"

#include <mrpt/core/initializer.h>

#include <string>

namespace esif::test
{
struct ImplausibleOptimumParams
{
	bool plausible = false;	 ///< reported as optimum_plausible (1/0)
	double chi2_per_dof = 7.1;
	int degenerate_poses = 2;

	void declare(ParamBinder& b)
	{
		b.flag("plausible", plausible, "reported as plugin_optimum_plausible");
		b.real("chi2_per_dof", chi2_per_dof, "reported as plugin_chi2_per_dof", Bounds::nonNegative());
		b.integer("degenerate_poses", degenerate_poses, "reported as plugin_degenerate_poses", Bounds::nonNegative());
	}
};

class ImplausibleOptimum : public FakePlugin
{
	DEFINE_MRPT_OBJECT(ImplausibleOptimum, esif::test)

   public:
	std::string sectionName() const override { return "implausible"; }
	void configure(const ConfigSection& section) override { loadParams(params_, section); }
	std::vector<ParamInfo> parameters() const override { return describeParams(params_); }
	Formulation formulation() const override { return Formulation::FullSlamOptimum; }
	CostFigures costFigures() const override
	{
		CostFigures cost;
		cost.counters = {
			{"optimum_plausible", params_.plausible ? 1.0 : 0.0},
			{"chi2_per_dof", params_.chi2_per_dof},
			{"degenerate_poses", double(params_.degenerate_poses)}};
		return cost;
	}

   private:
	ImplausibleOptimumParams params_;
};

IMPLEMENTS_MRPT_OBJECT(ImplausibleOptimum, FakePlugin, esif::test)

}  // namespace esif::test

MRPT_INITIALIZER(esif_register_implausible_optimum)
{
	mrpt::rtti::registerClass(CLASS_ID_NAMESPACE(ImplausibleOptimum, esif::test));
}
