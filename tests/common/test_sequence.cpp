// Sequence directories: round trip, and a clear error for each broken input.
#include "common/json_io.hpp"
#include "common/sequence.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <fstream>
#include <tuple>

using namespace stairs;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir(const std::string& name) {
  fs::path p = fs::temp_directory_path() / ("stairs_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  return p;
}

DepthImage image(int w, int h, uint16_t base) {
  DepthImage img;
  img.K = {w, h, 100, 100, (w - 1) / 2.0, (h - 1) / 2.0};
  img.depth.resize(static_cast<size_t>(w) * h);
  for (size_t i = 0; i < img.depth.size(); ++i) img.depth[i] = static_cast<uint16_t>(base + i);
  return img;
}

GroundTruth truth() {
  GroundTruth gt;
  gt.scene = "unit";
  Flight f;
  f.width_m = 1.2;
  for (int i = 0; i < 3; ++i) {
    Step s;
    s.riser_height_m = 0.18;
    s.tread_depth_m = i == 2 ? 1.5 : 0.25;
    s.landing = i == 2;
    s.nosing_m = {0.25 * i, 0, 0.18 * (i + 1)};
    f.steps.push_back(s);
  }
  gt.flights = {f};
  for (int i = 0; i < 2; ++i) {
    GroundTruthFrame fr;
    fr.timestamp = i / 30.0;
    fr.pitch_deg = -35;
    fr.height_m = 1.0;
    fr.distance_m = i ? std::optional<double>() : std::optional<double>(1.2);
    fr.visible_steps = {0, 1};
    gt.frames.push_back(fr);
  }
  return gt;
}

fs::path write_sequence(const std::string& name) {
  const fs::path dir = temp_dir(name);
  SequenceWriter w(dir.string(), image(32, 24, 0).K, 0.001);
  w.write(image(32, 24, 1000), 0.0);
  w.write(image(32, 24, 2000), 1.0 / 30);
  w.finish(truth());
  return dir;
}

void expect_error(const fs::path& dir, const std::string& needle, bool on_read = false) {
  try {
    SequenceReader r(dir.string());
    if (on_read) r.read(0);
    FAIL() << "no error for " << needle;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(Sequence, RoundTrip) {
  const fs::path dir = write_sequence("rt");
  SequenceReader r(dir.string());
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r.intrinsics().width, 32);
  EXPECT_DOUBLE_EQ(r.depth_scale(), 0.001);
  const DepthImage b = r.read(1);
  EXPECT_EQ(b.depth, image(32, 24, 2000).depth);
  EXPECT_EQ(b.seq, 1);
  EXPECT_EQ(b.utime, 33333);
  ASSERT_TRUE(r.ground_truth());
  const GroundTruth& gt = *r.ground_truth();
  EXPECT_EQ(gt.scene, "unit");
  ASSERT_EQ(gt.flights.size(), 1u);
  ASSERT_EQ(gt.flights[0].steps.size(), 3u);
  EXPECT_TRUE(gt.flights[0].steps[2].landing);
  EXPECT_NEAR(gt.flights[0].steps[1].nosing_m.z(), 0.36, 1e-12);
  ASSERT_EQ(gt.frames.size(), 2u);
  EXPECT_TRUE(gt.frames[0].distance_m.has_value());
  EXPECT_FALSE(gt.frames[1].distance_m.has_value());
  // The file holds DESIGN.md's keys.
  const auto j = read_json_file((dir / "groundtruth.json").string());
  EXPECT_TRUE(j["flights"][0]["steps"][0].contains("riser_height_m"));
  EXPECT_TRUE(j["flights"][0].contains("top_landing_depth_m"));
  EXPECT_TRUE(j["frames"][1]["distance_m"].is_null());
  EXPECT_EQ(j["frames"][0]["visible_steps"].size(), 2u);
  fs::remove_all(dir);
}

TEST(Sequence, ReadsTheRealDataDirectories) {
  for (const char* name : {"kinect1_thesis_up", "kinect2_lab_up"}) {
    const fs::path dir = fs::path(STAIRS_REALDATA_DIR) / name;
    if (!fs::exists(dir)) GTEST_SKIP() << dir << " not present";
    SequenceReader r(dir.string());
    EXPECT_EQ(r.size(), 2u);
    const DepthImage img = r.read(0);
    EXPECT_EQ(img.depth.size(), static_cast<size_t>(r.intrinsics().width) * r.intrinsics().height);
  }
}

// DESIGN.md odometry.txt: written by SequenceWriter, read back in order; each
// frame of a sequence source gets the samples up to its own time.
TEST(Sequence, OdometryRoundTrip) {
  const fs::path dir = temp_dir("odometry");
  SequenceWriter w(dir.string(), image(32, 24, 0).K, 0.001);
  w.write(image(32, 24, 1000), 0.0);
  w.write(image(32, 24, 2000), 0.1);
  for (int i = 0; i < 3; ++i) {
    OdometrySample o;
    o.utime = i * 50000;
    o.position_m = {0.1 * i, -0.2, 1.0};
    o.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * i, Eigen::Vector3d::UnitZ()));
    w.write_odometry(o);
  }
  w.finish();
  SequenceReader r(dir.string());
  ASSERT_EQ(r.odometry().size(), 3u);
  EXPECT_EQ(r.odometry()[2].utime, 100000);
  EXPECT_NEAR(r.odometry()[2].position_m.x(), 0.2, 1e-6);
  EXPECT_NEAR(r.odometry()[1].orientation.angularDistance(
                  Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()))),
              0.0, 1e-6);
  fs::remove_all(dir);
}

