#include <esif/association/Ambiguity.h>
#include <esif/association/CandidateWindow.h>
#include <esif/association/Chi2.h>
#include <esif/association/DataAssociation.h>
#include <esif/core/Errors.h>
#include <esif/core/MeasurementSubset.h>
#include <esif/models/RangeBearingModel.h>
#include <esif/ekf/LandmarkEkf.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace esif
{
LandmarkEkf::LandmarkEkf(const EkfAssociationParams& params, LandmarkId first_own_id, JacobianPoints jacobians)
	: params_(params),
	  gate_distance2_new_(chi2Quantile(params.new_landmark_chi2_quantile, 2)),
	  id_gate_distance2_(params.idGateDistance2()),
	  iterated_{params.update_iterations, params.relinearise_above_d2},
	  core_(jacobians),
	  next_own_id_(first_own_id),
	  tentative_(gate_distance2_new_, static_cast<std::size_t>(params.confirmation_window_steps)),
	  coincident_(params.merge_landmarks_after_matches, params.merge_chi2_quantile)
{
}

StepReport LandmarkEkf::processStep(const StepInput& step)
{
	tentative_.expire(step.index);
	if (step.odometry) core_.predict(*step.odometry);
	if (!step.scan) return {};
	if (params_.min_range_m > 0) return processUsableMeasurements(step);
	return processScan(step);
}

StepReport LandmarkEkf::processScan(const StepInput& step)
{
	std::vector<EkfSlamCore::Match> matches;
	unconfirmed_failing_.clear();
	StepReport report = associateScan(step, matches);
	const auto outcome = core_.update(matches, step.scan->sensor_on_robot, iterated_);
	if (outcome.linearisations > 1)
	{
		++iterated_updates_;
		relinearisations_ += static_cast<std::size_t>(outcome.linearisations - 1);
	}
	if (outcome.stopped_uphill) ++stopped_uphill_;
	for (const auto& m : matches) confirmed_.insert(ids_[m.landmark]);
	dropLandmarks(unconfirmed_failing_);
	addNewLandmarks(*step.scan, step.index, report);
	mergeCoincidentLandmarks();
	return report;
}

void LandmarkEkf::mergeCoincidentLandmarks()
{
	while (const auto pair = coincident_.nextPair(core_, ids_))
	{
		const auto [keep, drop] = *pair;
		if (!core_.mergeLandmarks(keep, drop)) return;
		coincident_.recordMerge(ids_[keep], ids_[drop]);
		ids_.erase(ids_.begin() + static_cast<std::ptrdiff_t>(drop));
		reindex();
	}
}

void LandmarkEkf::dropLandmarks(std::vector<std::size_t> indices)
{
	if (indices.empty()) return;
	std::sort(indices.begin(), indices.end());
	std::vector<std::size_t> keep;
	std::vector<LandmarkId> kept_ids;
	for (std::size_t i = 0; i < ids_.size(); ++i)
		if (!std::binary_search(indices.begin(), indices.end(), i)) keep.push_back(i), kept_ids.push_back(ids_[i]);
	core_.retainLandmarks(keep);
	ids_ = std::move(kept_ids);
	reindex();
}

void LandmarkEkf::reindex()
{
	index_of_.clear();
	for (std::size_t i = 0; i < ids_.size(); ++i) index_of_[ids_[i]] = i;
}

double LandmarkEkf::innovationDistance2(
	std::size_t index, const RangeBearing& m, const Eigen::Matrix2d& noise, const Pose2& sensor) const
{
	const auto h = core_.predictMeasurement(index, sensor);
	Eigen::Vector2d nu(m.range_m - h.z(0), wrapAngle(m.bearing_rad - h.z(1)));
	const Eigen::Matrix2d S = core_.predictionCovariance({index}, sensor) + noise;
	const Eigen::LLT<Eigen::Matrix2d> llt(S);
	if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
	return nu.dot(llt.solve(nu));
}

StepReport LandmarkEkf::processUsableMeasurements(const StepInput& step)
{
	// The scan without the measurements closer than min_range_m, which are
	// reported as rejected in their places (MeasurementSubset).
	const MeasurementSubset usable_part = measurementSubset(
		*step.scan, [&](std::size_t, const RangeBearing& m) { return m.range_m >= params_.min_range_m; });
	StepInput usable;
	usable.index = step.index;
	usable.time_s = step.time_s;
	usable.scan = usable_part.scan;
	return usable_part.spread(processScan(usable));
}

std::optional<std::size_t> LandmarkEkf::indexOf(LandmarkId id) const
{
	const auto it = index_of_.find(id);
	if (it == index_of_.end()) return std::nullopt;
	return it->second;
}

StepReport LandmarkEkf::associateScan(const StepInput& step, std::vector<EkfSlamCore::Match>& matches)
{
	const auto& ms = step.scan->measurements;
	const bool all_have_ids = std::all_of(ms.begin(), ms.end(), [](const RangeBearing& m) { return m.id.has_value(); });
	switch (params_.association)
	{
		case EkfAssociation::KnownIds: return associateByIds(step, matches);
		case EkfAssociation::Auto:
			return all_have_ids ? associateByIds(step, matches) : associateByDistance(*step.scan, matches);
		default: return associateByDistance(*step.scan, matches);
	}
}

StepReport LandmarkEkf::associateByIds(const StepInput& step, std::vector<EkfSlamCore::Match>& matches)
{
	const auto& ms = step.scan->measurements;
	const Pose2 sensor = step.scan->sensor_on_robot;
	// A second measurement of one landmark in one scan is not independent
	// information about it: only the one closest to the landmark is used
	// (the first when the landmark is new), so a misread ID cannot displace
	// the correct measurement.
	std::vector<double> d2(ms.size(), 0);
	std::unordered_map<LandmarkId, std::size_t> used;
	for (std::size_t i = 0; i < ms.size(); ++i)
	{
		if (!ms[i].id)
			throw InputError(
				"step " + std::to_string(step.index) + ", measurement " + std::to_string(i) +
				": no landmark ID but association = known_ids");
		// The ID gate is an outlier test of the sensor's own hypothesis: it
		// takes the noise the update will assume (a wrongly rejected ID loses
		// a valid measurement).
		if (const auto index = indexOf(*ms[i].id)) d2[i] = innovationDistance2(*index, ms[i], ms[i].cov, sensor);
		if (const auto [it, first] = used.emplace(*ms[i].id, i); !first && d2[i] < d2[it->second]) it->second = i;
	}

	StepReport report;
	for (std::size_t i = 0; i < ms.size(); ++i)
	{
		const LandmarkId id = *ms[i].id;
		const auto index = indexOf(id);
		if (used.at(id) != i)
			report.associations.push_back({Association::Kind::Rejected, id});
		else if (!index)
			report.associations.push_back({Association::Kind::New, id});
		else if (d2[i] <= id_gate_distance2_)
		{
			report.associations.push_back({Association::Kind::Matched, id});
			matches.push_back({*index, Eigen::Vector2d(ms[i].range_m, ms[i].bearing_rad), ms[i].cov});
		}
		else if (!confirmed_.count(id))
		{
			unconfirmed_failing_.push_back(*index);
			++id_gate_drops_;
			report.associations.push_back({Association::Kind::Rejected, id});
		}
		else
		{
			++id_gate_rejections_;
			report.associations.push_back({Association::Kind::Rejected, id});
		}
	}
	return report;
}

std::vector<std::size_t> LandmarkEkf::candidatesFor(const Scan& scan) const
{
	const CandidateWindow window(scan, params_.candidate_margin_m, params_.candidate_margin_deg);
	std::vector<std::size_t> out;
	// A merged landmark is offered once per landmark it stands for (at most
	// once per measurement), so that JCBB, one-to-one, can give it every
	// sighting of its cluster (CoincidentLandmarks.h).
	const int measurements = static_cast<int>(scan.measurements.size());
	for (std::size_t i = 0; i < core_.landmarkCount(); ++i)
		if (window.admits(core_.predictMeasurement(i, scan.sensor_on_robot).z))
			out.insert(out.end(), static_cast<std::size_t>(std::min(coincident_.standsFor(ids_[i]), measurements)), i);
	return out;
}

StepReport LandmarkEkf::associateByDistance(const Scan& scan, std::vector<EkfSlamCore::Match>& matches)
{
	const auto& ms = scan.measurements;
	const Pose2 sensor = scan.sensor_on_robot;
	const auto candidates = candidatesFor(scan);

	AssociationInput in;
	in.observations.resize(ms.size(), 2);
	for (std::size_t i = 0; i < ms.size(); ++i) in.observations.row(i) << ms[i].range_m, ms[i].bearing_rad;
	in.predictions.resize(candidates.size(), 2);
	for (std::size_t j = 0; j < candidates.size(); ++j)
		in.predictions.row(j) = core_.predictMeasurement(candidates[j], sensor).z.transpose();
	in.covariance = core_.predictionCovariance(candidates, sensor);
	// MRPT's association takes one noise for all measurements of a scan: the
	// sensor's nominal covariance (that of the first measurement), of one
	// sighting (sightingCov: a gate compares one measurement's innovation).
	for (std::size_t j = 0; j < candidates.size() && !ms.empty(); ++j)
		in.covariance.block<2, 2>(2 * j, 2 * j) += sightingCov(scan, ms.front());

	const auto result = associate(
		in, params_.association == EkfAssociation::NearestNeighbor ? AssociationMethod::NearestNeighbor
																   : AssociationMethod::Jcbb,
		params_.gate_chi2_quantile, params_.search);
	jcbb_nodes_ += result.jcbb_nodes;
	jcbb_fallbacks_ += result.fell_back;

	StepReport report;
	std::vector<bool> taken(candidates.size(), false);
	// With two pairs or more the joint test has decided between the
	// hypotheses; a lone pair rests on its individual gate alone.
	const bool lone_pair =
		std::count_if(result.candidate_of.begin(), result.candidate_of.end(), [](int c) { return c >= 0; }) == 1;
	for (std::size_t i = 0; i < ms.size(); ++i)
	{
		const int c = result.candidate_of[i];
		if (c >= 0 && !taken[c] && lone_pair && isAmbiguous(scan, ms[i], candidates, static_cast<std::size_t>(c)))
		{
			++rejections_.ambiguous_waits;
			report.associations.push_back({Association::Kind::Rejected, -1});
		}
		else if (c >= 0 && !taken[c])
		{
			taken[c] = true;
			const std::size_t idx = candidates[c];
			report.associations.push_back({Association::Kind::Matched, ids_[idx]});
			matches.push_back({idx, Eigen::Vector2d(ms[i].range_m, ms[i].bearing_rad), ms[i].cov});
			coincident_.countMatch(ids_[idx]);
		}
		else if (c < 0 && result.min_distance2[i] > gate_distance2_new_)
			report.associations.push_back({Association::Kind::New, -1});
		else
		{
			rejections_.poorly_observed += c < 0;
			report.associations.push_back({Association::Kind::Rejected, -1});
		}
	}
	return report;
}

bool LandmarkEkf::isAmbiguous(
	const Scan& scan, const RangeBearing& m, const std::vector<std::size_t>& candidates, std::size_t chosen) const
{
	const Pose2 sensor = scan.sensor_on_robot;
	const double margin = params_.ambiguityMarginDistance2();
	if (margin <= 0) return false;
	Eigen::VectorXd d2(static_cast<Eigen::Index>(candidates.size()));
	for (std::size_t j = 0; j < candidates.size(); ++j)
		d2(static_cast<Eigen::Index>(j)) = innovationDistance2(candidates[j], m, sightingCov(scan, m), sensor);
	const Eigen::Vector2d z_chosen = core_.predictMeasurement(candidates[chosen], sensor).z;
	const Eigen::LLT<Eigen::Matrix2d> sensor_noise(sightingCov(scan, m));
	return ambiguousMatch(d2, static_cast<Eigen::Index>(chosen), margin, [&](Eigen::Index j) {
		Eigen::Vector2d dz = core_.predictMeasurement(candidates[static_cast<std::size_t>(j)], sensor).z - z_chosen;
		dz(1) = wrapAngle(dz(1));
		return dz.dot(sensor_noise.solve(dz));
	});
}

bool LandmarkEkf::confirmedSighting(const Scan& scan, const RangeBearing& m, std::size_t step)
{
	const Pose2 sensor = scan.sensor_on_robot;
	const LandmarkFromMeasurement p = landmarkFromRangeBearing(core_.robot(), sensor, m.range_m, m.bearing_rad);
	Eigen::Matrix2d cov = p.d_robot * core_.robotCov() * p.d_robot.transpose() +
		p.d_measurement * sightingCov(scan, m) * p.d_measurement.transpose();
	cov = (0.5 * (cov + cov.transpose())).eval();
	return tentative_.confirm(std::nullopt, p.position, cov, step);
}

void LandmarkEkf::addNewLandmarks(const Scan& scan, std::size_t step, StepReport& report)
{
	const Pose2 sensor = scan.sensor_on_robot;
	for (std::size_t i = 0; i < report.associations.size(); ++i)
	{
		auto& a = report.associations[i];
		if (a.kind != Association::Kind::New) continue;
		const auto& m = scan.measurements[i];
		if (a.id < 0 && params_.confirm_new_landmarks && !confirmedSighting(scan, m, step))
		{
			a.kind = Association::Kind::Rejected;
			++rejections_.unconfirmed;
			continue;
		}
		if (a.id < 0)
		{
			while (index_of_.count(next_own_id_)) ++next_own_id_;
			a.id = next_own_id_++;
		}
		else
			coincident_.keepApart(a.id);
		const std::size_t idx = core_.addLandmark(Eigen::Vector2d(m.range_m, m.bearing_rad), m.cov, sensor);
		ids_.push_back(a.id);
		index_of_[a.id] = idx;
	}
}

void LandmarkEkf::addPriorLandmarks(const EarlierFeatures& features)
{
	if (features.size() == 0) return;
	for (const LandmarkId id : features.ids)
		if (index_of_.count(id))
			throw std::invalid_argument("LandmarkEkf::addPriorLandmarks: landmark " + std::to_string(id) + " is mapped already");
	const auto n = static_cast<Eigen::Index>(core_.stateDim());
	const auto m = static_cast<Eigen::Index>(2 * features.size());
	Eigen::VectorXd x(n + m);
	x << core_.state(), features.positions;
	Eigen::MatrixXd P = Eigen::MatrixXd::Zero(n + m, n + m);
	P.topLeftCorner(n, n) = core_.covariance();
	P.bottomRightCorner(m, m) = features.covariance;
	core_.setState(x, P);
	for (const LandmarkId id : features.ids)
	{
		index_of_[id] = ids_.size();
		ids_.push_back(id);
		confirmed_.insert(id);
	}
}

PoseEstimate LandmarkEkf::robotPose() const { return {core_.robot(), core_.robotCov()}; }

Estimate LandmarkEkf::estimate() const
{
	Estimate e;
	e.robot = robotPose();
	e.landmarks.reserve(ids_.size());
	for (std::size_t i = 0; i < ids_.size(); ++i) e.landmarks.push_back({ids_[i], core_.landmark(i), core_.landmarkCov(i)});
	return e;
}

}  // namespace esif
