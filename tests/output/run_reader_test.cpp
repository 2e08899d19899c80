// Reading a run folder back (the target of `weavelab fit`): what a run writes
// is read, and a folder no run writes is refused naming the file, line, frame
// and point before anything is allocated beyond what the file holds.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "models/scene/scene.h"
#include "output/run_reader.h"
#include "tests/output/output_test_util.h"

namespace wl {
namespace {

namespace fs = std::filesystem;

// A frame of `points` as the VTU writer lays it out (line 3 holds <Piece>,
// line 6 the first point).
std::string vtu(const std::vector<std::string>& points, const std::string& count = "") {
  std::string s = "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\">\n";
  s += "<UnstructuredGrid><Piece NumberOfPoints=\"" + (count.empty() ? std::to_string(points.size()) : count) +
       "\" NumberOfCells=\"0\">\n<Points>\n";
  s += "<DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const std::string& p : points) s += p + "\n";
  return s + "</DataArray>\n</Points>\n</Piece></UnstructuredGrid></VTKFile>\n";
}

class RunReader : public ::testing::Test {
 protected:
  // run.pvd listing `files` at `times`.
  void write_pvd(const std::vector<std::string>& times, const std::vector<std::string>& files) {
    std::ofstream pvd(dir_ / "run.pvd");
    pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
    for (size_t k = 0; k < times.size(); ++k)
      pvd << "    <DataSet timestep=\"" << times[k] << "\" group=\"\" part=\"0\" file=\"" << files[k] << "\"/>\n";
    pvd << "  </Collection>\n</VTKFile>\n";
  }
  void write_frame(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
  // Two frames at t = 0 and 0.01 s; the second one's text given.
  void write_run(const std::string& second) {
    write_frame("run_0.vtu", vtu({"0 0 0", "1 0 0"}));
    write_frame("run_1.vtu", second);
    write_pvd({"0", "0.01"}, {"run_0.vtu", "run_1.vtu"});
  }
  std::string refusal() {
    try {
      read_run_frames(dir_.path());
    } catch (const RunReadError& e) {
      return e.what();
    }
    return "(read without complaint)";
  }
  test::ScratchDir dir_;
};

TEST_F(RunReader, ReadsTheFramesOfARun) {
  write_run(vtu({"0 0 -0.5", "1 0 -0.25"}));
  const std::vector<RecordedFrame> frames = read_run_frames(dir_.path());
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[1].time, 0.01);
  EXPECT_EQ(frames[1].points(1, 2), -0.25);
}

TEST_F(RunReader, RefusesANonFiniteCoordinateNamingFileFramePointAndCoordinate) {
  for (const char* bad : {"nan", "inf", "-inf"}) {
    write_run(vtu({"0 0 0", std::string("1 ") + bad + " 0"}));
    const std::string why = refusal();
    const std::string where = (dir_ / "run_1.vtu").string() + ":7: frame 1 (t = 0.01 s), point 1: array 'Points'";
    EXPECT_NE(why.find(where), std::string::npos) << why;
    EXPECT_NE(why.find(std::string("coordinate y: got ") + bad + ", expected a finite number"), std::string::npos)
        << why;
  }
}

TEST_F(RunReader, RefusesAPointCountBeyondTheScenesAndTheFilesBeforeAllocating) {
  for (const char* count : {"2000000000", "9223372036854775808", "99999999999999999999"}) {
    write_run(vtu({"0 0 0", "1 0 0"}, count));
    const std::string why = refusal();
    EXPECT_NE(why.find((dir_ / "run_1.vtu").string() + ":3: frame 1 (t = 0.01 s): NumberOfPoints '" + count +
                       "', expected an integer from 1 to "),
              std::string::npos)
        << why;
  }
  // 16384² points would fit the scene's limit, not a file of a few hundred bytes.
  write_run(vtu({"0 0 0", "1 0 0"}, "268435456"));
  EXPECT_NE(refusal().find("bytes holds at most"), std::string::npos) << refusal();
}

TEST_F(RunReader, RefusesMoreValuesThanThePointCountAsTheyComeIn) {
  write_run(vtu({"0 0 0", "1 0 0", "2 0 0"}, "2"));
  EXPECT_NE(refusal().find(":8: frame 1 (t = 0.01 s): array 'Points' has more than the 6 values"), std::string::npos)
      << refusal();
}

TEST_F(RunReader, RefusesAFrameThatIsNotARegularFile) {
  write_frame("run_0.vtu", vtu({"0 0 0", "1 0 0"}));
  write_pvd({"0", "0.01"}, {"run_0.vtu", "/dev/zero"});
  EXPECT_NE(refusal().find((dir_ / "run.pvd").string() + ":5: frame 1 (t = 0.01 s): /dev/zero: not a regular file"),
            std::string::npos)
      << refusal();
  write_pvd({"0", "0.01"}, {"run_0.vtu", "."});
  EXPECT_NE(refusal().find(": not a regular file"), std::string::npos) << refusal();
  write_pvd({"0", "0.01"}, {"run_0.vtu", "run_9.vtu"});
  EXPECT_NE(refusal().find("run_9.vtu: missing"), std::string::npos) << refusal();
}

TEST_F(RunReader, RefusesTimesThatDoNotIncrease) {
  write_frame("run_0.vtu", vtu({"0 0 0", "1 0 0"}));
  const std::string pvd = (dir_ / "run.pvd").string();
  write_pvd({"0", "0.02", "0.01"}, {"run_0.vtu", "run_0.vtu", "run_0.vtu"});
  EXPECT_NE(refusal().find(pvd + ":6: timestep 0.01, expected a finite time after the previous frame's (0.02 s)"),
            std::string::npos)
      << refusal();
  write_pvd({"0", "0"}, {"run_0.vtu", "run_0.vtu"});
  EXPECT_NE(refusal().find(pvd + ":5: timestep 0,"), std::string::npos) << refusal();
  write_pvd({"0", "nan"}, {"run_0.vtu", "run_0.vtu"});
  EXPECT_NE(refusal().find(pvd + ":5: timestep nan,"), std::string::npos) << refusal();
}

TEST_F(RunReader, RefusesMoreFramesThanARunWrites) {
  write_frame("run_0.vtu", vtu({"0 0 0", "1 0 0"}));
  std::vector<std::string> times, files;
  for (int k = 0; k <= static_cast<int>(kMaxFrames) + 1; ++k) {
    times.push_back(std::to_string(k));
    files.push_back("run_0.vtu");
  }
  write_pvd(times, files);
  std::string expected = ":";
  expected += std::to_string(static_cast<int>(kMaxFrames) + 5);
  expected += ": more than 100001 frames";
  EXPECT_NE(refusal().find(expected), std::string::npos) << refusal();
}

}  // namespace
}  // namespace wl
