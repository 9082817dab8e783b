/// \file G2oReader.cpp
/// A g2o file read back strictly, like the run outputs (RunOutputReader.cpp):
/// every token read whole as a number (NumberToken.h), every edge checked against
/// the vertices, every information matrix positive definite, so a damaged
/// file or a solver's output of another problem is reported at its line.

#include <esif/core/Errors.h>
#include <esif/core/InputBounds.h>
#include <esif/core/NumberToken.h>
#include <esif/core/TextInput.h>
#include <esif/formats/G2oFormat.h>

#include <Eigen/Cholesky>

#include <cmath>
#include <vector>

namespace esif
{
namespace
{
struct Line
{
	const std::string& path;
	std::size_t lineno;
	std::vector<std::string> tokens;

	[[noreturn]] void fail(const std::string& problem) const
	{
		throw InputError(path + ":" + std::to_string(lineno) + ": " + problem);
	}

	/// Checks that the line holds its tag and `count` values, described by `layout`.
	void expect(std::size_t count, const std::string& layout) const
	{
		if (tokens.size() != count + 1)
			fail(tokens[0] + " needs " + std::to_string(count) + " values '" + layout + "', found " +
				 std::to_string(tokens.size() - 1));
	}

	long long id(std::size_t k) const
	{
		const auto v = integerToken<long long>(tokens[k]);
		if (!v || *v < 0) fail("vertex ID '" + tokens[k] + "' is not a non-negative integer");
		return *v;
	}

	double number(std::size_t k) const
	{
		const auto v = doubleToken(tokens[k], NonFinite::accepted);
		if (!v) fail("'" + tokens[k] + "' is not a number");
		if (!std::isfinite(*v)) fail("'" + tokens[k] + "' is not finite");
		return *v;
	}

	/// A coordinate [m] within +-kMaxCoordinate_m.
	double coordinate(std::size_t k) const
	{
		const double v = number(k);
		if (std::abs(v) > kMaxCoordinate_m) fail("'" + tokens[k] + "' is beyond +-1e7 m (a corrupt file?)");
		return v;
	}

	/// A heading [rad] within +-kMaxHeading_rad.
	double heading(std::size_t k) const
	{
		const double v = number(k);
		if (std::abs(v) > kMaxHeading_rad) fail("'" + tokens[k] + "' is beyond +-1e6 rad (a corrupt file?)");
		return v;
	}

	/// The symmetric N x N information matrix from its upper triangle at
	/// tokens[first..]; fails unless it is positive definite.
	template <int N>
	void checkInformation(std::size_t first) const
	{
		Eigen::Matrix<double, N, N> m;
		std::size_t k = first;
		for (int r = 0; r < N; ++r)
			for (int c = r; c < N; ++c) m(r, c) = m(c, r) = number(k++);
		if (Eigen::LLT<Eigen::Matrix<double, N, N>>(m).info() != Eigen::Success)
			fail(tokens[0] + ": information matrix is not positive definite");
	}
};

/// An edge's vertex references, checked once every vertex is known (g2o
/// files may define vertices after the edges that use them).
struct EdgeRef
{
	std::size_t line;
	std::string tag;
	long long pose;
	long long other;
	bool other_is_pose;
};

class Reader
{
   public:
	explicit Reader(const std::string& path) : path_(path) {}

	void readLine(const Line& l)
	{
		const std::string& tag = l.tokens[0];
		if (tag == "VERTEX_SE2") return addPose(l);
		if (tag == "VERTEX_XY") return addPoint(l);
		if (tag == "FIX")
		{
			for (std::size_t k = 1; k < l.tokens.size(); ++k) l.id(k);
			return;
		}
		if (tag == "EDGE_SE2")
		{
			l.expect(11, "id1 id2 dx dy dtheta I11 I12 I13 I22 I23 I33");
			for (std::size_t k = 3; k < 6; ++k) l.number(k);
			l.checkInformation<3>(6);
			edges_.push_back({l.lineno, tag, l.id(1), l.id(2), true});
			++graph_.odometry_edges;
			return;
		}
		if (tag == "EDGE_SE2_XY")
		{
			l.expect(7, "pose_id point_id px py I11 I12 I22");
			for (std::size_t k = 3; k < 5; ++k) l.number(k);
			l.checkInformation<2>(5);
			edges_.push_back({l.lineno, tag, l.id(1), l.id(2), false});
			++graph_.point_edges;
			return;
		}
		if (tag == "BR")
		{
			l.expect(6, "pose_id point_id bearing range sigma_bearing sigma_range");
			for (std::size_t k = 3; k < 7; ++k) l.number(k);
			if (!(l.number(5) > 0 && l.number(6) > 0)) l.fail("BR: the sigmas must be positive");
			edges_.push_back({l.lineno, tag, l.id(1), l.id(2), false});
			++graph_.point_edges;
			return;
		}
		l.fail("unknown tag '" + tag + "' (esif reads VERTEX_SE2, VERTEX_XY, EDGE_SE2, EDGE_SE2_XY, BR, FIX)");
	}

	G2oGraph finish()
	{
		for (const EdgeRef& e : edges_)
		{
			const Line l{path_, e.line, {e.tag}};
			if (!graph_.poses.count(e.pose)) l.fail(e.tag + ": no VERTEX_SE2 " + std::to_string(e.pose));
			if (e.other_is_pose && !graph_.poses.count(e.other))
				l.fail(e.tag + ": no VERTEX_SE2 " + std::to_string(e.other));
			if (!e.other_is_pose && !graph_.points.count(e.other))
				l.fail(e.tag + ": no VERTEX_XY " + std::to_string(e.other));
		}
		return std::move(graph_);
	}

   private:
	void checkNew(const Line& l, long long id)
	{
		if (const auto [it, added] = vertex_line_.emplace(id, l.lineno); !added)
			l.fail("vertex " + std::to_string(id) + " is defined twice (first on line " + std::to_string(it->second) +
				   ")");
	}
	void addPose(const Line& l)
	{
		l.expect(4, "id x y theta");
		checkNew(l, l.id(1));
		graph_.poses.emplace(l.id(1), Pose2(l.coordinate(2), l.coordinate(3), l.heading(4)));
	}
	void addPoint(const Line& l)
	{
		l.expect(3, "id x y");
		checkNew(l, l.id(1));
		graph_.points.emplace(l.id(1), Eigen::Vector2d(l.coordinate(2), l.coordinate(3)));
	}

	const std::string& path_;
	G2oGraph graph_;
	std::map<long long, std::size_t> vertex_line_;
	std::vector<EdgeRef> edges_;
};
}  // namespace

G2oGraph readG2oFile(const std::string& path)
{
	TextLineReader in(path, "g2o file");
	Reader reader(path);
	for (std::string text; in.next(text);)
	{
		Line l{path, in.lineNumber(), whitespaceTokens(text)};
		if (l.tokens.empty() || l.tokens[0][0] == '#') continue;
		reader.readLine(l);
	}
	return reader.finish();
}

}  // namespace esif
