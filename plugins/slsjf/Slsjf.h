#pragma once
/// \file Slsjf.h
/// SLSJF, the Sparse Local Submap Joining Filter (book Ch. 5): local EKF
/// maps, each a virtual observation of its features and end pose from its
/// start pose (eq. 5.8), fused one by one into a global map that keeps
/// every feature and every map's end pose (eq. 5.3) with an exactly sparse
/// information matrix (Sec. 5.3) and, apart from linearisation, no loss of
/// information (Sec. 5.7.2). Algorithm 5.1 per map: start pose (5.4-5.6),
/// data association (5.4.1), new features and end pose (5.7), update
/// (5.8-5.9), state recovery (5.14, incremental Cholesky). Optional
/// relinearisation of all fused maps (`smoothing`, after the authors'
/// I-SLSJF) reaches the optimum of the local-map formulation.
///
/// On a rawlog its local maps come from the SDK's MapJoiningPlugin (the
/// framework's LocalMapBuilder); on `esif run --local-maps` it fuses the maps
/// it is given.

#include "GlobalMap.h"
#include "MapAssociation.h"
#include "SlsjfParams.h"

#include <esif/plugin/MapJoiningPlugin.h>
#include <esif/plugin/PluginWithParams.h>

#include <map>
#include <memory>
#include <optional>
#include <vector>

namespace esif
{
class Slsjf : public PluginWithParams<slsjf::SlsjfParams, MapJoiningPlugin>
{
	DEFINE_MRPT_OBJECT(Slsjf, esif)

   public:
	Slsjf() : PluginWithParams("SLSJF") {}
	std::string sectionName() const override { return "slsjf"; }
	PoseEstimate robotPose() const override;
	Estimate estimate() const override;
	CostFigures costFigures() const override;
	Formulation formulation() const override { return Formulation::Slsjf; }
	/// With smoothing, every step's pose re-estimated with all data: its map's
	/// start pose from the final global state composed with the robot pose
	/// in that map (first-order covariance). Plain SLSJF keeps its online poses.
	std::optional<std::vector<PoseEstimate>> smoothedTrajectory() const override;
	std::optional<StateInformation> stateInformation() const override;

	std::vector<PoseEstimate> endPoses() const override;
	StepReport mapReport(std::size_t k) const override;
	std::vector<LocalMapFusionCost> fusionCosts() const override { return costs_; }

   protected:
	void fuseLocalMap(const LocalMap& map) override;
	void finishJoining() override;
	std::vector<SettledFusion> settledFusions() const override;
	SparseInformationCore& globalInformation() const override;
	/// The global features within `radius_m` of the last fused map's end
	/// pose, moved into its frame with the joint covariance of [end pose;
	/// features] (one recovery per local map).
	std::optional<EarlierFeatures> globalFeaturesNearOpenMapStart(double radius_m) override;

   private:
	void start() override;
	/// What the fusion of one map decided, for reports and the robot pose.
	struct MapRecord
	{
		std::size_t first_step = 0;
		std::vector<StepReport> step_reports;  ///< by the local map's feature IDs
		std::vector<LandmarkId> local_ids;	///< the map's feature IDs, in order
		StepReport decisions;  ///< one per feature: global id or rejected
	};

	void requireConfigured() const;
	bool useIds(const LocalMap& map) const;
	slsjf::MapAssociationOutcome associate(const LocalMap& map, std::optional<VarId> start);
	void smooth();
	PoseEstimate openMapStart() const;
	const std::vector<Eigen::MatrixXd>& marginals() const;

	// Behind const estimate()/robotPose(): recovery and marginal caches.
	std::unique_ptr<slsjf::GlobalMap> global_;
	std::vector<MapRecord> records_;
	std::vector<LocalMapFusionCost> costs_;
	Eigen::Matrix3d last_end_cov_ = Eigen::Matrix3d::Zero();  // of the last fused map's end pose
	mutable std::optional<std::vector<Eigen::MatrixXd>> marginals_;	 // cleared by every change

	struct Tally
	{
		MapAssociationTally association;
		std::size_t maps_selected = 0, smoothing_runs = 0, smoothing_iterations = 0;
		double smoothing_s = 0;
	} tally_;
};

}  // namespace esif
