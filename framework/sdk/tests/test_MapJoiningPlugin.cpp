/// \file test_MapJoiningPlugin.cpp
/// What MapJoiningPlugin does for every joining filter on a rawlog, checked
/// on a joiner that fuses nothing: a filter that cannot give the open map its
/// global features stops with one InputError naming the key when a config
/// sets local_map_global_features_radius_m, at the first fusion.

#include <esif/config/ConfigFile.h>
#include <esif/core/Errors.h>
#include <esif/plugin/MapJoiningPlugin.h>
#include <esif/plugin/PluginWithParams.h>
#include <esif/sparse/SparseInformationCore.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace
{
using namespace esif;

struct SilentJoinerParams
{
	LocalMapBuilderParams builder;
	void declare(ParamBinder& b) { builder.declare(b); }
};

/// A joiner that counts the maps it is given and implements none of the
/// optional hooks (globalFeaturesNearOpenMapStart among them).
class SilentJoiner : public PluginWithParams<SilentJoinerParams, MapJoiningPlugin>
{
   public:
	SilentJoiner() : PluginWithParams("silent joiner") {}
	mrpt::rtti::CObject* clone() const override { return nullptr; }  // never registered nor cloned

	std::string sectionName() const override { return "silent"; }
	PoseEstimate robotPose() const override { return {}; }
	Estimate estimate() const override { return {}; }
	CostFigures costFigures() const override { return {}; }
	std::vector<PoseEstimate> endPoses() const override { return {}; }
	StepReport mapReport(std::size_t) const override { return {}; }
	std::vector<LocalMapFusionCost> fusionCosts() const override { return {}; }
	std::size_t fused = 0;

   protected:
	void fuseLocalMap(const LocalMap&) override { ++fused; }
	void finishJoining() override {}
	std::vector<SettledFusion> settledFusions() const override { return {}; }
	SparseInformationCore& globalInformation() const override { return information_; }

   private:
	mutable SparseInformationCore information_;
};

StepInput stepWithOneSighting(std::size_t k)
{
	StepInput s;
	s.index = k;
	Scan scan;
	RangeBearing m;
	m.range_m = 5.0;
	m.bearing_rad = 0.0;
	m.cov = Eigen::Vector2d(0.01, 1e-4).asDiagonal();
	scan.measurements.push_back(m);
	s.scan = scan;
	return s;
}

void configure(SilentJoiner& joiner, const std::string& keys)
{
	joiner.configure(ConfigFile::fromText("[silent]\n" + keys, "silent.ini").section("silent"));
	joiner.reserveLandmarkIds(0);
}

TEST(MapJoiningPlugin, AFilterWithoutGlobalFeaturesRefusesTheRadiusAtTheFirstFusion)
{
	SilentJoiner joiner;
	configure(joiner, "local_map_steps = 1\nlocal_association = jcbb\nlocal_map_global_features_radius_m = 20\n");
	try
	{
		joiner.processStep(stepWithOneSighting(0));
		FAIL() << "no InputError";
	}
	catch (const InputError& e)
	{
		EXPECT_EQ(std::string(e.what()), "silent joiner: local_map_global_features_radius_m is not supported by this filter");
	}
	EXPECT_EQ(joiner.fused, 1u);  // the map was fused; the error comes when the open map asks for the global features
}

TEST(MapJoiningPlugin, WithoutTheRadiusTheSameFilterRuns)
{
	SilentJoiner joiner;
	configure(joiner, "local_map_steps = 1\nlocal_association = jcbb\n");
	for (std::size_t k = 0; k < 3; ++k) joiner.processStep(stepWithOneSighting(k));
	EXPECT_EQ(joiner.fused, 3u);
}

}  // namespace
