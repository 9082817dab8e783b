// The second round of hostile inputs, each answered with one error line and
// the right exit code, or a correct result: empty option values, control
// bytes in paths and labels, Markdown in labels, an ambiguous --reference,
// out of memory outside the replay loop, reference runs and dataset files
// beyond their documented bounds (a rawlog cut inside a value: test_io_hostile).

#include <ChildProcess.h>
#include <EsifTestSupport.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <sys/stat.h>

namespace fs = std::filesystem;

namespace
{
using esif::test::expectOneErrorLine;
using esif::test::quoted;
using esif::test::readText;
using esif::test::runEsif;
using esif::test::simulateSmall;
using esif::test::sourcePath;
using esif::test::TempDir;

void put(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::string config(const std::string& name) { return quoted(sourcePath("configs/" + name)); }

/// A small simulated rawlog (200 steps) and a ceres_full run of it, shared by the suite.
class HostileInputs : public ::testing::Test
{
   protected:
	static void SetUpTestSuite()
	{
		dir_ = new TempDir;
		ASSERT_EQ(simulateSmall(rawlog()).exit_code, 0);
		const auto ref = runEsif("run -q --no-figures --config " + config("ceres_full.ini") + " --rawlog " +
								 quoted(rawlog()) + " --out " + quoted(reference()));
		ASSERT_EQ(ref.exit_code, 0) << ref.out;
	}
	static void TearDownTestSuite()
	{
		delete dir_;
		dir_ = nullptr;
	}
	static std::string rawlog() { return dir_->file("s.rawlog"); }
	static std::string reference() { return dir_->file("ref"); }

	/// A copy of the reference run (no marker: a folder of the user's) with
	/// line `line` of `file` changed by `edit`.
	static std::string damagedReference(
		const std::string& name, const std::string& file, int line, const std::function<std::string(std::string)>& edit)
	{
		const std::string copy = dir_->file(name);
		fs::copy(reference(), copy, fs::copy_options::recursive);
		fs::remove(copy + "/.esif-output");
		std::istringstream in(readText(copy + "/" + file));
		std::string out;
		int number = 0;
		for (std::string l; std::getline(in, l);) out += (++number == line ? edit(l) : l) + "\n";
		put(copy + "/" + file, out);
		return copy;
	}

	static TempDir* dir_;
};
TempDir* HostileInputs::dir_ = nullptr;

/// `row` with its second field (x of trajectory.tum or landmarks.txt) set to `value`.
std::string withX(const std::string& row, const std::string& value)
{
	const auto a = row.find(' '), b = row.find(' ', a + 1);
	return row.substr(0, a + 1) + value + row.substr(b);
}

TEST_F(HostileInputs, AnEmptyOptionValueIsRefusedNotTakenForTheDefault)
{
	expectOneErrorLine(runEsif("simulate --config " + config("sim/small.ini") + " --out " +
							   quoted(dir_->file("e.rawlog")) + " --seed ''"),
					   "esif simulate: --seed: the value is empty");
	expectOneErrorLine(runEsif("simulate --config " + config("sim/small.ini") + " --out " +
							   quoted(dir_->file("e.rawlog")) + " --noise-seed="),
					   "esif simulate: --noise-seed: the value is empty");
	expectOneErrorLine(runEsif("import mrclam --dataset " + quoted(dir_->path()) + " --robot '' --out " +
							   quoted(dir_->file("m.rawlog"))),
					   "esif import mrclam: --robot: the value is empty");
	expectOneErrorLine(runEsif("import victoria-park --in x --out " + quoted(dir_->file("v.rawlog")) + " --std-range-m ''"),
					   "esif import: --std-range-m: the value is empty");
	expectOneErrorLine(runEsif("run --config " + config("ekf.ini") + " --rawlog " + quoted(rawlog()) + " --out ''"),
					   "esif run: --out: the value is empty");
	expectOneErrorLine(runEsif("montecarlo --collect ''"), "esif montecarlo: --collect: the value is empty");
	EXPECT_FALSE(fs::exists(dir_->file("e.rawlog")));
}

/// True when `text` holds a byte a terminal would act on: C0 controls but
/// line breaks and tabs, DEL, C1 controls raw or UTF-8 encoded.
bool holdsTerminalControls(const std::string& text)
{
	// The paths here are ASCII but for the bytes under test, so any byte
	// from DEL up is one that was not escaped.
	return std::any_of(text.begin(), text.end(), [](char ch) {
		const auto c = static_cast<unsigned char>(ch);
		return (c < 0x20 && c != '\n' && c != '\t') || c >= 0x7f;
	});
}

TEST_F(HostileInputs, NoByteOfAPathReachesTheTerminalAsAControl)
{
	const std::string evil = dir_->file("\x9b" "31mX\xc2\x9b" "32m\x1b]0;t\x07");
	// An error line.
	const auto error = runEsif("run --config " + quoted(evil + ".ini") + " --rawlog x --out " + quoted(dir_->file("o")));
	EXPECT_EQ(error.exit_code, 1);
	EXPECT_FALSE(holdsTerminalControls(error.out)) << error.out;
	EXPECT_NE(error.out.find("\\x9b31mX\\xc2\\x9b32m\\x1b]0;t\\x07.ini: config file not found"), std::string::npos)
		<< error.out;
	// A summary on stdout names the path too. (An output's own name may hold
	// no C0 control: the record of what esif wrote is a text file of lines.)
	const std::string c1 = dir_->file("\x9b" "31mX\xc2\x9b" "32m");
	expectOneErrorLine(simulateSmall(evil + ".rawlog"), "holds a control character");
	const auto simulated = simulateSmall(c1 + ".rawlog");
	EXPECT_EQ(simulated.exit_code, 0) << simulated.out;
	EXPECT_FALSE(holdsTerminalControls(simulated.out)) << simulated.out;
	EXPECT_NE(simulated.out.find("Simulated " + dir_->file("\\x9b31mX\\xc2\\x9b32m.rawlog")), std::string::npos)
		<< simulated.out;
	// A warning: the same rawlog cut short.
	const std::string cut = c1 + "_cut.rawlog";
	put(cut, readText(c1 + ".rawlog").substr(0, 4000));
	const auto warned = runEsif("run -q --no-figures --config " + config("ekf.ini") + " --rawlog " + quoted(cut) +
								" --out " + quoted(dir_->file("w")));
	EXPECT_FALSE(holdsTerminalControls(warned.out)) << warned.out;
	EXPECT_NE(warned.out.find("esif: "), std::string::npos) << warned.out;
}

TEST_F(HostileInputs, ALabelStaysOneCellOfComparisonMdAndNeverHtml)
{
	std::string ekf = readText(sourcePath("configs/ekf.ini"));
	ekf.replace(ekf.find("label"), ekf.find('\n', ekf.find("label")) - ekf.find("label"),
				"label = a | b <script>alert(1)</script> & c");
	put(dir_->file("p.ini"), ekf);
	const auto r = runEsif("compare --configs " + quoted(dir_->file("p.ini")) + "," + config("dslam.ini") +
						   " --rawlog " + quoted(rawlog()) + " --out " + quoted(dir_->file("md")));
	ASSERT_EQ(r.exit_code, 0) << r.out;
	const std::string md = readText(dir_->file("md/comparison.md"));
	EXPECT_EQ(md.find("<script"), std::string::npos) << md;
	EXPECT_NE(md.find("| a &#124; b &lt;script&gt;alert(1)&lt;/script&gt; &amp; c | dslam |"), std::string::npos) << md;
	// The header, the delimiter row under it and a row of figures have as many cells.
	std::istringstream lines(md);
	std::vector<long> cells;
	for (std::string line; std::getline(lines, line);)
		if (line.rfind("| metric |", 0) == 0 || (cells.size() == 1 && line.rfind("|---", 0) == 0) ||
			line.rfind("| ate_rmse_m |", 0) == 0)
			cells.push_back(std::count(line.begin(), line.end(), '|'));
	EXPECT_EQ(cells, std::vector<long>(3, 4)) << md;
}

TEST_F(HostileInputs, ALabelSeveralRunsCarryNamesNoReference)
{
	std::string dslam = readText(sourcePath("configs/dslam.ini"));
	dslam.replace(dslam.find("label"), dslam.find('\n', dslam.find("label")) - dslam.find("label"), "label = ekf");
	put(dir_->file("dslam.ini"), dslam);
	// The run folder "ekf" is that of configs/ekf.ini, but "ekf" is also the other one's label.
	expectOneErrorLine(runEsif("compare --configs " + config("ekf.ini") + "," + quoted(dir_->file("dslam.ini")) +
							   " --rawlog " + quoted(rawlog()) + " --reference ekf --out " + quoted(dir_->file("c"))),
					   "--reference 'ekf': several runs have this label (" + sourcePath("configs/ekf.ini") + ", " +
						   dir_->file("dslam.ini") + "); name one of their run folders (dslam) or give each config "
													 "its own [esif] label");
	EXPECT_FALSE(fs::exists(dir_->file("c")));
}

TEST_F(HostileInputs, OutOfMemoryOutsideTheReplayLoopExits3)
{
	TempDir dir;
	const std::string small = dir.file("s.rawlog");
	ASSERT_EQ(simulateSmall(small).exit_code, 0);
	// Two million landmarks of ground truth beside a rawlog of 16: read before the replay.
	{
		std::ofstream truth(dir.file("s_ground_truth.txt"), std::ios::trunc);
		for (int i = 0; i < 2000000; ++i) truth << " 1.0 2.0 0.0 5 0 0.0 " << i << "\n";
	}
	const auto [code, text] = esif::test::finish(esif::test::spawnEsif(
		{"run", "-q", "--no-figures", "--config", sourcePath("configs/ekf.ini"), "--rawlog", small, "--out",
		 dir.file("o")},
		esif::test::SpawnLimits{{}, rlim_t{600} << 20, {}}));
	EXPECT_EQ(code, 3) << text;
	EXPECT_EQ(text, "esif: out of memory\n");
	EXPECT_FALSE(fs::exists(dir.file("o")));
}

TEST_F(HostileInputs, AReferenceRunBeyondItsBoundsIsRefusedNamingFileAndLine)
{
	const auto compareWith = [&](const std::string& ref) {
		return runEsif("compare --configs " + config("ekf.ini") + " --rawlog " + quoted(rawlog()) + " --reference " +
					   quoted(ref) + " --out " + quoted(dir_->file("cmp_" + fs::path(ref).filename().string())));
	};
	const std::string far = damagedReference("far", "trajectory.tum", 5, [](std::string l) { return withX(l, "1e308"); });
	expectOneErrorLine(compareWith(far), far + "/trajectory.tum:5: position (1e+308");
	const std::string nan = damagedReference("nan", "trajectory.tum", 5, [](std::string l) { return withX(l, "nan"); });
	expectOneErrorLine(compareWith(nan), nan + "/trajectory.tum:5: position (nan");
	for (const std::string id : {"-7", "99999999999"})
	{
		const std::string bad = damagedReference("id" + id, "landmarks.txt", 3, [&](std::string l) {
			return id + l.substr(l.find(' '));
		});
		expectOneErrorLine(compareWith(bad), bad + "/landmarks.txt:3: landmark ID " + id + " is outside 0..2147483647");
	}
	// A reference run cut short: not scored in part.
	const std::string cut = dir_->file("cut");
	fs::copy(reference(), cut, fs::copy_options::recursive);
	fs::remove(cut + "/.esif-output");
	std::string rows = readText(cut + "/trajectory.tum");
	for (int i = 0; i < 102; ++i) rows.erase(rows.rfind('\n', rows.size() - 2) + 1);
	put(cut + "/trajectory.tum", rows);
	const std::string slsjf = config("slsjf.ini");
	expectOneErrorLine(runEsif("run -q --no-figures --config " + slsjf + " --rawlog " + quoted(rawlog()) +
							   " --reference-run " + quoted(cut) + " --out " + quoted(dir_->file("rc"))),
					   cut + "/trajectory.tum: 98 rows, the rawlog has 200 steps");
	expectOneErrorLine(runEsif("localmaps check -q --config " + slsjf + " --rawlog " + quoted(rawlog()) +
							   " --reference-run " + quoted(cut) + " --out " + quoted(dir_->file("lc"))),
					   cut + "/trajectory.tum: 98 rows, the rawlog has 200 steps");
	expectOneErrorLine(runEsif("localmaps check -q --config " + slsjf + " --rawlog " + quoted(rawlog()) +
							   " --reference-run " + quoted(far) + " --out " + quoted(dir_->file("ld"))),
					   far + "/trajectory.tum:5: position (1e+308");
	expectOneErrorLine(runEsif("export g2o --rawlog " + quoted(rawlog()) + " --associations-from " + quoted(far) +
							   " --out " + quoted(dir_->file("far.g2o"))),
					   far + "/trajectory.tum:5: position (1e+308");
	compareWith(reference());  // the intact one is a reference
	EXPECT_TRUE(fs::exists(dir_->file("cmp_ref/comparison.md")));
}

TEST_F(HostileInputs, AReferenceFolderWithoutItsTrajectoryIsNamedSo)
{
	const std::string ref = dir_->file("no_trajectory");
	fs::copy(reference(), ref, fs::copy_options::recursive);
	fs::remove(ref + "/.esif-output");
	fs::remove(ref + "/trajectory.tum");
	const auto compareWith = [&] {
		return runEsif("compare --configs " + config("ekf.ini") + " --rawlog " + quoted(rawlog()) + " --reference " +
					   quoted(ref) + " --out " + quoted(dir_->file("cmp_none")));
	};
	expectOneErrorLine(compareWith(), ref + "/trajectory.tum: trajectory not found");
	::mkfifo((ref + "/trajectory.tum").c_str(), 0644);
	expectOneErrorLine(compareWith(), ref + "/trajectory.tum: trajectory is not a regular file");
	EXPECT_FALSE(fs::exists(dir_->file("cmp_none")));
}

/// A recording in the MRCLAM layout, robot 1 driving 1 m in 10 s and
/// measuring two landmarks (as test_MrclamImporter's synthetic one).
std::string mrclamRecording(const TempDir& dir, const std::string& measurements, const std::string& odometry)
{
	const std::string d = dir.file("mrclam");
	fs::create_directory(d);
	put(d + "/Barcodes.dat", "1 5\n6 63\n7 81\n");
	put(d + "/Landmark_Groundtruth.dat", "6 1.0 2.0 0.001 0.001\n7 3.0 -1.0 0.001 0.001\n");
	put(d + "/Robot1_Odometry.dat", odometry);
	put(d + "/Robot1_Measurement.dat", measurements);
	put(d + "/Robot1_Groundtruth.dat", "99.0 0.0 0.0 0.0\n200.0 1.2 0.0 0.0\n");
	return d;
}

TEST_F(HostileInputs, DatasetFilesTheImportersCannotTakeAreOneLineAtTheirLine)
{
	TempDir dir;
	const std::string odometry = "100.0 0.1 0.0\n101.0 0.1 0.0\n102.0 0.1 0.0\n103.0 0.0 0.0\n";
	const std::string measured = "101.0 63 2.0 0.5\n101.0 81 3.0 -0.2\n102.5 63 1.5 0.4\n";
	const auto import = [&](const std::string& rec, const std::string& extra = "") {
		return runEsif("import mrclam --dataset " + quoted(rec) + " --robot 1 --out " + quoted(dir.file("m.rawlog")) +
					   " " + extra);
	};
	const auto ok = import(mrclamRecording(dir, measured, odometry));
	ASSERT_EQ(ok.exit_code, 0) << ok.out;
	// A measurement line repeated: its line, not MRPT's "Duplicate landmark ID" as an internal error.
	const std::string rec = mrclamRecording(dir, "101.0 63 2.0 0.5\n101.0 63 2.0 0.5\n", odometry);
	expectOneErrorLine(import(rec), rec + "/Robot1_Measurement.dat:2: column 2 (barcode) = 63: read twice at the same time");
	// Odometry cut after 2 s of a recording measured for 20 s.
	const std::string long_rec = mrclamRecording(dir, measured + "120.0 81 2.0 0.0\n", "100.0 0.1 0.0\n101.0 0.1 0.0\n");
	expectOneErrorLine(import(long_rec), long_rec + "/Robot1_Odometry.dat: its last velocity command is at 101 s");
	// Noise a rawlog cannot carry: a subnormal passes "> 0" and squares to zero.
	const std::string fine = mrclamRecording(dir, measured, odometry);
	expectOneErrorLine(import(fine, "--std-range-m 1e-320"), "--std-range-m = ");
	expectOneErrorLine(import(fine, "--odometry-floor-m 1e-320"), "--odometry-floor-m = ");
	expectOneErrorLine(import(fine, "--odometry-turn-psd 0"), "--odometry-turn-psd = 0: must be at least 1e-12");

	// Victoria Park: a LANDMARK line repeated.
	put(dir.file("vp.txt"), "ODOMETRY 0 1 1.0 0 0 0.01 0 0 0.01 0 0.001\nLANDMARK 1 7 5.0 1.0 0.4 0 0.4\n"
							"LANDMARK 1 7 5.0 1.0 0.4 0 0.4\nODOMETRY 1 2 1.0 0 0 0.01 0 0 0.01 0 0.001\n");
	expectOneErrorLine(runEsif("import victoria-park --in " + quoted(dir.file("vp.txt")) + " --out " +
							   quoted(dir.file("v.rawlog"))),
					   dir.file("vp.txt") + ":3: LANDMARK 1 7: landmark 7 is measured twice from pose 1");
	expectOneErrorLine(runEsif("import victoria-park --in " + quoted(dir.file("vp.txt")) + " --out " +
							   quoted(dir.file("v.rawlog")) + " --std-bearing-deg 1e-320"),
					   "--std-bearing-deg = ");
}

}  // namespace