// A malformed optional file leaves the sequence readable without it, with a
// warning naming the file and the line.
TEST(Sequence, MalformedOdometryOrImuIsLeftOutWithAWarning) {
  for (const auto& [file, body, needle] :
       {std::tuple<std::string, std::string, std::string>{"odometry.txt", "# t x y z qw qx qy qz\n0 0 0 0 1 0 0\n",
                                                          "odometry.txt:2: expected"},
        {"odometry.txt", "0 0 0 0 1 0 0 0\n0.1 0 0 0 0.5 0 0 0\n", "odometry.txt:2: qw qx qy qz is no unit quaternion"},
        {"odometry.txt", "0.1 0 0 0 1 0 0 0\n0.1 0 0 0 1 0 0 0\n", "odometry.txt:2: time does not increase"},
        {"odometry.txt", "0 nan 0 0 1 0 0 0\n", "odometry.txt:1: expected"},
        {"imu.txt", "# raw\n[2018-4-13]\n1,2,3\n", "imu.txt:2: expected"},
        {"imu.txt", "0.1 0 0 9.8 0 0 0\n0.05 0 0 9.8 0 0 0\n", "imu.txt:2: time does not increase"}}) {
    const fs::path dir = write_sequence("bad_optional");
    std::ofstream(dir / file) << body;
    SequenceReader r(dir.string());
    EXPECT_EQ(r.size(), 2u);
    EXPECT_TRUE(r.odometry().empty() && r.imu().empty());
    ASSERT_EQ(r.warnings().size(), 1u) << needle;
    EXPECT_NE(r.warnings()[0].find(needle), std::string::npos) << r.warnings()[0];
    fs::remove_all(dir);
  }
}

// Issue 18: depth_scale 1.0 (metres per unit) reads, but would put every point
// a kilometre away: a plausibility warning naming the file.
TEST(Sequence, ImplausibleDepthScaleIsWarnedAbout) {
  const fs::path dir = temp_dir("depth_scale");
  SequenceWriter w(dir.string(), image(32, 24, 0).K, 1.0);
  w.write(image(32, 24, 1000), 0.0);
  w.finish();
  SequenceReader r(dir.string());
  ASSERT_EQ(r.warnings().size(), 1u);
  EXPECT_NE(r.warnings()[0].find("camera.json: depth_scale"), std::string::npos) << r.warnings()[0];
  EXPECT_TRUE(SequenceReader(write_sequence("depth_scale_ok").string()).warnings().empty());
  fs::remove_all(dir);
}

