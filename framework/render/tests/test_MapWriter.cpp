/// \file test_MapWriter.cpp
/// The map outputs of a small synthetic run are written and read back with
/// MRPT's own readers (and plain parsing for the text files).

#include <esif/core/Errors.h>
#include <esif/formats/MapWriter.h>
#include <esif/run/MapOutputs.h>

#include <mrpt/img/CImage.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/maps/CLandmarksMap.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CSetOfLines.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/serialization/CArchive.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace
{
const std::set<std::string> kOutputs = {"map.simplemap", "landmarks.gz", "landmarks.txt",
										"trajectory.tum", "scene.3Dscene", "map.png", "map.svg"};

/// A fresh, empty folder removed at the end of the test.
class TempDir
{
   public:
	TempDir()
	{
		static int counter = 0;
		path_ = fs::temp_directory_path() /
				("esif_test_MapWriter_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
		fs::remove_all(path_);
		fs::create_directories(path_);
	}
	~TempDir()
	{
		std::error_code ec;
		fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ec);
		fs::remove_all(path_, ec);
	}
	std::string str() const { return path_.string(); }
	std::string file(const std::string& name) const { return (path_ / name).string(); }
	std::set<std::string> entries() const
	{
		std::set<std::string> names;
		for (const auto& e : fs::directory_iterator(path_)) names.insert(e.path().filename().string());
		return names;
	}

   private:
	fs::path path_;
};

mrpt::obs::CSensoryFrame::Ptr frameWithBearingRange(int n_measurements)
{
	auto obs = mrpt::obs::CObservationBearingRange::Create();
	obs->maxSensorDistance = 8;
	obs->sensor_std_range = 0.1f;
	obs->sensor_std_yaw = 0.01f;
	for (int i = 0; i < n_measurements; ++i)
	{
		mrpt::obs::CObservationBearingRange::TMeasurement m;
		m.range = 1.0f + i;
		m.yaw = 0.1f * i;
		m.pitch = 0;
		m.landmarkID = 10 + i;
		obs->sensedData.push_back(m);
	}
	auto sf = mrpt::obs::CSensoryFrame::Create();
	sf->insert(obs);
	return sf;
}

Eigen::Matrix3d poseCov(double s)
{
	Eigen::Matrix3d c;
	c << 0.04 * s, 0.01 * s, 0.002 * s,  //
		0.01 * s, 0.09 * s, -0.003 * s,	 //
		0.002 * s, -0.003 * s, 0.0025 * s;
	return c;
}

/// Four landmarks with known covariances, a 60-step arc, three keyframes (the
/// last without a frame) and ground truth.
esif::RunRecord makeRun(std::size_t steps = 60)
{
	esif::RunRecord run;
	run.plugin = "TestPlugin";
	run.rawlog = "/some/where/synthetic.rawlog";
	for (std::size_t k = 0; k < steps; ++k)
	{
		esif::TrajectoryPoint p;
		p.step = k;
		p.time_s = 1.5 + 0.1 * static_cast<double>(k);
		const double a = 0.05 * static_cast<double>(k);
		p.pose.mean = esif::Pose2(6 * std::sin(a), 6 * (1 - std::cos(a)), a);
		p.pose.cov = poseCov(1 + 0.01 * static_cast<double>(k));
		run.trajectory.push_back(p);
	}
	const std::vector<std::pair<esif::LandmarkId, Eigen::Vector2d>> lms = {
		{3, {2.0, 1.0}}, {7, {-1.5, 4.25}}, {12, {7.125, 3.5}}, {40, {0.333333333333, -2.0}}};
	for (std::size_t i = 0; i < lms.size(); ++i)
	{
		esif::LandmarkEstimate l;
		l.id = lms[i].first;
		l.mean = lms[i].second;
		const double s = 1.0 + static_cast<double>(i);
		l.cov << 0.01 * s, 0.004 * s, 0.004 * s, 0.0225 * s;
		run.final_estimate.landmarks.push_back(l);
	}
	run.final_estimate.robot = run.trajectory.back().pose;

	run.keyframes.push_back({run.trajectory[0].pose, frameWithBearingRange(2)});
	run.keyframes.push_back({run.trajectory[steps / 2].pose, frameWithBearingRange(3)});
	run.keyframes.push_back({run.trajectory[steps - 1].pose, nullptr});

	esif::GroundTruth truth;
	for (const auto& [id, p] : lms) truth.landmarks[id] = p + Eigen::Vector2d(0.05, -0.04);
	for (const auto& t : run.trajectory)
		truth.path.push_back(esif::Pose2(t.pose.mean.x() + 0.02, t.pose.mean.y() - 0.03, t.pose.mean(2)));
	run.truth = truth;
	return run;
}

std::vector<std::vector<double>> readNumberRows(const std::string& path)
{
	std::ifstream in(path);
	std::vector<std::vector<double>> rows;
	std::string line;
	while (std::getline(in, line))
	{
		if (line.empty() || line[0] == '#') continue;
		std::istringstream ss(line);
		std::vector<double> row;
		double v;
		while (ss >> v) row.push_back(v);
		EXPECT_TRUE(ss.eof()) << "unparsable line: " << line;
		rows.push_back(row);
	}
	return rows;
}

void expectNearRel(double expected, double actual, double rel, const std::string& what)
{
	EXPECT_NEAR(expected, actual, rel * std::max(1.0, std::abs(expected))) << what;
}
}  // namespace

