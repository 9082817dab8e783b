#include "VictoriaParkRecord.h"

#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/core/NumberToken.h>

#include <Eigen/Eigenvalues>

#include <cstdio>
#include <sstream>
#include <vector>

namespace esif::victoria_park
{
namespace
{
struct Layout
{
	const char* keyword;
	std::vector<const char*> fields;
};

const Layout kOdometry{"ODOMETRY", {"i", "j", "dx", "dy", "dtheta", "c11", "c12", "c13", "c22", "c23", "c33"}};
const Layout kLandmark{"LANDMARK", {"i", "l", "x", "y", "c11", "c12", "c22"}};

/// A computed figure (an eigenvalue, a bound like 2 pi) to 4 significant
/// digits: unlike the file's own values, its 17 digits would only be noise.
std::string approx(double v)
{
	char buf[32];
	std::snprintf(buf, sizeof(buf), "%.4g", v);
	return buf;
}

/// The numbers of one record, each known by its field name for the errors.
class Fields
{
   public:
	Fields(const Layout& layout, std::istringstream& in, const std::string& where) : layout_(layout), where_(where)
	{
		std::vector<std::string> tokens;
		for (std::string t; in >> t;) tokens.push_back(t);
		if (tokens.size() != layout.fields.size())
		{
			std::string names;
			for (const char* f : layout.fields) names += std::string(" ") + f;
			throw InputError(
				where + ": expected '" + layout.keyword + names + "' (" + std::to_string(layout.fields.size()) +
				" numbers), found " + std::to_string(tokens.size()));
		}
		for (std::size_t i = 0; i < tokens.size(); ++i) values_.push_back(number(i, tokens[i]));
	}

	/// Field `i`, within +-`limit`; `why` says what the limit stands for.
	double bounded(std::size_t i, double limit, const std::string& unit, const std::string& why) const
	{
		if (std::abs(values_[i]) > limit)
			fail(i, "must be within +-" + approx(limit) + " " + unit + " (" + why + ")");
		return values_[i];
	}

	/// Field `i` as a node ID: an integer in [0, kMaxNodeId].
	long nodeId(std::size_t i) const
	{
		const double v = values_[i];
		if (!(v >= 0 && v <= kMaxNodeId && v == std::floor(v)))
			fail(i, "a node ID must be an integer in [0, " + formatNumber(kMaxNodeId) + "]");
		return static_cast<long>(v);
	}

	/// The symmetric matrix whose upper triangle is fields `first`... row by
	/// row, checked to be a covariance: positive variances on the diagonal,
	/// eigenvalues in [kMinVariance, kMaxVariance].
	template <int N>
	Eigen::Matrix<double, N, N> covariance(std::size_t first) const
	{
		Eigen::Matrix<double, N, N> cov;
		std::size_t k = first;
		for (int r = 0; r < N; ++r)
			for (int c = r; c < N; ++c, ++k)
			{
				if (r == c && !(values_[k] > 0 && values_[k] <= kMaxVariance))
					fail(k, "a variance must be in (0, " + formatNumber(kMaxVariance) + "]");
				cov(r, c) = cov(c, r) = values_[k];
			}
		using Solver = Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>>;
		const auto eigenvalues = Solver(cov, Eigen::EigenvaluesOnly).eigenvalues();  // ascending
		if (!(eigenvalues(0) >= kMinVariance && eigenvalues(N - 1) <= kMaxVariance))
		{
			std::string names, values;
			for (std::size_t j = first; j < k; ++j)
			{
				names += std::string(j == first ? "" : " ") + layout_.fields[j];
				values += (j == first ? "" : " ") + formatNumber(values_[j]);
			}
			throw InputError(
				where_ + ": " + layout_.keyword + " covariance (" + names + ") = (" + values + "): eigenvalues " +
				approx(eigenvalues(0)) + " to " + approx(eigenvalues(N - 1)) + ", must be in [" +
				formatNumber(kMinVariance) + ", " + formatNumber(kMaxVariance) + "] (positive definite, finite)");
		}
		return cov;
	}

	[[noreturn]] void fail(std::size_t i, const std::string& rule) const
	{
		throw InputError(
			where_ + ": " + layout_.keyword + " " + layout_.fields[i] + " = " + formatNumber(values_[i]) + ": " + rule);
	}

   private:
	double number(std::size_t i, const std::string& token) const
	{
		const auto v = doubleToken(token, NonFinite::accepted);
		const std::string head = where_ + ": " + layout_.keyword + " " + layout_.fields[i] + " = '" + token + "': ";
		if (!v) throw InputError(head + "not a number");
		if (!std::isfinite(*v)) throw InputError(head + "not a finite number");
		return *v;
	}

	const Layout& layout_;
	const std::string where_;
	std::vector<double> values_;
};

OdometryRecord odometry(const Fields& f)
{
	OdometryRecord r;
	r.from = f.nodeId(0);
	r.to = f.nodeId(1);
	const std::string step_reason = "longest plausible odometry step";
	r.delta << f.bounded(2, kMaxOdometryStep_m, "m", step_reason), f.bounded(3, kMaxOdometryStep_m, "m", step_reason),
		f.bounded(4, kMaxHeadingChange_rad, "rad", "one full turn; degrees instead of radians?");
	r.cov = f.covariance<3>(5);
	return r;
}

LandmarkRecord landmark(const Fields& f, const std::string& where)
{
	LandmarkRecord r;
	r.pose = f.nodeId(0);
	r.landmark = f.nodeId(1);
	const std::string range_reason = "farthest plausible landmark";
	r.point << f.bounded(2, kMaxLandmarkRange_m, "m", range_reason), f.bounded(3, kMaxLandmarkRange_m, "m", range_reason);
	if (r.point.norm() < kMinLandmarkRange_m)
		throw InputError(
			where + ": LANDMARK x, y = " + formatNumber(r.point.x()) + ", " + formatNumber(r.point.y()) + ": " +
			formatNumber(r.point.norm()) + " m from the sensor, nearer than " + formatNumber(kMinLandmarkRange_m) +
			" m (bearing undefined)");
	r.cov = f.covariance<2>(4);
	return r;
}
}  // namespace

std::optional<Record> parseRecord(const std::string& line, const std::string& where)
{
	std::istringstream in(line);
	std::string kind;
	if (!(in >> kind)) return std::nullopt;
	if (kind == kOdometry.keyword) return odometry(Fields(kOdometry, in, where));
	if (kind == kLandmark.keyword) return landmark(Fields(kLandmark, in, where), where);
	throw InputError(where + ": unknown record '" + kind + "' (expected ODOMETRY or LANDMARK)");
}

}  // namespace esif::victoria_park