TEST(Sequence, MissingCameraJson) {
  const fs::path dir = write_sequence("nocam");
  fs::remove(dir / "camera.json");
  expect_error(dir, "camera.json: missing");
  fs::remove_all(dir);
}

TEST(Sequence, BadJson) {
  const fs::path dir = write_sequence("badjson");
  std::ofstream(dir / "camera.json") << "{\"width\": 32, ";
  expect_error(dir, "camera.json: bad JSON");
  std::ofstream(dir / "camera.json") << "{\"width\": 32}";
  expect_error(dir, "missing key 'height'");
  std::ofstream(dir / "groundtruth.json") << "[1,2";
  std::ofstream(dir / "camera.json") << "{\"width\":32,\"height\":24,\"fx\":1,\"fy\":1,\"cx\":0,\"cy\":0,\"depth_scale\":0.001}";
  expect_error(dir, "groundtruth.json: bad JSON");
  fs::remove_all(dir);
}

// A malformed field gives the reader's own error naming the file and the field,
// never a raw JSON type error (the sequence-parser fuzz target found a step
// that was a number: tests/fuzz/corpus/sequence/step_is_a_number).
TEST(Sequence, MalformedGroundTruthFieldsNameTheField) {
  const fs::path dir = write_sequence("badgt");
  const std::pair<const char*, const char*> cases[] = {
      {R"({"flights":[{"steps":[5]}]})", "groundtruth.json: flights[0].steps[0]: is not an object"},
      {R"({"flights":[7]})", "groundtruth.json: flights[0]: is not an object"},
      {R"({"flights":[{"steps":[{"landing":"yes"}]}]})", "flights[0].steps[0]: 'landing' is not true/false"},
      {R"({"flights":[{"steps":[{"nosing_m":["a",1]}]}]})", "flights[0].steps[0]: 'nosing_m' holds a non-number"},
      {R"({"flights":[],"frames":[{"timestamp":0,"pitch_deg":0,"roll_deg":0,"height_m":1,"visible_steps":[1.5]}]})",
       "frames[0]: 'visible_steps' holds a value that is no step index"},
      {R"({"flights":[],"frames":[{"timestamp":0,"pitch_deg":0,"roll_deg":0,"height_m":1,"position_m":{"x":1}}]})",
       "frames[0]: 'position_m' is not an array of 3"},
      {R"({"flights":[],"frames":[3]})", "frames[0]: is not an object"}};
  for (const auto& [text, needle] : cases) {
    std::ofstream(dir / "groundtruth.json") << text;
    expect_error(dir, needle);
  }
  fs::remove_all(dir);
}

TEST(Sequence, MissingPng) {
  const fs::path dir = write_sequence("nopng");
  fs::remove(dir / "depth" / "000000.png");
  expect_error(dir, "000000.png: missing", true);
  fs::remove_all(dir);
}

TEST(Sequence, EightBitPng) {
  const fs::path dir = write_sequence("8bit");
  cv::imwrite((dir / "depth" / "000000.png").string(), cv::Mat(24, 32, CV_8UC1, cv::Scalar(7)));
  expect_error(dir, "16-bit", true);
  fs::remove_all(dir);
}

TEST(Sequence, MisSizedPng) {
  const fs::path dir = write_sequence("size");
  cv::imwrite((dir / "depth" / "000000.png").string(), cv::Mat(20, 32, CV_16UC1, cv::Scalar(700)));
  expect_error(dir, "does not match camera.json", true);
  fs::remove_all(dir);
}

TEST(Sequence, UnfinishedWriterLeavesNoIndex) {
  const fs::path dir = temp_dir("unfinished");
  {
    SequenceWriter w(dir.string(), image(8, 8, 0).K, 0.001);
    w.write(image(8, 8, 10), 0.0);
  }  // no finish(): interrupted
  EXPECT_FALSE(fs::exists(dir / "depth.txt"));
  expect_error(dir, "camera.json: missing");
  fs::remove_all(dir);
}