TEST(MapWriter, WritesExactlyTheSixOutputsAndNoTemporaries)
{
	TempDir dir;
	esif::writeMapOutputs(makeRun(), dir.str());
	EXPECT_EQ(dir.entries(), kOutputs);
	for (const auto& name : kOutputs) EXPECT_GT(fs::file_size(dir.file(name)), 0u) << name;
}

TEST(MapWriter, SimpleMapReloadsWithKeyframePosesAndFrames)
{
	TempDir dir;
	const esif::RunRecord run = makeRun();
	esif::writeMapOutputs(run, dir.str());

	mrpt::maps::CSimpleMap sm;
	ASSERT_TRUE(sm.loadFromFile(dir.file("map.simplemap")));
	ASSERT_EQ(sm.size(), run.keyframes.size());
	for (std::size_t i = 0; i < sm.size(); ++i)
	{
		const auto [pdf3d, sf] = sm.get(i);
		ASSERT_TRUE(pdf3d);
		ASSERT_TRUE(sf);
		const mrpt::poses::CPosePDFGaussian pdf(*pdf3d);
		const esif::PoseEstimate& want = run.keyframes[i].pose;
		EXPECT_NEAR(pdf.mean.x(), want.mean.x(), 1e-12);
		EXPECT_NEAR(pdf.mean.y(), want.mean.y(), 1e-12);
		EXPECT_NEAR(pdf.mean.phi(), want.mean(2), 1e-12);
		for (int r = 0; r < 3; ++r)
			for (int c = 0; c < 3; ++c) EXPECT_NEAR(pdf.cov(r, c), want.cov(r, c), 1e-12) << r << "," << c;

		const std::size_t want_obs = run.keyframes[i].frame ? run.keyframes[i].frame->size() : 0;
		ASSERT_EQ(sf->size(), want_obs);
		if (want_obs > 0)
		{
			const auto obs = sf->getObservationByClass<mrpt::obs::CObservationBearingRange>();
			ASSERT_TRUE(obs);
			const auto src = run.keyframes[i].frame->getObservationByClass<mrpt::obs::CObservationBearingRange>();
			ASSERT_EQ(obs->sensedData.size(), src->sensedData.size());
			EXPECT_EQ(obs->sensedData.back().landmarkID, src->sensedData.back().landmarkID);
			EXPECT_FLOAT_EQ(obs->sensedData.back().range, src->sensedData.back().range);
		}
	}
}

