#include <esif/sparsebench/DslamLikeSequence.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace esif
{
namespace
{
/// Boustrophedon lanes 2 spacings apart over [0, w] x [0, h], along x
/// (along_x) or along y, starting one spacing outside the grid.
std::vector<Eigen::Vector2d> lanes(double w, double h, double spacing, bool along_x)
{
	const double across = along_x ? h : w, along = along_x ? w : h;
	std::vector<Eigen::Vector2d> out;
	bool forward = true;
	for (double c = spacing; c <= across + spacing + 1e-9; c += 2 * spacing, forward = !forward)
	{
		const double a0 = forward ? -spacing : along + spacing, a1 = forward ? along + spacing : -spacing;
		out.push_back(along_x ? Eigen::Vector2d(a0, c) : Eigen::Vector2d(c, a0));
		out.push_back(along_x ? Eigen::Vector2d(a1, c) : Eigen::Vector2d(c, a1));
	}
	return out;
}
}  // namespace

DslamLikeSequence::DslamLikeSequence(const DslamSequenceOptions& options) : options_(options), rng_(options.seed)
{
	if (options.features < 2 || options.min_in_view < 2 || options.max_in_view < options.min_in_view ||
		options.features < options.min_in_view || !(options.spacing_m > 0) || !(options.step_m > 0) ||
		!(options.range_m > 0) || !(options.sigma_m > 0))
		throw std::invalid_argument("DslamLikeSequence: invalid options");
	columns_ = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(options.features))));
	for (int f = 0; f < options.features; ++f)
		features_.emplace_back((f % columns_) * options.spacing_m, (f / columns_) * options.spacing_m);
	mapped_.assign(features_.size(), false);

	const double w = (columns_ - 1) * options.spacing_m;
	const double h = ((options.features - 1) / columns_) * options.spacing_m;
	path_ = lanes(w, h, options.spacing_m, true);
	const auto columns_sweep = lanes(w, h, options.spacing_m, false);
	const std::size_t rows_end = path_.size();
	path_.insert(path_.end(), columns_sweep.begin(), columns_sweep.end());
	path_.push_back(path_.front());  // close the cycle: the sweeps repeat
	arc_.assign(1, 0.0);
	for (std::size_t i = 1; i < path_.size(); ++i) arc_.push_back(arc_.back() + (path_[i] - path_[i - 1]).norm());
	mapping_steps_ = static_cast<int>(std::ceil(arc_[rows_end - 1] / options.step_m)) + 1;
}

Eigen::Vector3d DslamLikeSequence::pose(long k) const
{
	const double s = std::fmod(k * options_.step_m, arc_.back());
	const auto it = std::upper_bound(arc_.begin(), arc_.end(), s);
	const std::size_t i = std::min<std::size_t>(std::max<std::ptrdiff_t>(it - arc_.begin(), 1), path_.size() - 1);
	const Eigen::Vector2d a = path_[i - 1], b = path_[i];
	const double len = arc_[i] - arc_[i - 1];
	const Eigen::Vector2d p = len > 0 ? Eigen::Vector2d(a + (b - a) * ((s - arc_[i - 1]) / len)) : a;
	return {p.x(), p.y(), std::atan2(b.y() - a.y(), b.x() - a.x())};
}

std::vector<int> DslamLikeSequence::near(const Eigen::Vector2d& p, double radius) const
{
	// Grid lookup: only the cells within the radius.
	const double sp = options_.spacing_m;
	const int rows = (options_.features + columns_ - 1) / columns_;
	const int c0 = std::max(0, static_cast<int>(std::floor((p.x() - radius) / sp)));
	const int c1 = std::min(columns_ - 1, static_cast<int>(std::ceil((p.x() + radius) / sp)));
	const int r0 = std::max(0, static_cast<int>(std::floor((p.y() - radius) / sp)));
	const int r1 = std::min(rows - 1, static_cast<int>(std::ceil((p.y() + radius) / sp)));
	std::vector<std::pair<double, int>> found;
	for (int r = r0; r <= r1; ++r)
		for (int c = c0; c <= c1; ++c)
		{
			const int f = r * columns_ + c;
			if (f >= options_.features) continue;
			const double d = (features_[f] - p).norm();
			if (d <= radius) found.emplace_back(d, f);
		}
	std::sort(found.begin(), found.end());
	std::vector<int> out;
	for (const auto& [d, f] : found) out.push_back(f);
	return out;
}

