#include <esif/association/Chi2.h>
#include <esif/calibration/InnovationLikelihood.h>
#include <esif/core/Errors.h>
#include <esif/ekf/EkfSlamCore.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace esif
{
namespace
{
const double kLog2Pi = std::log(2 * M_PI);
/// The iterated update (EkfSlamCore.h): after a long blind drive the first
/// re-observation corrects metres, and a plain update linearised there
/// leaves the later innovations inconsistent, which the fit would otherwise
/// blame on the noise.
const IteratedUpdate kIterated{10, 1.0};

/// log of the outlier density: uniform over [0, max range] x field of view.
/// A log without them spreads it over 100 m and the whole circle.
double outlierLogDensity(const Scan& scan)
{
	const double range = scan.max_range_m > 0 ? scan.max_range_m : 100.0;
	const double fov = scan.fov_rad > 0 ? scan.fov_rad : 2 * M_PI;
	return -std::log(range * fov);
}

/// -log N(nu; 0, S) through the Cholesky factor of S; nullopt if S is not positive definite.
std::optional<double> gaussianNll(const Eigen::VectorXd& nu, const Eigen::MatrixXd& S)
{
	const Eigen::LLT<Eigen::MatrixXd> llt(S);
	if (llt.info() != Eigen::Success) return std::nullopt;
	const double log_det = 2 * llt.matrixLLT().diagonal().array().log().sum();
	return 0.5 * (nu.dot(llt.solve(nu)) + log_det + static_cast<double>(nu.size()) * kLog2Pi);
}

/// The EKF pass over one log, accumulating into `stats`.
class LikelihoodPass
{
   public:
	LikelihoodPass(const NoiseCalibration& calibration, const LikelihoodOptions& options, InnovationStats& stats)
		: calibration_(calibration),
		  log_inlier_(std::log1p(-options.outlier_fraction)),
		  log_outlier_(options.outlier_fraction > 0 ? std::log(options.outlier_fraction)
													: -std::numeric_limits<double>::infinity()),
		  gate_9999_(chi2Quantile(0.9999, 2)),
		  stats_(stats)
	{
	}

	void step(const StepInput& raw)
	{
		const StepInput step = calibratedStep(raw, calibration_);
		if (step.odometry) core_.predict(*step.odometry);
		if (step.scan) scan(*step.scan);
	}

	/// Sum of the individual NIS of the inliers so far.
	double nisSum() const { return nis_sum_; }

   private:
	void scan(const Scan& scan)
	{
		const Pose2 sensor = scan.sensor_on_robot;
		const double log_outlier_density = log_outlier_ + outlierLogDensity(scan);
		std::vector<EkfSlamCore::Match> inliers;
		std::vector<const RangeBearing*> fresh;
		std::unordered_set<LandmarkId> seen;
		for (const auto& m : scan.measurements)
		{
			if (!m.id || !seen.insert(*m.id).second) continue;	// one measurement per landmark and scan
			const auto it = index_.find(*m.id);
			if (it == index_.end())
			{
				fresh.push_back(&m);
				continue;
			}
			++stats_.reobservations;
			const auto h = core_.predictMeasurement(it->second, sensor);
			Eigen::VectorXd nu(2);
			nu << m.range_m - h.z(0), wrapAngle(m.bearing_rad - h.z(1));
			const Eigen::MatrixXd S = core_.predictionCovariance({it->second}, sensor) + m.cov;
			const auto nll = gaussianNll(nu, S);
			if (!nll) throw NumericalError("innovation covariance not positive definite");
			const double nis = nu.dot(S.llt().solve(nu));
			stats_.above_gate_9999 += nis > gate_9999_;
			if (log_inlier_ - *nll < log_outlier_density)
			{
				++stats_.outliers;
				stats_.nll -= log_outlier_density;
				continue;
			}
			nis_sum_ += nis;
			inliers.push_back({it->second, Eigen::Vector2d(m.range_m, m.bearing_rad), m.cov});
		}
		scoreJointly(inliers, sensor);
		core_.update(inliers, sensor, kIterated);
		for (const RangeBearing* m : fresh)
		{
			index_[*m->id] = core_.addLandmark(Eigen::Vector2d(m->range_m, m->bearing_rad), m->cov, sensor);
			++stats_.initialisations;
		}
	}

	/// The inliers of one scan share the robot's error: their density is joint.
	void scoreJointly(const std::vector<EkfSlamCore::Match>& inliers, const Pose2& sensor)
	{
		if (inliers.empty()) return;
		const auto k = static_cast<Eigen::Index>(inliers.size());
		std::vector<std::size_t> indices;
		Eigen::VectorXd nu(2 * k);
		for (Eigen::Index i = 0; i < k; ++i)
		{
			const auto& m = inliers[static_cast<std::size_t>(i)];
			indices.push_back(m.landmark);
			const auto h = core_.predictMeasurement(m.landmark, sensor);
			nu.segment<2>(2 * i) << m.z(0) - h.z(0), wrapAngle(m.z(1) - h.z(1));
		}
		Eigen::MatrixXd S = core_.predictionCovariance(indices, sensor);
		for (Eigen::Index i = 0; i < k; ++i) S.block<2, 2>(2 * i, 2 * i) += inliers[static_cast<std::size_t>(i)].R;
		const auto nll = gaussianNll(nu, S);
		if (!nll) throw NumericalError("joint innovation covariance not positive definite");
		stats_.nll += *nll - static_cast<double>(k) * log_inlier_;
	}

	const NoiseCalibration& calibration_;
	const double log_inlier_, log_outlier_, gate_9999_;
	InnovationStats& stats_;
	// First-estimates Jacobians: the EKF variant that does not gain spurious
	// heading information (EkfSlamCore.h), so its S measures the noise
	// rather than the filter's own over-confidence.
	EkfSlamCore core_{JacobianPoints::FirstEstimates};
	std::unordered_map<LandmarkId, std::size_t> index_;
	double nis_sum_ = 0;
};
}  // namespace

InnovationStats innovationLikelihood(
	const std::vector<CalibrationLog>& logs, const NoiseCalibration& calibration, const LikelihoodOptions& options)
{
	InnovationStats stats;
	double nis_sum = 0;
	try
	{
		for (const auto& log : logs)
		{
			LikelihoodPass pass(calibration, options, stats);
			for (const auto& step : log.steps) pass.step(step);
			nis_sum += pass.nisSum();
		}
	}
	catch (const NumericalError&)
	{
		stats.nll = std::numeric_limits<double>::infinity();
		return stats;
	}
	const std::size_t inliers = stats.reobservations - stats.outliers;
	stats.nis_mean = inliers ? nis_sum / static_cast<double>(inliers) : 0;
	stats.above_gate_9999 = stats.reobservations ? stats.above_gate_9999 / static_cast<double>(stats.reobservations) : 0;
	return stats;
}

}  // namespace esif