TEST(MapWriter, LandmarksGzReloadsAsCLandmarksMap)
{
	TempDir dir;
	const esif::RunRecord run = makeRun();
	esif::writeMapOutputs(run, dir.str());

	mrpt::io::CFileGZInputStream in(dir.file("landmarks.gz"));
	const auto map = mrpt::serialization::archiveFrom(in).ReadObject<mrpt::maps::CLandmarksMap>();
	ASSERT_TRUE(map);
	ASSERT_EQ(map->landmarks.size(), run.final_estimate.landmarks.size());
	for (const esif::LandmarkEstimate& want : run.final_estimate.landmarks)
	{
		const mrpt::maps::CLandmark* got = map->landmarks.getByID(want.id);
		ASSERT_NE(got, nullptr) << "landmark " << want.id;
		EXPECT_EQ(got->getType(), mrpt::vision::featBeacon);
		EXPECT_DOUBLE_EQ(got->pose_mean.x, want.mean.x());
		EXPECT_DOUBLE_EQ(got->pose_mean.y, want.mean.y());
		EXPECT_DOUBLE_EQ(got->pose_mean.z, 0.0);
		// The covariance is stored as float.
		expectNearRel(want.cov(0, 0), got->pose_cov_11, 1e-6, "cov_11");
		expectNearRel(want.cov(1, 1), got->pose_cov_22, 1e-6, "cov_22");
		expectNearRel(want.cov(0, 1), got->pose_cov_12, 1e-6, "cov_12");
		EXPECT_GT(got->pose_cov_33, 0.0f);
		EXPECT_EQ(got->pose_cov_13, 0.0f);
		EXPECT_EQ(got->pose_cov_23, 0.0f);
	}
}

TEST(MapWriter, LandmarksTxtParsesBackExactly)
{
	TempDir dir;
	const esif::RunRecord run = makeRun();
	esif::writeMapOutputs(run, dir.str());

	std::ifstream in(dir.file("landmarks.txt"));
	std::string first;
	std::getline(in, first);
	EXPECT_EQ(first.rfind("#", 0), 0u) << "header comment expected, got: " << first;

	const auto rows = readNumberRows(dir.file("landmarks.txt"));
	ASSERT_EQ(rows.size(), run.final_estimate.landmarks.size());
	for (std::size_t i = 0; i < rows.size(); ++i)
	{
		const esif::LandmarkEstimate& want = run.final_estimate.landmarks[i];
		ASSERT_EQ(rows[i].size(), 6u);
		EXPECT_EQ(rows[i][0], static_cast<double>(want.id));
		// Round-trip precision: exact equality.
		EXPECT_EQ(rows[i][1], want.mean.x());
		EXPECT_EQ(rows[i][2], want.mean.y());
		EXPECT_EQ(rows[i][3], want.cov(0, 0));
		EXPECT_EQ(rows[i][4], want.cov(0, 1));
		EXPECT_EQ(rows[i][5], want.cov(1, 1));
	}
}