std::vector<int> DslamLikeSequence::visible(const Eigen::Vector3d& pose) const
{
	const Eigen::Vector2d p = pose.head<2>();
	const double half_fov = 0.5 * options_.fov_deg * M_PI / 180.0;
	std::vector<int> seen;
	for (int f : near(p, options_.range_m))
	{
		const Eigen::Vector2d d = features_[f] - p;
		const double bearing = std::remainder(std::atan2(d.y(), d.x()) - pose.z(), 2 * M_PI);
		if (std::abs(bearing) <= half_fov && static_cast<int>(seen.size()) < options_.max_in_view) seen.push_back(f);
	}
	// Too few in view (at the borders): the nearest ones complete the set.
	for (double radius = options_.range_m; static_cast<int>(seen.size()) < options_.min_in_view; radius *= 2)
		for (int f : near(p, radius))
			if (static_cast<int>(seen.size()) < options_.min_in_view &&
				std::find(seen.begin(), seen.end(), f) == seen.end())
				seen.push_back(f);
	return seen;
}

int DslamLikeSequence::nearestMapped(const Eigen::Vector2d& p) const
{
	for (double radius = options_.range_m;; radius *= 2)
		for (int f : near(p, radius))
			if (mapped_[f]) return f;
}

DslamStep DslamLikeSequence::next()
{
	DslamStep s;
	s.robot = pose(step_++);
	std::vector<int> seen = visible(s.robot);
	const auto mapped_in_view = std::find_if(seen.begin(), seen.end(), [&](int f) {
		return mapped_[f];
	});
	if (mapped_count_ == 0)
	{
		s.reference = seen.front();  // the first feature anchors the map
		s.anchor = true;
		s.new_features.push_back(s.reference);
	}
	else if (mapped_in_view != seen.end())
		s.reference = *mapped_in_view;  // nearest mapped feature in view
	else
		s.reference = nearestMapped(s.robot.head<2>());  // keeps the map connected
	for (int f : seen)
		if (f != s.reference) s.others.push_back(f);
	std::normal_distribution<double> noise(0.0, options_.sigma_m);
	const Eigen::Vector2d n_ref(noise(rng_), noise(rng_));
	s.z.resize(2 * s.others.size());
	for (std::size_t a = 0; a < s.others.size(); ++a)
	{
		const int f = s.others[a];
		const Eigen::Vector2d n(noise(rng_), noise(rng_));
		s.z.segment<2>(2 * a) = features_[f] - features_[s.reference] + n - n_ref;
		if (!mapped_[f]) s.new_features.push_back(f);
	}
	for (int f : s.new_features)
		if (!mapped_[f])
		{
			mapped_[f] = true;
			++mapped_count_;
		}
	return s;
}

Eigen::MatrixXd DslamLikeSequence::covariance(const DslamStep& step) const
{
	const int m = static_cast<int>(step.others.size());
	const double v = options_.sigma_m * options_.sigma_m;
	Eigen::MatrixXd R = Eigen::MatrixXd::Zero(2 * m, 2 * m);
	for (int a = 0; a < m; ++a)
		for (int b = 0; b < m; ++b)
			R.block<2, 2>(2 * a, 2 * b) = v * (a == b ? 2.0 : 1.0) * Eigen::Matrix2d::Identity();
	return R;
}

}  // namespace esif
