#include <esif/association/Chi2.h>
#include <esif/core/Errors.h>
#include <esif/eval/EstimationErrors.h>
#include <esif/eval/LocalMapConsistency.h>

namespace esif
{
namespace
{
/// nees(), with a covariance that is not positive definite an error naming `what`.
double neesOf(const Eigen::VectorXd& e, const Eigen::MatrixXd& P, const std::string& what)
{
	const auto value = nees(e, P);
	if (!value) throw NumericalError(what + ": covariance not positive definite");
	return *value;
}
}  // namespace

LocalMapConsistency localMapConsistency(
	const LocalMap& map, const Pose2& start, const Pose2& end, const std::map<LandmarkId, Eigen::Vector2d>& landmarks)
{
	const std::string what = "local map " + std::to_string(map.index);
	LocalMapConsistency out;
	out.index = map.index;
	out.features = map.features.size();

	// The map's own state and information (eq. 5.1), variables by the map's IDs.
	StateInformation state;
	state.variables.push_back(StateVariable::poseOf(std::nullopt, map.index));
	for (const auto& f : map.features) state.variables.push_back(StateVariable::landmarkOf(f.id));
	state.mean = map.state();
	state.information = map.information.sparseView();

	// The reference in the map's start frame.
	StateReference reference;
	reference.poses_by_local_map[map.index] = inverseCompose(start, end);
	for (const auto& f : map.features)
		if (const auto it = landmarks.find(f.id); it != landmarks.end())
			reference.landmarks[f.id] = inverseCompose(start, Pose2(it->second.x(), it->second.y(), 0)).head<2>();
	out.whole = *stateNees(state, reference, std::nullopt, what);

	const Eigen::MatrixXd P = map.covarianceMatrix();
	Eigen::Vector3d e = map.end_pose - reference.poses_by_local_map[map.index];
	e(2) = wrapAngle(e(2));
	out.end_pose_nees = neesOf(e, P.topLeftCorner<3, 3>(), what + " end pose");
	out.end_heading_error_rad = e(2);

	const double bound = chi2Quantile(0.95, 2);
	std::size_t inside = 0;
	for (std::size_t i = 0; i < map.features.size(); ++i)
	{
		const auto ref = reference.landmarks.find(map.features[i].id);
		if (ref == reference.landmarks.end()) continue;
		++out.features_compared;
		const Eigen::Index at = 3 + 2 * static_cast<Eigen::Index>(i);
		const Eigen::Vector2d ef = map.features[i].position - ref->second;
		if (neesOf(ef, P.block<2, 2>(at, at), what + " feature " + std::to_string(map.features[i].id)) <= bound)
			++inside;
	}
	if (out.features_compared > 0)
		out.features_inside_fraction = static_cast<double>(inside) / static_cast<double>(out.features_compared);
	return out;
}

}  // namespace esif
