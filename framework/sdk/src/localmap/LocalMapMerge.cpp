#include <esif/core/Errors.h>
#include <esif/localmap/LocalMapMerge.h>
#include <esif/models/LocalMapObservation.h>
#include <esif/models/Se2.h>

#include <Eigen/Cholesky>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace esif
{
namespace
{
using Index = Eigen::Index;

/// Where each variable of the merged problem sits in the stacked vector x.
/// The variables kept come first, in the order of the result's state
/// ([e_b; features]), and the ones marginalised out last (e_a, then s), so
/// that the final Schur complement keeps a leading block.
struct Layout
{
	static constexpr Index kEndB = 0;  ///< e_b
	Index end_a = 0;  ///< e_a: a's end pose = b's start pose, or the pose b's link starts from
	Index start_b = -1;	 ///< s: b's own start pose (only with b.link)
	Index kept = 0;	 ///< dimension of [e_b; features]
	Index dim = 0;	///< dimension of x
	std::vector<LandmarkId> ids;  ///< merged features: a's in a's order, then those only in b
	std::vector<Index> col_of_a, col_of_b;	///< column of each feature of a (of b) in x
	std::vector<std::size_t> b_only;  ///< indices (in b) of the features only in b
};

Layout makeLayout(const LocalMap& a, const LocalMap& b)
{
	Layout L;
	std::map<LandmarkId, Index> col;  // feature ID -> column
	Index next = 3;
	for (const auto& f : a.features)
	{
		L.ids.push_back(f.id);
		L.col_of_a.push_back(next);
		col[f.id] = next;
		next += 2;
	}
	for (std::size_t i = 0; i < b.features.size(); ++i)
	{
		const auto it = col.find(b.features[i].id);
		if (it != col.end())
		{
			L.col_of_b.push_back(it->second);
			continue;
		}
		L.ids.push_back(b.features[i].id);
		L.b_only.push_back(i);
		L.col_of_b.push_back(next);
		next += 2;
	}
	L.kept = next;
	L.end_a = next;
	next += 3;
	if (b.link)
	{
		L.start_b = next;
		next += 3;
	}
	L.dim = next;
	return L;
}

/// Scalar indices of x for a list of variables given by (first column, size).
std::vector<Index> scalarIndices(const std::vector<std::pair<Index, Index>>& blocks)
{
	std::vector<Index> out;
	for (const auto& [first, size] : blocks)
		for (Index j = 0; j < size; ++j) out.push_back(first + j);
	return out;
}

/// Adds one Gaussian term with residual r = z - h(x), Jacobian J = dh/dx
/// restricted to the scalar indices `idx`, and information W to the normal
/// equations H delta = g: H += J^T W J, g += J^T W r (eq. 5.6, 5.9 in
/// Gauss-Newton form).
void addTerm(const std::vector<Index>& idx, const Eigen::MatrixXd& J, const Eigen::MatrixXd& W, const Eigen::VectorXd& r,
			 Eigen::MatrixXd& H, Eigen::VectorXd& g)
{
	const Eigen::MatrixXd JtW = J.transpose() * W;
	const Eigen::MatrixXd h = JtW * J;
	const Eigen::VectorXd v = JtW * r;
	const Index n = static_cast<Index>(idx.size());
	for (Index i = 0; i < n; ++i)
	{
		g(idx[i]) += v(i);
		for (Index j = 0; j < n; ++j) H(idx[i], idx[j]) += h(i, j);
	}
}

struct Normal
{
	Eigen::MatrixXd H;
	Eigen::VectorXd g;
};

/// The normal equations of the merge, linearised at x.
Normal normalEquations(const LocalMap& a, const LocalMap& b, const Layout& L, const Eigen::VectorXd& x,
					   const Eigen::MatrixXd& info_a, const Eigen::MatrixXd& info_b,
					   const Eigen::Matrix3d& link_info)
{
	Normal ne{Eigen::MatrixXd::Zero(L.dim, L.dim), Eigen::VectorXd::Zero(L.dim)};

	// Map a: a prior on [e_a; features of a] (it is the global map of SLSJF's
	// k = 1 step, "set as the global map"); linear, so its Jacobian is the
	// identity and only the residual changes between iterations.
	{
		std::vector<std::pair<Index, Index>> blocks{{L.end_a, 3}};
		for (const Index c : L.col_of_a) blocks.emplace_back(c, 2);
		const auto idx = scalarIndices(blocks);
		Eigen::VectorXd r = a.state();
		for (std::size_t i = 0; i < idx.size(); ++i) r(static_cast<Index>(i)) -= x(idx[i]);
		r(2) = wrapAngle(r(2));
		addTerm(idx, Eigen::MatrixXd::Identity(r.size(), r.size()), info_a, r, ne.H, ne.g);
	}

	const Pose2 e_a = x.segment<3>(L.end_a);
	Pose2 start = e_a;
	// Eq. (5.4)-(5.6): the link. Its covariance Q is the odometry
	// increment's, over (dx, dy, dphi) in the frame of e_a (StepInput's
	// OdometryIncrement, the covariance LandmarkEkf predicts with), so u is
	// taken as a measurement of s from e_a: u = e_a^-1 (+) s + v, v ~ N(0, Q).
	// To first order this is eq. 5.4, s = e_a (+) u + w, with w's covariance
	// d(e_a (+) u)/du Q d(e_a (+) u)/du^T: Q rotated into a's frame.
	if (b.link)
	{
		start = x.segment<3>(L.start_b);
		const PoseInFrame h = poseInFrame(e_a, start);
		Eigen::VectorXd r = b.link->delta - h.value;
		r(2) = wrapAngle(r(2));
		Eigen::MatrixXd J(3, 6);
		J.leftCols<3>() = h.d_frame;
		J.rightCols<3>() = h.d_pose;
		addTerm(scalarIndices({{L.end_a, 3}, {L.start_b, 3}}), J, link_info, r, ne.H, ne.g);
	}

	// Eq. (5.8)-(5.9): map b as one virtual observation, made from its start
	// pose, of [e_b; features of b]; relinearised at x on every iteration.
	{
		std::vector<Eigen::Vector2d> features;
		for (const Index c : L.col_of_b) features.push_back(x.segment<2>(c));
		const LocalMapPrediction p = predictLocalMap(start, x.segment<3>(Layout::kEndB), features);
		Eigen::VectorXd r = b.state() - p.h;
		r(2) = wrapAngle(r(2));	 // the heading row of the innovation
		Eigen::MatrixXd J(p.h.size(), 3 + p.d_state.cols());
		J.leftCols<3>() = p.d_start;
		J.rightCols(p.d_state.cols()) = p.d_state;
		std::vector<std::pair<Index, Index>> blocks{{b.link ? L.start_b : L.end_a, 3}, {Layout::kEndB, 3}};
		for (const Index c : L.col_of_b) blocks.emplace_back(c, 2);
		addTerm(scalarIndices(blocks), J, info_b, r, ne.H, ne.g);
	}
	return ne;
}

/// Checks sizes and finiteness of a map the merge reads, and that its
/// feature IDs are distinct (IDs are what the merge joins by).
void checkInput(const LocalMap& m, const char* name)
{
	const std::string where = "mergeConsecutiveLocalMaps: map " + std::string(name) + " (index " +
		std::to_string(m.index) + "): ";
	const Index n = static_cast<Index>(m.stateDim());
	if (m.information.rows() != n || m.information.cols() != n)
		throw std::invalid_argument(where + "information is " + std::to_string(m.information.rows()) + "x" +
									std::to_string(m.information.cols()) + ", expected " + std::to_string(n) + "x" +
									std::to_string(n));
	std::map<LandmarkId, int> seen;
	for (const auto& f : m.features)
		if (++seen[f.id] > 1) throw std::invalid_argument(where + "feature " + std::to_string(f.id) + " appears twice");
	if (!m.state().allFinite() || !m.information.allFinite())
		throw NumericalError(where + "non-finite state or information");
	if (m.link && (!m.link->delta.allFinite() || !m.link->cov.allFinite()))
		throw NumericalError(where + "non-finite link");
}

void wrapHeadings(const Layout& L, Eigen::VectorXd& x)
{
	x(Layout::kEndB + 2) = wrapAngle(x(Layout::kEndB + 2));
	x(L.end_a + 2) = wrapAngle(x(L.end_a + 2));
	if (L.start_b >= 0) x(L.start_b + 2) = wrapAngle(x(L.start_b + 2));
}

}  // namespace

LocalMap mergeConsecutiveLocalMaps(const LocalMap& a, const LocalMap& b)
{
	if (b.index != a.index + 1)
		throw std::invalid_argument("mergeConsecutiveLocalMaps: maps " + std::to_string(a.index) + " and " +
									std::to_string(b.index) + " are not consecutive (the second must be map " +
									std::to_string(a.index + 1) + ")");
	checkInput(a, "a");
	checkInput(b, "b");
	const std::string maps = "local maps " + std::to_string(a.index) + " and " + std::to_string(b.index);

	// The information matrices of files are symmetric only to ~1e-4 relative
	// (SLSJF.md §13): use their symmetric part, as the filters do.
	const Eigen::MatrixXd info_a = 0.5 * (a.information + a.information.transpose());
	const Eigen::MatrixXd info_b = 0.5 * (b.information + b.information.transpose());
	Eigen::Matrix3d link_info = Eigen::Matrix3d::Zero();
	if (b.link)
	{
		// Q^-1 of the 3x3 link covariance (eq. 5.6); Q must be positive
		// definite: a zero Q means start = previous end, a map without a link.
		const Eigen::Matrix3d Q = 0.5 * (b.link->cov + b.link->cov.transpose());
		const Eigen::LLT<Eigen::Matrix3d> llt(Q);
		if (llt.info() != Eigen::Success)
			throw NumericalError("mergeConsecutiveLocalMaps: " + maps + ": the link covariance is not positive definite");
		link_info = llt.solve(Eigen::Matrix3d::Identity());
		link_info = 0.5 * (link_info + link_info.transpose());
	}

	const Layout L = makeLayout(a, b);

	// Linearisation point: a's own estimates for e_a and a's features; the
	// start pose of b through its link (eq. 5.4), and e_b and the features
	// only in b placed through that start pose (eq. 5.7), so that the
	// innovations of b's new rows and of the link start at zero.
	Eigen::VectorXd x = Eigen::VectorXd::Zero(L.dim);
	x.segment<3>(L.end_a) = a.end_pose;
	for (std::size_t i = 0; i < a.features.size(); ++i) x.segment<2>(L.col_of_a[i]) = a.features[i].position;
	Pose2 start = a.end_pose;
	if (b.link)
	{
		start = compose(a.end_pose, b.link->delta);
		x.segment<3>(L.start_b) = start;
	}
	x.segment<3>(Layout::kEndB) = compose(start, b.end_pose);
	for (const std::size_t i : L.b_only) x.segment<2>(L.col_of_b[i]) = pointFromFrame(start, b.features[i].position).value;
	wrapHeadings(L, x);

	// Gauss-Newton: the map-b observation and the link are nonlinear in the
	// start pose, so the optimum needs relinearisation (iterated SLSJF on
	// two maps). The problem is small and dense: a few hundred scalars. With
	// noisy maps the residuals at the optimum are not zero, so convergence is
	// linear (grid196 30-step pairs: updates shrink ~30x per iteration, 5-7
	// iterations); noise-free maps stop after the first.
	for (int iteration = 0; iteration < kMergeMaxIterations; ++iteration)
	{
		const Normal ne = normalEquations(a, b, L, x, info_a, info_b, link_info);
		const Eigen::LLT<Eigen::MatrixXd> llt(ne.H);
		if (llt.info() != Eigen::Success)
			throw NumericalError("mergeConsecutiveLocalMaps: " + maps +
								 ": the normal matrix is not positive definite (a map's information is not SPD)");
		const Eigen::VectorXd delta = llt.solve(ne.g);
		if (!delta.allFinite()) throw NumericalError("mergeConsecutiveLocalMaps: " + maps + ": non-finite update");
		x += delta;
		wrapHeadings(L, x);
		if (delta.cwiseAbs().maxCoeff() < kMergeTolerance) break;
	}

	// The information of all variables at the estimate, then e_a (and s)
	// marginalised out by the Schur complement
	//     I_kk - I_km I_mm^-1 I_mk,
	// the information form of dropping variables (no inverse of the large
	// matrix: only of the 3x3 or 6x6 block of the marginalised poses).
	const Normal ne = normalEquations(a, b, L, x, info_a, info_b, link_info);
	const Index k = L.kept, m = L.dim - L.kept;
	const Eigen::LLT<Eigen::MatrixXd> llt_mm(ne.H.bottomRightCorner(m, m));
	if (llt_mm.info() != Eigen::Success)
		throw NumericalError("mergeConsecutiveLocalMaps: " + maps +
							 ": the information of the shared pose is not positive definite");
	Eigen::MatrixXd info = ne.H.topLeftCorner(k, k) - ne.H.topRightCorner(k, m) * llt_mm.solve(ne.H.bottomLeftCorner(m, k));
	info = 0.5 * (info + info.transpose());
	const Eigen::LLT<Eigen::MatrixXd> llt(info);
	if (!info.allFinite() || llt.info() != Eigen::Success)
		throw NumericalError("mergeConsecutiveLocalMaps: " + maps +
							 ": the merged information matrix is not symmetric positive definite");
	Eigen::MatrixXd cov = llt.solve(Eigen::MatrixXd::Identity(k, k));
	cov = 0.5 * (cov + cov.transpose());

	LocalMap out;
	out.index = a.index;
	out.end_pose = x.segment<3>(Layout::kEndB);
	out.end_pose.z() = wrapAngle(out.end_pose.z());
	std::map<LandmarkId, bool> earlier_in_b;
	for (const auto& f : b.features) earlier_in_b[f.id] = f.in_earlier_maps;
	for (std::size_t i = 0; i < L.ids.size(); ++i)
	{
		LocalMapFeature f;
		f.id = L.ids[i];
		f.position = x.segment<2>(static_cast<Index>(3 + 2 * i));
		// A feature of a keeps a's flag: it is known to an earlier map than
		// the merged one only if a knew it; b's flag of such a feature may
		// only mean "seen in map a", which is now inside the merged map.
		f.in_earlier_maps = i < a.features.size() ? a.features[i].in_earlier_maps : earlier_in_b.at(f.id);
		out.features.push_back(f);
	}
	out.information = std::move(info);
	out.covariance = std::move(cov);
	out.ids_identify_features = a.ids_identify_features && b.ids_identify_features;
	out.link = a.link;	// the merged map starts where a started
	out.first_step = a.first_step;
	out.last_step = b.last_step;
	out.steps = a.steps + b.steps;
	out.measurements = a.measurements + b.measurements;
	out.step_reports = a.step_reports;
	out.step_reports.insert(out.step_reports.end(), b.step_reports.begin(), b.step_reports.end());
	return out;
}

}  // namespace esif
