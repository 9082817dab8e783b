#include <esif/core/Errors.h>
#include <esif/localmap/LocalMapMarginal.h>

#include <Eigen/Cholesky>
#include <stdexcept>
#include <string>

namespace esif
{
LocalMap marginaliseFeatures(const LocalMap& map, const std::vector<bool>& keep)
{
	if (keep.size() != map.features.size())
		throw std::invalid_argument("marginaliseFeatures: " + std::to_string(keep.size()) + " flags for " +
									std::to_string(map.features.size()) + " features of local map " +
									std::to_string(map.index));
	const auto n = static_cast<Eigen::Index>(map.stateDim());
	const auto square = [n](const Eigen::MatrixXd& m) { return m.rows() == n && m.cols() == n; };
	if (!square(map.information) || (map.covariance && !square(*map.covariance)))
		throw std::invalid_argument("marginaliseFeatures: local map " + std::to_string(map.index) +
									": information or covariance does not match its state of " + std::to_string(n));
	LocalMap out = map;
	out.features.clear();
	std::vector<Eigen::Index> kept = {0, 1, 2}, dropped;
	for (std::size_t i = 0; i < map.features.size(); ++i)
	{
		const auto r = static_cast<Eigen::Index>(3 + 2 * i);
		auto& rows = keep[i] ? kept : dropped;
		rows.push_back(r);
		rows.push_back(r + 1);
		if (keep[i]) out.features.push_back(map.features[i]);
	}
	if (dropped.empty()) return out;

	const Eigen::LLT<Eigen::MatrixXd> llt(map.information(dropped, dropped));
	if (llt.info() != Eigen::Success)
		throw NumericalError("local map " + std::to_string(map.index) +
							 ": the information of the features marginalised out is not positive definite");
	const Eigen::MatrixXd L_kd = map.information(kept, dropped);
	const Eigen::MatrixXd information = map.information(kept, kept) - L_kd * llt.solve(L_kd.transpose());
	out.information = 0.5 * (information + information.transpose());
	if (map.covariance) out.covariance = Eigen::MatrixXd((*map.covariance)(kept, kept));
	return out;
}

}  // namespace esif