TEST(MapWriter, TrajectoryTumHasOneLinePerPointAndYawQuaternions)
{
	TempDir dir;
	esif::RunRecord run = makeRun();
	// Known yaws, including one outside (-pi, pi] that must be wrapped.
	run.trajectory[0].pose.mean(2) = M_PI / 2;
	run.trajectory[1].pose.mean(2) = -2.0;
	run.trajectory[2].pose.mean(2) = 2 * M_PI + 0.5;
	esif::writeMapOutputs(run, dir.str());

	const auto rows = readNumberRows(dir.file("trajectory.tum"));
	ASSERT_EQ(rows.size(), run.trajectory.size());
	for (std::size_t i = 0; i < rows.size(); ++i)
	{
		ASSERT_EQ(rows[i].size(), 8u);
		const auto& p = run.trajectory[i];
		EXPECT_EQ(rows[i][0], p.time_s);
		EXPECT_EQ(rows[i][1], p.pose.mean.x());
		EXPECT_EQ(rows[i][2], p.pose.mean.y());
		EXPECT_EQ(rows[i][3], 0.0);
		EXPECT_EQ(rows[i][4], 0.0);
		EXPECT_EQ(rows[i][5], 0.0);
		EXPECT_NEAR(rows[i][6] * rows[i][6] + rows[i][7] * rows[i][7], 1.0, 1e-12);
		EXPECT_GE(rows[i][7], 0.0);
	}
	EXPECT_NEAR(rows[0][6], std::sqrt(0.5), 1e-12);
	EXPECT_NEAR(rows[0][7], std::sqrt(0.5), 1e-12);
	EXPECT_NEAR(rows[1][6], std::sin(-1.0), 1e-12);
	EXPECT_NEAR(rows[1][7], std::cos(-1.0), 1e-12);
	EXPECT_NEAR(rows[2][6], std::sin(0.25), 1e-12);
	EXPECT_NEAR(rows[2][7], std::cos(0.25), 1e-12);
}

TEST(MapWriter, SceneReloadsWithNamedObjects)
{
	TempDir dir;
	esif::writeMapOutputs(makeRun(), dir.str());

	mrpt::opengl::COpenGLScene scene;
	ASSERT_TRUE(scene.loadFromFile(dir.file("scene.3Dscene")));
	ASSERT_TRUE(scene.getViewport("main"));
	EXPECT_GE(scene.getViewport("main")->size(), 6u);
	for (const char* name : {"grid", "trajectory", "landmarks", "landmark_ellipses", "robot", "truth_path",
							 "truth_landmarks"})
		EXPECT_TRUE(scene.getByName(name)) << name;
	const auto traj = std::dynamic_pointer_cast<mrpt::opengl::CSetOfLines>(scene.getByName("trajectory"));
	ASSERT_TRUE(traj);
	EXPECT_GT(traj->size(), 10u);
}

TEST(MapWriter, SceneWithoutTruthHasNoTruthObjects)
{
	TempDir dir;
	esif::RunRecord run = makeRun();
	run.truth.reset();
	esif::writeMapOutputs(run, dir.str());

	mrpt::opengl::COpenGLScene scene;
	ASSERT_TRUE(scene.loadFromFile(dir.file("scene.3Dscene")));
	EXPECT_TRUE(scene.getByName("landmarks"));
	EXPECT_FALSE(scene.getByName("truth_path"));
	EXPECT_FALSE(scene.getByName("truth_landmarks"));
}

TEST(MapWriter, MapPngLoadsWithRequestedSizeAndShowsContent)
{
	TempDir dir;
	esif::MapWriterOptions options;
	options.image_size_px = 640;
	esif::writeMapOutputs(makeRun(), dir.str(), options);

	mrpt::img::CImage img;
	ASSERT_TRUE(img.loadFromFile(dir.file("map.png")));
	EXPECT_EQ(img.getWidth(), 640u);
	EXPECT_EQ(img.getHeight(), 640u);
	ASSERT_TRUE(img.isColor());

	// White background with some red (landmarks), blue (path) and green
	// (ground truth) pixels.
	std::size_t white = 0, red = 0, blue = 0, green = 0;
	for (int y = 0; y < 640; ++y)
		for (int x = 0; x < 640; ++x)
		{
			const auto* px = img.ptr<uint8_t>(x, y);  // OpenCV order: B, G, R
			const int b = px[0], g = px[1], r = px[2];
			if (r == 255 && g == 255 && b == 255) ++white;
			if (r > 180 && g < 60 && b < 60) ++red;
			if (b > 180 && r < 80 && g < 120) ++blue;
			if (g > 120 && r < 60 && b < 60) ++green;
		}
	EXPECT_GT(white, 640u * 640u / 2);
	EXPECT_GT(red, 20u);
	EXPECT_GT(blue, 100u);
	EXPECT_GT(green, 20u);
}

