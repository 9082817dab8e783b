#include <esif/sparsebench/DslamSequenceFeeder.h>
#include <esif/sparsebench/SparseBenchmark.h>
#include <esif/core/Elapsed.h>
#include <esif/core/Errors.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>

namespace esif
{
namespace
{
using Clock = SteadyClock;

/// Recovery parameters for a bench method name; false for dense_inverse.
bool sparseParamsFor(const std::string& method, SparseRecoveryParams& p)
{
	if (method == "dense_inverse") return false;
	if (method == "incremental_cholesky" || method == "incremental_cholesky_camd")
		p.recovery = RecoveryMethod::IncrementalCholesky;
	else if (method == "pcg" || method == "pcg_camd")
		p.recovery = RecoveryMethod::Pcg;
	else if (method == "fresh_cholesky")
		p.recovery = RecoveryMethod::FreshCholesky;
	else
		throw ConfigError("esif bench sparse: unknown method '" + method + "'");
	p.reordering =
		method.size() > 5 && method.substr(method.size() - 5) == "_camd" ? Reordering::Camd : Reordering::Distance;
	return true;
}

/// The textbook baseline: x = I^-1 i with the dense inverse, eq. (3.16).
void denseInverseRecovery(const InformationForm& info)
{
	const Eigen::MatrixXd I = info.matrix().toDense();
	const Eigen::LLT<Eigen::MatrixXd> llt(I);
	if (llt.info() != Eigen::Success)
		throw NumericalError("dense inverse: information matrix is not positive definite");
	const Eigen::MatrixXd P = llt.solve(Eigen::MatrixXd::Identity(I.rows(), I.cols()));
	const Eigen::VectorXd x = P * info.vector();
	if (!x.allFinite()) throw NumericalError("dense inverse: non-finite state");
}
}  // namespace

const std::vector<std::string>& sparseBenchMethods()
{
	static const std::vector<std::string> names = {
		"incremental_cholesky", "incremental_cholesky_camd", "pcg", "pcg_camd", "fresh_cholesky", "dense_inverse"};
	return names;
}

SparseBenchResult runSparseBenchmark(const std::string& method, int features, int steps,
									 const SparseRecoveryParams& base, unsigned seed)
{
	const auto t_start = Clock::now();
	SparseRecoveryParams params = base;
	const bool sparse = sparseParamsFor(method, params);
	DslamSequenceOptions options;
	options.features = features;
	options.seed = seed;
	DslamLikeSequence sequence(options);
	SparseInformationCore core(params);
	DslamSequenceFeeder feeder;

	// Mapping sweep: every feature enters the map; no recovery needed here
	// (the model is linear), so no method pays for it.
	for (int k = 0; k < sequence.mappingSteps(); ++k) feeder.apply(sequence.next(), sequence, core);
	if (sparse) core.recoverState();
	const SparseCounters before = core.counters();

	double timed_s = 0;
	std::size_t iterations_max = 0;
	for (int k = 0; k < steps; ++k)
	{
		const DslamStep step = sequence.next();
		const std::size_t iterations_before = core.counters().pcg_iterations_total;
		const auto t0 = Clock::now();
		feeder.apply(step, sequence, core);
		if (sparse)
			core.recoverState();
		else
			denseInverseRecovery(core.information());
		timed_s += secondsSince(t0);
		iterations_max = std::max(iterations_max, core.counters().pcg_iterations_total - iterations_before);
	}

	SparseBenchResult r;
	r.method = method;
	r.features = feeder.mappedFeatures();
	r.steps = steps;
	r.us_per_step = steps > 0 ? 1e6 * timed_s / steps : 0.0;
	const SparseCounters after = core.counters();
	const auto n = static_cast<std::size_t>(core.stateDim());
	r.factor_nnz = sparse ? after.factor_nnz : n * (n + 1) / 2;
	r.reorders = after.full_reorders - before.full_reorders;
	r.partial_refactorisations = after.partial_refactorisations - before.partial_refactorisations;
	const std::size_t solves = after.pcg_solves - before.pcg_solves;
	r.pcg_iterations_mean =
		solves > 0 ? static_cast<double>(after.pcg_iterations_total - before.pcg_iterations_total) / solves : 0.0;
	r.pcg_iterations_max = iterations_max;
	r.update_s = after.update_time_s - before.update_time_s;
	r.factor_s = after.factor_time_s - before.factor_time_s;
	r.recovery_s = after.recovery_time_s - before.recovery_time_s;
	r.total_s = secondsSince(t_start);
	return r;
}

}  // namespace esif
