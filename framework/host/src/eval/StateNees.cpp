#include <esif/core/Errors.h>
#include <esif/eval/LandmarkIdentities.h>
#include <esif/eval/StateNees.h>

#include <esif/eval/MonteCarloStatistics.h>

#include <Eigen/CholmodSupport>

#include <cmath>
#include <vector>

namespace esif
{
namespace
{
/// The reference value of one variable, if the reference has it.
std::optional<Eigen::VectorXd> referenceOf(
	const StateVariable& v, const StateReference& reference,
	const std::optional<std::map<LandmarkId, LandmarkId>>& to_reference)
{
	if (v.kind == StateVariable::Kind::Landmark)
	{
		LandmarkId id = v.landmark;
		if (to_reference)
		{
			const auto mapped = to_reference->find(id);
			if (mapped == to_reference->end()) return std::nullopt;
			id = mapped->second;
		}
		const auto it = reference.landmarks.find(id);
		if (it == reference.landmarks.end()) return std::nullopt;
		return Eigen::VectorXd(it->second);
	}
	if (v.step)
		if (const auto it = reference.poses_by_step.find(*v.step); it != reference.poses_by_step.end())
			return Eigen::VectorXd(it->second);
	if (v.local_map)
		if (const auto it = reference.poses_by_local_map.find(*v.local_map); it != reference.poses_by_local_map.end())
			return Eigen::VectorXd(it->second);
	return std::nullopt;
}

/// Rows/columns `keep` of the symmetric sparse `M`, in that order.
Eigen::SparseMatrix<double> principalBlock(
	const Eigen::SparseMatrix<double>& M, const std::vector<int>& rows, const std::vector<int>& cols)
{
	std::vector<int> row_at(static_cast<std::size_t>(M.rows()), -1), col_at(static_cast<std::size_t>(M.cols()), -1);
	for (std::size_t i = 0; i < rows.size(); ++i) row_at[static_cast<std::size_t>(rows[i])] = static_cast<int>(i);
	for (std::size_t j = 0; j < cols.size(); ++j) col_at[static_cast<std::size_t>(cols[j])] = static_cast<int>(j);
	std::vector<Eigen::Triplet<double>> entries;
	for (int c = 0; c < M.outerSize(); ++c)
	{
		const int j = col_at[static_cast<std::size_t>(c)];
		if (j < 0) continue;
		for (Eigen::SparseMatrix<double>::InnerIterator it(M, c); it; ++it)
			if (const int i = row_at[static_cast<std::size_t>(it.row())]; i >= 0) entries.emplace_back(i, j, it.value());
	}
	Eigen::SparseMatrix<double> out(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
	out.setFromTriplets(entries.begin(), entries.end());
	return out;
}
}  // namespace

StateReference stateReferenceOf(const GroundTruth& truth)
{
	StateReference r;
	r.landmarks = truth.landmarks;
	for (std::size_t k = 0; k < truth.path.size(); ++k) r.poses_by_step[k] = truth.path[k];
	return r;
}

StateReference stateReferenceOf(const RunOutputs& run, std::size_t steps)
{
	GroundTruth truth = runAsGroundTruth(run);
	if (truth.path.size() != steps) truth.path.clear();	 // rows that cannot be paired with steps
	if (run.identities && run.identities->truth)
	{
		// By true landmark: the landmark that stands for each (its duplicates left out).
		std::map<LandmarkId, Eigen::Vector2d> by_true_id;
		for (const auto& [true_id, id] : primaryLandmarks(*run.identities)) by_true_id.emplace(true_id, truth.landmarks.at(id));
		truth.landmarks = std::move(by_true_id);
	}
	return stateReferenceOf(truth);
}

std::optional<StateNees> stateNees(
	const StateInformation& state, const StateReference& reference,
	const std::optional<std::map<LandmarkId, LandmarkId>>& to_reference, const std::string& what)
{
	StateNees out;
	std::vector<int> compared, marginalised;
	std::vector<double> error;
	int offset = 0;
	for (const StateVariable& v : state.variables)
	{
		const int d = v.dim();
		if (const auto ref = referenceOf(v, reference, to_reference))
		{
			Eigen::VectorXd e = state.mean.segment(offset, d) - *ref;
			if (v.kind == StateVariable::Kind::Pose) e(2) = wrapAngle(e(2));
			for (int i = 0; i < d; ++i)
			{
				compared.push_back(offset + i);
				error.push_back(e(i));
			}
			++(v.kind == StateVariable::Kind::Pose ? out.poses_compared : out.landmarks_compared);
		}
		else
		{
			for (int i = 0; i < d; ++i) marginalised.push_back(offset + i);
			++out.variables_marginalised;
		}
		offset += d;
	}
	if (offset != state.mean.size() || state.information.rows() != offset || state.information.cols() != offset)
		throw NumericalError(what + ": state information of inconsistent size");
	if (compared.empty()) return std::nullopt;

	const Eigen::Map<const Eigen::VectorXd> e(error.data(), static_cast<Eigen::Index>(error.size()));
	out.nees = e.dot(principalBlock(state.information, compared, compared) * e);
	if (!marginalised.empty())
	{
		// Schur complement: the information of the compared variables alone.
		const Eigen::SparseMatrix<double> I_uu = principalBlock(state.information, marginalised, marginalised);
		const Eigen::VectorXd b = principalBlock(state.information, marginalised, compared) * e;
		// CHOLMOD rejects a matrix without entries, and would print its own
		// warnings: esif reports the failure itself.
		const bool empty_diagonal = (I_uu.diagonal().array() <= 0).any();
		Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
		llt.cholmod().print = 0;
		if (!empty_diagonal) llt.compute(I_uu);
		if (empty_diagonal || llt.info() != Eigen::Success)
			throw NumericalError(what + ": the information of the variables without a reference is not positive definite");
		out.nees -= b.dot(llt.solve(b));
	}
	if (!std::isfinite(out.nees)) throw NumericalError(what + ": the state NEES is not finite");
	out.dof = compared.size();
	const AneesBounds interval = aneesBounds(static_cast<int>(out.dof), 1);	// one run: chi-square(dof) itself
	out.lower95 = interval.lo;
	out.upper95 = interval.hi;
	return out;
}

}  // namespace esif