TEST(MapWriter, EmptyRunStillWritesAllOutputs)
{
	TempDir dir;
	esif::RunRecord run;
	esif::writeMapOutputs(run, dir.str());
	EXPECT_EQ(dir.entries(), kOutputs);

	mrpt::maps::CSimpleMap sm;
	ASSERT_TRUE(sm.loadFromFile(dir.file("map.simplemap")));
	EXPECT_EQ(sm.size(), 0u);
	EXPECT_TRUE(readNumberRows(dir.file("landmarks.txt")).empty());
	EXPECT_TRUE(readNumberRows(dir.file("trajectory.tum")).empty());
	mrpt::opengl::COpenGLScene scene;
	EXPECT_TRUE(scene.loadFromFile(dir.file("scene.3Dscene")));
	mrpt::img::CImage img;
	EXPECT_TRUE(img.loadFromFile(dir.file("map.png")));
}

TEST(MapWriter, LongTrajectoryIsDecimatedInTheScene)
{
	TempDir dir;
	const esif::RunRecord run = makeRun(18000);
	esif::writeMapOutputs(run, dir.str());

	EXPECT_EQ(readNumberRows(dir.file("trajectory.tum")).size(), 18000u);
	mrpt::opengl::COpenGLScene scene;
	ASSERT_TRUE(scene.loadFromFile(dir.file("scene.3Dscene")));
	const auto traj = std::dynamic_pointer_cast<mrpt::opengl::CSetOfLines>(scene.getByName("trajectory"));
	ASSERT_TRUE(traj);
	EXPECT_GT(traj->size(), 100u);
	EXPECT_LT(traj->size(), 5000u);
}

TEST(MapWriter, BinaryOutputsAreGzipAndPngWhateverTheTemporaryName)
{
	// The writers save under a ".tmp" name first; the formats must not depend
	// on that name's extension.
	TempDir dir;
	esif::writeMapOutputs(makeRun(), dir.str());
	const auto magic = [&](const std::string& name) {
		std::ifstream in(dir.file(name), std::ios::binary);
		std::string m(4, '\0');
		in.read(m.data(), 4);
		return m;
	};
	for (const char* gz : {"map.simplemap", "landmarks.gz", "scene.3Dscene"})
		EXPECT_EQ(magic(gz).substr(0, 2), std::string("\x1f\x8b")) << gz;
	EXPECT_EQ(magic("map.png"), std::string("\x89PNG"));
}

