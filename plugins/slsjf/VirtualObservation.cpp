#include "VirtualObservation.h"

#include <esif/core/Errors.h>

#include <Eigen/Cholesky>

namespace esif::slsjf
{
VirtualObservation keepFeatures(const LocalMap& map, const std::vector<bool>& keep)
{
	VirtualObservation out;
	std::vector<Eigen::Index> a = {0, 1, 2}, b;
	for (std::size_t i = 0; i < map.features.size(); ++i)
	{
		const auto r = static_cast<Eigen::Index>(3 + 2 * i);
		auto& rows = keep[i] ? a : b;
		rows.push_back(r);
		rows.push_back(r + 1);
		if (keep[i]) out.kept.push_back(i);
	}
	const Eigen::VectorXd x = map.state();
	out.z = x(a);
	out.information = map.information(a, a);
	if (b.empty()) return out;

	// Marginalising the dropped features: Lambda_aa - Lambda_ab Lambda_bb^-1 Lambda_ba.
	const Eigen::LLT<Eigen::MatrixXd> llt(map.information(b, b));
	if (llt.info() != Eigen::Success)
		throw NumericalError(
			"local map " + std::to_string(map.index) + ": the information of its left-out features is not positive definite");
	const Eigen::MatrixXd Lab = map.information(a, b);
	out.information -= Lab * llt.solve(Lab.transpose());
	out.information = 0.5 * (out.information + out.information.transpose()).eval();
	return out;
}

}  // namespace esif::slsjf
