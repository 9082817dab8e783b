#include <esif/core/Errors.h>
#include <esif/io/AtomicFile.h>
#include <esif/io/RawlogWriter.h>
#include <esif/io/VictoriaParkImporter.h>
#include <esif/models/Se2.h>

#include <mrpt/io/CFileGZOutputStream.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <unordered_map>
#include <vector>

namespace esif
{
namespace
{
constexpr double kDeg = M_PI / 180.0;

/// Parses the numbers after the record keyword; false unless exactly `n`
/// finite numbers follow.
bool readFields(std::istringstream& in, std::size_t n, std::vector<double>& out)
{
	out.clear();
	std::string tok;
	while (in >> tok)
	{
		char* end = nullptr;
		const double v = std::strtod(tok.c_str(), &end);
		if (end == tok.c_str() || *end != '\0' || !std::isfinite(v)) return false;
		out.push_back(v);
	}
	return out.size() == n;
}

bool isNodeId(double v) { return v >= 0 && v == std::floor(v) && v < 2147483647.0; }

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

	void addOdometry(const std::vector<double>& f, const std::string& where)
	{
		if (!isNodeId(f[0]) || !isNodeId(f[1])) throw InputError(where + ": pose ids must be non-negative integers");
		const auto from = static_cast<long>(f[0]), to = static_cast<long>(f[1]);
		const auto it = step_of_node_.find(from);
		if (it == step_of_node_.end() || it->second != steps_.size() - 1)
			throw InputError(where + ": odometry must start at the latest pose (" + std::to_string(last_node_) + ")");
		if (step_of_node_.count(to)) throw InputError(where + ": pose " + std::to_string(to) + " already exists");
		StepInput step;
		step.index = steps_.size();
		step.time_s = options_.dt_s * static_cast<double>(step.index);
		OdometryIncrement odo;
		odo.delta = {f[2], f[3], wrapAngle(f[4])};
		odo.cov << f[5], f[6], f[7],  //
			f[6], f[8], f[9],  //
			f[7], f[9], f[10];
		step.odometry = odo;
		step.scan = makeScan();
		step_of_node_[to] = steps_.size();
		last_node_ = to;
		steps_.push_back(step);
	}

	void addLandmark(const std::vector<double>& f, const std::string& where)
	{
		if (!isNodeId(f[0]) || !isNodeId(f[1])) throw InputError(where + ": pose and landmark ids must be non-negative integers");
		const auto it = step_of_node_.find(static_cast<long>(f[0]));
		if (it == step_of_node_.end()) throw InputError(where + ": pose " + std::to_string(static_cast<long>(f[0])) + " not defined yet");
		RangeBearing m;
		m.range_m = std::hypot(f[2], f[3]);
		m.bearing_rad = std::atan2(f[3], f[2]);
		if (options_.keep_ids) m.id = static_cast<LandmarkId>(f[1]);
		ids_.insert(static_cast<long>(f[1]));
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
	std::set<long> ids_;
	long last_node_ = 0;
	std::size_t measurements_ = 0;
};
}  // namespace

VictoriaParkImportSummary importVictoriaPark(
	const std::string& in_path, const std::string& out_rawlog, const VictoriaParkImportOptions& options)
{
	if (!(options.std_range_m > 0) || !(options.std_bearing_deg > 0) || !(options.max_range_m > 0) ||
		!(options.fov_deg > 0 && options.fov_deg <= 360) || !(options.dt_s > 0))
		throw ConfigError("import victoria-park: noise, range, field of view and dt must be > 0 (fov <= 360 deg)");
	std::ifstream in(in_path);
	if (!in) throw InputError(in_path + ": cannot open Victoria Park file");

	StepTable table(options);
	std::string line;
	std::vector<double> fields;
	for (std::size_t lineno = 1; std::getline(in, line); ++lineno)
	{
		std::istringstream ss(line);
		std::string kind;
		if (!(ss >> kind)) continue;  // blank line
		const std::string where = in_path + ":" + std::to_string(lineno);
		if (kind == "ODOMETRY")
		{
			if (!readFields(ss, 11, fields)) throw InputError(where + ": expected 'ODOMETRY i j dx dy dtheta c11 c12 c13 c22 c23 c33'");
			table.addOdometry(fields, where);
		}
		else if (kind == "LANDMARK")
		{
			if (!readFields(ss, 7, fields)) throw InputError(where + ": expected 'LANDMARK i l x y c11 c12 c22'");
			table.addLandmark(fields, where);
		}
		else
			throw InputError(where + ": unknown record '" + kind + "' (expected ODOMETRY or LANDMARK)");
	}
	if (table.steps().size() < 2) throw InputError(in_path + ": no ODOMETRY records");

	const auto folder = std::filesystem::path(out_rawlog).parent_path();
	if (!folder.empty()) ensureDirectory(folder.string());
	const SensorNoise noise{options.std_range_m, options.std_bearing_deg * kDeg};
	writeAtomically(out_rawlog, [&](const std::string& tmp) {
		mrpt::io::CFileGZOutputStream out(tmp, mrpt::io::OpenMode::TRUNCATE, 9);
		auto ar = mrpt::serialization::archiveFrom(out);
		for (const auto& step : table.steps()) appendStep(ar, step, noise);
		out.close();
	});
	return {table.steps().size(), table.measurements(), table.ids()};
}

}  // namespace esif
