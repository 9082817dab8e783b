#include <esif/sparsebench/DslamSequenceFeeder.h>

namespace esif
{
void DslamSequenceFeeder::apply(const DslamStep& step, const DslamLikeSequence& sequence, SparseInformationCore& core)
{
	if (var_of_.empty()) var_of_.assign(sequence.features().size(), -1);
	const double sigma = sequence.options().sigma_m;
	if (step.anchor)
	{
		const Eigen::Vector2d p = sequence.features()[step.reference];
		var_of_[step.reference] = core.addPoint(p).value;
		core.addPrior(variable(step.reference), p, Eigen::Matrix2d::Identity() / (sigma * sigma));
		++mapped_;
	}
	const Eigen::Vector2d ref = core.estimate(variable(step.reference));
	for (std::size_t a = 0; a < step.others.size(); ++a)
		if (var_of_[step.others[a]] < 0)
		{
			var_of_[step.others[a]] = core.addPoint(ref + step.z.segment<2>(2 * a)).value;
			++mapped_;
		}
	if (step.others.empty()) return;

	// z = J x with J = [-I; -I; ...] for the reference, +I for each other.
	const int m = static_cast<int>(step.others.size());
	std::vector<VarId> vars = {variable(step.reference)};
	Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * m, 2 * (m + 1));
	for (int a = 0; a < m; ++a)
	{
		vars.push_back(variable(step.others[a]));
		J.block<2, 2>(2 * a, 0) = -Eigen::Matrix2d::Identity();
		J.block<2, 2>(2 * a, 2 * (a + 1)) = Eigen::Matrix2d::Identity();
	}
	Eigen::VectorXd x(2 * (m + 1));
	for (int a = 0; a <= m; ++a) x.segment<2>(2 * a) = core.estimate(vars[a]);
	core.addMeasurement(vars, J, sequence.covariance(step), step.z - J * x);
	core.setReferencePoint(step.robot.head<2>());
}

}  // namespace esif