/// Runs `write` in a forked child whose files may not exceed `limit_bytes`
/// (RLIMIT_FSIZE, SIGXFSZ ignored: writes beyond fail with EFBIG, as on a
/// full disk). Exit 0: it threw an InputError naming `path` and the
/// system's reason and left no file; 1: it reported success; 2: another message.
int writeUnderFileSizeLimit(const std::function<void()>& write, const std::string& path, rlim_t limit_bytes)
{
	const pid_t pid = ::fork();
	if (pid == 0)
	{
		::signal(SIGXFSZ, SIG_IGN);
		const rlimit limit{limit_bytes, limit_bytes};
		::setrlimit(RLIMIT_FSIZE, &limit);
		try
		{
			write();
		}
		catch (const esif::InputError& e)
		{
			const std::string what = e.what();
			const bool named = what.rfind(path + ": ", 0) == 0 && what.find(std::strerror(EFBIG)) != std::string::npos;
			::_exit(named && !fs::exists(path) ? 0 : 2);
		}
		::_exit(1);
	}
	int status = 0;
	::waitpid(pid, &status, 0);
	return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(MapWriter, FullDiskIsAnErrorNamingTheFileForEveryOutput)
{
	// MRPT's gz streams and imwrite report success when the disk is full, and
	// a truncated map was renamed into place. 64 bytes is below every output
	// of makeRun() (landmarks.txt's header line alone is longer; a gzip of a
	// serialized MRPT object has a 10-byte header and the class name), so
	// each write must fail, and say so.
	TempDir dir;
	const esif::RunRecord run = makeRun();
	const std::vector<std::pair<std::string, std::function<void(const std::string&)>>> writers = {
		{"map.simplemap", [&](const std::string& p) { esif::writeSimpleMap(run, p); }},
		{"scene.3Dscene", [&](const std::string& p) { esif::writeScene(run, p, {}); }},
		{"landmarks.gz", [&](const std::string& p) { esif::writeLandmarksGz(run.final_estimate, p); }},
		{"landmarks.txt", [&](const std::string& p) { esif::writeLandmarksTxt(run.final_estimate, p); }},
		{"map.png", [&](const std::string& p) { esif::writeMapImage(run, p, {}); }},
	};
	for (const auto& [name, write] : writers)
	{
		const std::string path = dir.file(name);
		EXPECT_EQ(writeUnderFileSizeLimit([&] { write(path); }, path, 64), 0) << name;
	}
	EXPECT_TRUE(dir.entries().empty()) << "no temporary file left";
}

TEST(MapWriter, NonFiniteLandmarkIsKeptInTextAndLeftOutOfMrptMap)
{
	TempDir dir;
	esif::RunRecord run = makeRun();
	run.final_estimate.landmarks[1].mean.x() = std::numeric_limits<double>::quiet_NaN();
	run.final_estimate.landmarks[2].cov(1, 1) = std::numeric_limits<double>::infinity();
	esif::writeMapOutputs(run, dir.str());
	EXPECT_EQ(dir.entries(), kOutputs);

	mrpt::io::CFileGZInputStream in(dir.file("landmarks.gz"));
	const auto map = mrpt::serialization::archiveFrom(in).ReadObject<mrpt::maps::CLandmarksMap>();
	EXPECT_EQ(map->landmarks.size(), run.final_estimate.landmarks.size() - 1);
	EXPECT_EQ(map->landmarks.getByID(run.final_estimate.landmarks[1].id), nullptr);

	std::ifstream txt(dir.file("landmarks.txt"));
	const std::string all((std::istreambuf_iterator<char>(txt)), std::istreambuf_iterator<char>());
	EXPECT_NE(all.find("\n7 nan 4.25 "), std::string::npos) << all;

	mrpt::img::CImage img;
	EXPECT_TRUE(img.loadFromFile(dir.file("map.png")));
	mrpt::opengl::COpenGLScene scene;
	EXPECT_TRUE(scene.loadFromFile(dir.file("scene.3Dscene")));
}

TEST(MapWriter, MapTooWideForCLandmarksMapHasNoLandmarksGzAndAWarning)
{
	// CLandmarksMap indexes landmarks on a dense 0.2 m grid: a city-sized map
	// (or one landmark diverged 100 km away) would exhaust a reader's memory.
	// The file is left out with one warning line; the other outputs stand.
	TempDir dir;
	esif::RunRecord run = makeRun();
	run.final_estimate.landmarks[0].mean = Eigen::Vector2d(1e5, 0);
	ASSERT_TRUE(esif::landmarksGzRefusal(run.final_estimate));
	testing::internal::CaptureStderr();
	EXPECT_NO_THROW(esif::writeMapOutputs(run, dir.str()));
	const std::string warning = testing::internal::GetCapturedStderr();
	EXPECT_EQ(warning.rfind("esif: warning: landmarks.gz not written: landmarks span 100010 x 20 m", 0), 0u) << warning;
	EXPECT_EQ(std::count(warning.begin(), warning.end(), '\n'), 1) << warning;
	std::set<std::string> others = kOutputs;
	others.erase("landmarks.gz");
	EXPECT_EQ(dir.entries(), others);
	// The writer itself still refuses it, naming the file.
	EXPECT_THROW(esif::writeLandmarksGz(run.final_estimate, dir.file("landmarks.gz")), esif::InputError);
	EXPECT_FALSE(esif::landmarksGzRefusal(makeRun().final_estimate));
}

TEST(MapWriter, MissingFolderThrowsInputErrorAndCreatesNothing)
{
	TempDir dir;
	const std::string missing = dir.file("no/such/folder");
	EXPECT_THROW(esif::writeMapOutputs(makeRun(), missing), esif::InputError);
	EXPECT_FALSE(fs::exists(dir.file("no")));
	EXPECT_TRUE(dir.entries().empty());
}

TEST(MapWriter, FolderThatIsAFileThrowsInputError)
{
	TempDir dir;
	std::ofstream(dir.file("plain")) << "x";
	EXPECT_THROW(esif::writeMapOutputs(makeRun(), dir.file("plain")), esif::InputError);
	EXPECT_EQ(dir.entries(), std::set<std::string>{"plain"});
}

TEST(MapWriter, EachWriterThrowsInputErrorWhenItCannotWrite)
{
	// The folder of each path does not exist, so even the temporary file
	// cannot be created: every writer must report it as InputError naming the
	// file, and leave nothing behind.
	TempDir dir;
	const esif::RunRecord run = makeRun();
	const esif::MapWriterOptions options;
	const std::string base = dir.file("missing") + "/";
	const auto expectInputError = [&](const std::function<void(const std::string&)>& write, const std::string& name) {
		try
		{
			write(base + name);
			ADD_FAILURE() << name << ": no exception";
		}
		catch (const esif::InputError& e)
		{
			EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
		}
		catch (const std::exception& e)
		{
			ADD_FAILURE() << name << ": wrong exception type: " << e.what();
		}
	};
	expectInputError([&](const std::string& p) { esif::writeSimpleMap(run, p); }, "map.simplemap");
	expectInputError([&](const std::string& p) { esif::writeLandmarksGz(run.final_estimate, p); }, "landmarks.gz");
	expectInputError([&](const std::string& p) { esif::writeLandmarksTxt(run.final_estimate, p); }, "landmarks.txt");
	expectInputError([&](const std::string& p) { esif::writeTrajectoryTum(run.trajectory, p); }, "trajectory.tum");
	expectInputError([&](const std::string& p) { esif::writeScene(run, p, options); }, "scene.3Dscene");
	expectInputError([&](const std::string& p) { esif::writeMapImage(run, p, options); }, "map.png");
	EXPECT_TRUE(dir.entries().empty());
}

TEST(MapWriter, UnwritableFolderThrowsInputErrorAndLeavesNothing)
{
	if (::geteuid() == 0) GTEST_SKIP() << "permissions do not stop root";
	TempDir dir;
	fs::permissions(dir.str(), fs::perms::owner_read | fs::perms::owner_exec);
	EXPECT_THROW(esif::writeMapOutputs(makeRun(), dir.str()), esif::InputError);
	fs::permissions(dir.str(), fs::perms::owner_all);
	EXPECT_TRUE(dir.entries().empty());
}

TEST(MapWriter, InvalidOptionsThrowConfigErrorBeforeWriting)
{
	TempDir dir;
	esif::MapWriterOptions bad_size;
	bad_size.image_size_px = 10;
	EXPECT_THROW(esif::writeMapOutputs(makeRun(), dir.str(), bad_size), esif::ConfigError);
	esif::MapWriterOptions bad_sigmas;
	bad_sigmas.ellipse_sigmas = 0;
	EXPECT_THROW(esif::writeMapOutputs(makeRun(), dir.str(), bad_sigmas), esif::ConfigError);
	EXPECT_TRUE(dir.entries().empty());
}
