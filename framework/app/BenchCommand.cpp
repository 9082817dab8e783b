/// \file BenchCommand.cpp
/// `esif bench sparse`: times the sparse core's recovery methods on a
/// D-SLAM-like sequence (SparseBenchmark.h) and prints CSV. A benchmark, not
/// a test: numbers depend on the machine.

#include "CommandLine.h"
#include "Commands.h"

#include <esif/sparsebench/SparseBenchmark.h>
#include <esif/core/Errors.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace esif::app
{
namespace
{
/// Timed steps per size when --steps is not given: long enough for several
/// reorderings to be amortised, short enough that the default run (three
/// sizes, six methods, fresh factorisation of 10 000 scalars every step)
/// stays under about three minutes on two cores.
constexpr int kDefaultSteps = 400;
/// Bounds of the command line, so a typo cannot allocate gigabytes: 20,000
/// features is four times the largest map of the book's experiments (a
/// sparse state of 40,000 scalars); the dense inverse, O(n^2) memory, runs up
/// to 5,000 features (a 10,000-dimensional matrix, 800 MB).
constexpr int kMinFeatures = 20, kMaxFeatures = 20000, kMaxDenseFeatures = 5000;
constexpr int kMaxSteps = 100000;

std::vector<int> parseSizes(const std::string& text)
{
	std::vector<int> sizes;
	for (const auto& item : splitCommas(text))
	{
		std::size_t used = 0;
		int v = 0;
		try
		{
			v = std::stoi(item, &used);
		}
		catch (const std::exception&)
		{
			used = 0;
		}
		if (used != item.size() || v < kMinFeatures || v > kMaxFeatures)
			throw ConfigError("esif bench sparse: --features: '" + printableToken(item) + "' is not a whole number in [" +
							  std::to_string(kMinFeatures) + ", " + std::to_string(kMaxFeatures) + "]");
		sizes.push_back(v);
	}
	if (sizes.empty()) throw ConfigError("esif bench sparse: --features: no size given");
	return sizes;
}

std::vector<std::string> parseMethods(const std::string& text)
{
	const auto& known = sparseBenchMethods();
	auto methods = splitCommas(text);
	if (methods.empty()) throw ConfigError("esif bench sparse: --methods: no method given");
	for (const auto& m : methods)
		if (std::find(known.begin(), known.end(), m) == known.end())
		{
			std::string list;
			for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
			throw ConfigError(
				"esif bench sparse: --methods: unknown method '" + printableToken(m) + "' (known: " + list + ")");
		}
	return methods;
}

std::string joined(const std::vector<std::string>& items)
{
	std::string out;
	for (const auto& s : items) out += (out.empty() ? "" : ",") + s;
	return out;
}
}  // namespace

int benchCommand(int argc, char** argv)
{
	TCLAP::CmdLine cmd(
		"Benchmarks: 'sparse' times state recovery of the sparse information core on a D-SLAM-like sequence (a "
		"robot maps a grid of features, then keeps sweeping it, closing loops; each timed step adds one "
		"measurement of the 5-15 features in view and recovers the whole state) and prints CSV "
		"method,features,steps,us_per_step,factor_nnz,reorders. Details go to stderr.",
		' ', "");
	TCLAP::UnlabeledValueArg<std::string> what("benchmark", "which benchmark: sparse", true, "", "sparse", cmd);
	TCLAP::ValueArg<std::string> features("", "features", "comma-separated map sizes (features, 20 to 20000)", false,
										  "300,1225,5000", "N,N,...", cmd);
	TCLAP::ValueArg<int> steps("", "steps", "timed steps per size (default 400)", false, kDefaultSteps, "N", cmd);
	TCLAP::ValueArg<std::string> methods("", "methods",
										 "comma-separated methods (dense_inverse runs at the smallest size only, "
										 "and only up to 5000 features)",
										 false, joined(sparseBenchMethods()), "A,B,...", cmd);
	TCLAP::ValueArg<int> n0("", "n0", "the book's n0: trailing dimension that triggers a reordering", false,
							SparseRecoveryParams{}.n0, "N", cmd);
	TCLAP::ValueArg<int> seed("", "seed", "noise seed", false, 1, "N", cmd);
	if (!parseCommandLine(cmd, argc, argv)) return 0;
	if (what.getValue() != "sparse")
		throw ConfigError("esif bench: unknown benchmark '" + printableToken(what.getValue()) + "' (known: sparse)");
	if (steps.getValue() < 1 || steps.getValue() > kMaxSteps)
		throw ConfigError("esif bench sparse: --steps: must be in [1, " + std::to_string(kMaxSteps) + "]");
	if (n0.getValue() < 1 || n0.getValue() > 2 * kMaxFeatures)
		throw ConfigError("esif bench sparse: --n0: must be in [1, " + std::to_string(2 * kMaxFeatures) + "]");

	const auto sizes = parseSizes(features.getValue());
	const auto method_list = parseMethods(methods.getValue());
	const int smallest = *std::min_element(sizes.begin(), sizes.end());
	SparseRecoveryParams params;
	params.n0 = n0.getValue();
	std::fprintf(stderr, "esif bench sparse: %d timed steps per size (%s), n0 = %d, methods %s\n", steps.getValue(),
				 steps.isSet() ? "--steps" : "default", params.n0, joined(method_list).c_str());

	const auto start = std::chrono::steady_clock::now();
	std::printf("method,features,steps,us_per_step,factor_nnz,reorders\n");
	for (int size : sizes)
		for (const auto& method : method_list)
		{
			if (method == "dense_inverse" && (size != smallest || size > kMaxDenseFeatures))
				continue;  // O(n^3) per step, O(n^2) memory
			const SparseBenchResult r =
				runSparseBenchmark(method, size, steps.getValue(), params, static_cast<unsigned>(seed.getValue()));
			std::printf("%s,%d,%d,%.1f,%zu,%zu\n", r.method.c_str(), r.features, r.steps, r.us_per_step, r.factor_nnz,
						r.reorders);
			std::fflush(stdout);
			std::fprintf(stderr,
						 "  %-26s %5d features: partial refactorisations %zu, PCG iterations/solve mean %.2f max %zu; "
						 "timed: update %.3f s, factor %.3f s, recovery %.3f s; run %.1f s\n",
						 r.method.c_str(), r.features, r.partial_refactorisations, r.pcg_iterations_mean,
						 r.pcg_iterations_max, r.update_s, r.factor_s, r.recovery_s, r.total_s);
		}
	const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
	std::fprintf(stderr, "esif bench sparse: done in %.1f s\n", seconds);
	return 0;
}

}  // namespace esif::app
