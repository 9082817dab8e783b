#include "ImportOptions.h"
#include "VictoriaParkRecord.h"

#include <esif/config/ParamBinder.h>
#include <esif/core/Errors.h>
#include <esif/core/TextInput.h>
#include <esif/formats/GzArchive.h>
#include <esif/formats/RawlogWriter.h>
#include <esif/formats/VictoriaParkImporter.h>
#include <esif/models/Se2.h>
#include <esif/safeio/AtomicFile.h>
#include <esif/safeio/OutputApart.h>

#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <unordered_map>
#include <vector>

namespace esif
{
namespace
{
constexpr double kDeg = M_PI / 180.0;

/// The steps of the dataset: one per pose, odometry from the previous pose.
class StepTable
{
   public:
	explicit StepTable(const VictoriaParkImportOptions& o) : options_(o)
	{
		steps_.emplace_back();	// pose 0: no odometry, possibly measurements
		steps_.back().scan = makeScan();
		step_of_node_[0] = 0;
	}

	void addOdometry(const victoria_park::OdometryRecord& r, const std::string& where)
	{
		const auto it = step_of_node_.find(r.from);
		if (it == step_of_node_.end() || it->second != steps_.size() - 1)
			throw InputError(
				where + ": ODOMETRY i = " + std::to_string(r.from) + ": odometry must start at the latest pose (" +
				std::to_string(last_node_) + ")");
		if (step_of_node_.count(r.to))
			throw InputError(where + ": ODOMETRY j = " + std::to_string(r.to) + ": pose already exists");
		StepInput step;
		step.index = steps_.size();
		step.time_s = options_.dt_s * static_cast<double>(step.index);
		OdometryIncrement odo;
		odo.delta = {r.delta.x(), r.delta.y(), wrapAngle(r.delta.z())};
		odo.cov = r.cov;
		step.odometry = odo;
		step.scan = makeScan();
		step_of_node_[r.to] = steps_.size();
		last_node_ = r.to;
		steps_.push_back(step);
	}

	void addLandmark(const victoria_park::LandmarkRecord& r, const std::string& where)
	{
		const auto it = step_of_node_.find(r.pose);
		if (it == step_of_node_.end())
			throw InputError(where + ": LANDMARK i = " + std::to_string(r.pose) + ": pose not defined yet");
		RangeBearing m;
		m.range_m = r.point.norm();
		// The scans store the sensor range: a filter predicting visibility
		// from it must not meet a measurement beyond.
		if (m.range_m > options_.max_range_m)
			throw InputError(
				where + ": LANDMARK x, y = " + formatNumber(r.point.x()) + ", " + formatNumber(r.point.y()) + ": range " +
				formatNumber(m.range_m) + " m beyond the sensor range --max-range-m = " +
				formatNumber(options_.max_range_m) + " m");
		m.bearing_rad = std::atan2(r.point.y(), r.point.x());
		if (const auto [first, fresh] = seen_[it->second].emplace(r.landmark, where); !fresh)
			throw InputError(
				where + ": LANDMARK " + std::to_string(r.pose) + " " + std::to_string(r.landmark) + ": landmark " +
				std::to_string(r.landmark) + " is measured twice from pose " + std::to_string(r.pose) +
				" (first on line " + first->second.substr(first->second.rfind(':') + 1) + "): a repeated line");
		if (options_.keep_ids) m.id = static_cast<LandmarkId>(r.landmark);
		ids_.insert(r.landmark);
		steps_[it->second].scan->measurements.push_back(m);
		++measurements_;
	}

	const std::vector<StepInput>& steps() const { return steps_; }
	std::size_t measurements() const { return measurements_; }
	std::size_t ids() const { return ids_.size(); }

   private:
	Scan makeScan() const
	{
		Scan s;
		s.max_range_m = options_.max_range_m;
		s.fov_rad = options_.fov_deg * kDeg;
		return s;
	}

	const VictoriaParkImportOptions& options_;
	std::vector<StepInput> steps_;
	std::unordered_map<long, std::size_t> step_of_node_;
	/// The landmarks each step's scan holds, with where each was read: one
	/// scan cannot measure a landmark twice.
	std::unordered_map<std::size_t, std::map<long, std::string>> seen_;
	std::set<long> ids_;
	long last_node_ = 0;
	std::size_t measurements_ = 0;
};

void validateOptions(const VictoriaParkImportOptions& o)
{
	using namespace victoria_park;
	const std::string who = "import victoria-park";
	checkSensorNoise(who, o.std_range_m, o.std_bearing_deg);
	checkImportOption(who, "--max-range-m", o.max_range_m, 0, kMaxLandmarkRange_m, "farthest plausible landmark");
	checkImportOption(who, "--fov-deg", o.fov_deg, 0, 360.0, "a full circle");
	// One hour between poses: slower than any logged vehicle run.
	checkImportOption(who, "--dt-s", o.dt_s, 0, 3600.0, "one hour between poses");
}
}  // namespace

VictoriaParkImportSummary importVictoriaPark(
	const std::string& in_path, const std::string& out_rawlog, const VictoriaParkImportOptions& options)
{
	validateOptions(options);
	requireOutputApart(out_rawlog, {{"the dataset", in_path}});
	TextLineReader in(in_path, "Victoria Park file");

	StepTable table(options);
	for (std::string line; in.next(line);)
	{
		const std::string where = in.where();
		const auto record = victoria_park::parseRecord(line, where);
		if (!record) continue;	// blank line
		if (const auto* odometry = std::get_if<victoria_park::OdometryRecord>(&*record))
			table.addOdometry(*odometry, where);
		else
			table.addLandmark(std::get<victoria_park::LandmarkRecord>(*record), where);
	}
	if (table.steps().size() < 2) throw InputError(in_path + ": no ODOMETRY records");

	const auto folder = std::filesystem::path(out_rawlog).parent_path();
	if (!folder.empty()) ensureDirectory(folder.string());
	const SensorNoise noise{options.std_range_m, options.std_bearing_deg * kDeg};
	writeGzArchiveAtomically(
		out_rawlog, [&](mrpt::serialization::CArchive& ar) { for (const auto& step : table.steps()) appendStep(ar, step, noise); },
		9);
	return {table.steps().size(), table.measurements(), table.ids()};
}

}  // namespace esif
