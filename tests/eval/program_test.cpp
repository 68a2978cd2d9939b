// stairs-eval as a program: real simulated input (log and sequence directory),
// the Result JSON it writes, and its errors on bad files.
#include "common/lcm_bridge.hpp"
#include "common/lcm_log.hpp"
#include "common/sequence.hpp"
#include "drivers/sim/render.hpp"
#include "drivers/sim/trajectory.hpp"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kFrames = 12;

fs::path work_dir() {
  const fs::path d = fs::path(STAIRS_BINARY_DIR) / "eval-program-test" /
                     ::testing::UnitTest::GetInstance()->current_test_info()->name();
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// kFrames frames spread over a hand-held walk up the straight_up preset,
// written as a log (depth + ground truth) and as a sequence directory.
void make_inputs(const fs::path& log, const fs::path& seq) {
  using namespace stairs;
  const sim::Scene scene = sim::make_preset("straight_up");
  const Intrinsics K{640, 480, 525.0, 525.0, 319.5, 239.5};
  sim::Renderer renderer(scene, K, sim::SensorModel{}, 7);
  const sim::Trajectory trajectory(scene, sim::trajectory_defaults(sim::Carrier::HandHeld));
  GroundTruth truth = renderer.stair_truth();
  LogWriter writer(log.string());
  SequenceWriter sequence(seq.string(), K, 0.001);
  for (int i = 0; i < kFrames; ++i) {
    const int index = i * (trajectory.frames() - 1) / (kFrames - 1);
    const double t = trajectory.time_s(index);
    const auto pose = trajectory.pose(index);
    const int64_t utime = static_cast<int64_t>(t * 1e6);
    const DepthImage image = renderer.render(pose, utime, i);
    const GroundTruthFrame frame = renderer.truth(pose, t, image);
    writer.write_message("STAIRS_DEPTH", utime, to_lcm(image, 1));
    writer.write_message("STAIRS_GROUND_TRUTH", utime, to_lcm(truth, frame, utime, i));
    sequence.write(image, t);
    truth.frames.push_back(frame);
  }
  writer.close();
  sequence.finish(truth);
}

struct Outcome {
  int status = -1;
  std::string output;  // stdout and stderr
};

Outcome run_eval(const std::string& args) {
  const std::string cmd = std::string(STAIRS_BINARY_DIR) + "/bin/stairs-eval " + args + " 2>&1";
  Outcome o;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return o;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) o.output.append(buf.data(), n);
  o.status = pclose(p);
  return o;
}

json read(const fs::path& p) {
  std::ifstream in(p);
  return json::parse(in);
}

void expect_complete(const json& r, int frames) {
  for (const char* k : {"input", "frames_total", "frames_processed", "frames", "model", "score"})
    ASSERT_TRUE(r.contains(k)) << k;
  EXPECT_EQ(r["frames_processed"], frames);
  ASSERT_EQ(r["frames"].size(), size_t(frames));
  for (const json& f : r["frames"]) {
    for (const char* k : {"timestamp", "camera", "direction", "steps", "latency_ms"}) EXPECT_TRUE(f.contains(k)) << k;
    EXPECT_TRUE(f["latency_ms"]["perception"].is_number());
    EXPECT_TRUE(f["latency_ms"]["tracker"].is_number());
  }
  ASSERT_TRUE(r["model"].is_object());
  EXPECT_TRUE(r["model"].contains("flights"));
  ASSERT_TRUE(r["score"].is_object()) << "ground truth was in the input";
  const json& s = r["score"];
  EXPECT_EQ(s["frames_scored"], frames);
  EXPECT_GT(s["visible_steps"].get<int>(), 0);
  EXPECT_GT(s["model_steps_real"].get<int>(), 0);
  EXPECT_TRUE(s["latency_ms"]["perception"]["median"].is_number());
}

// The shared option parser (common/daemon.hpp): -h is --help, --version names the program and version.
TEST(EvalProgram, ShortHelpAndVersion) {
  const Outcome h = run_eval("-h");
  EXPECT_EQ(h.status, 0) << h.output;
  EXPECT_EQ(h.output.rfind("Usage: stairs-eval", 0), 0u) << h.output;
  EXPECT_NE(h.output.find("--version"), std::string::npos) << h.output;
  const Outcome v = run_eval("--version");
  EXPECT_EQ(v.status, 0) << v.output;
  EXPECT_EQ(v.output.rfind("stairs-eval 0.", 0), 0u) << v.output;
}

TEST(EvalProgram, ScoresLogAndSequenceAlike) {
  const fs::path d = work_dir();
  make_inputs(d / "walk.lcmlog", d / "walk");
  const Outcome a = run_eval("--quiet --json " + (d / "log.json").string() + " " + (d / "walk.lcmlog").string());
  ASSERT_EQ(a.status, 0) << a.output;
  const Outcome b = run_eval("--json " + (d / "seq.json").string() + " " + (d / "walk").string());
  ASSERT_EQ(b.status, 0) << b.output;
  EXPECT_NE(b.output.find("Table 6.1"), std::string::npos) << b.output;
  EXPECT_NE(b.output.find("Table 6.4"), std::string::npos) << b.output;
  const json log = read(d / "log.json"), seq = read(d / "seq.json");
  expect_complete(log, kFrames);
  expect_complete(seq, kFrames);
  // Same frames and truth through both readers: same scores.
  EXPECT_EQ(log["score"]["visible_steps"], seq["score"]["visible_steps"]);
  EXPECT_EQ(log["score"]["frame_steps_matched"], seq["score"]["frame_steps_matched"]);
  EXPECT_EQ(log["score"]["model_steps_real"], seq["score"]["model_steps_real"]);
}

TEST(EvalProgram, MaxFramesAndResolution) {
  const fs::path d = work_dir();
  make_inputs(d / "walk.lcmlog", d / "walk");
  const Outcome a = run_eval("--quiet --max-frames 5 --resolution 320x240 --json " + (d / "r.json").string() + " " +
                             (d / "walk").string());
  ASSERT_EQ(a.status, 0) << a.output;
  const json r = read(d / "r.json");
  EXPECT_EQ(r["frames_total"], kFrames);
  expect_complete(r, 5);
  const Outcome bad = run_eval("--quiet --resolution 300x200 " + (d / "walk").string());
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.output.find("--resolution"), std::string::npos) << bad.output;
}

TEST(EvalProgram, BadFilesFailClearlyWithoutJson) {
  const fs::path d = work_dir();
  make_inputs(d / "walk.lcmlog", d / "walk");
  // A log cut inside its last event.
  const fs::path cut = d / "cut.lcmlog";
  fs::copy_file(d / "walk.lcmlog", cut);
  fs::resize_file(cut, fs::file_size(cut) - 100);
  // A sequence with a broken groundtruth.json.
  fs::copy(d / "walk", d / "broken", fs::copy_options::recursive);
  std::ofstream(d / "broken" / "groundtruth.json") << "{\"flights\": [";
  const fs::path config = d / "config.json";
  std::ofstream(config) << "{\"perception\": 3}";

  const std::pair<std::string, std::string> cases[] = {
      {(d / "missing.lcmlog").string(), "missing.lcmlog"},
      {cut.string(), "cut.lcmlog"},
      {(d / "broken").string(), "groundtruth.json"},
      {"--config " + config.string() + " " + (d / "walk").string(), "config.json"},
  };
  for (const auto& [args, names] : cases) {
    const fs::path out = d / "out.json";
    const Outcome o = run_eval("--quiet --json " + out.string() + " " + args);
    EXPECT_NE(o.status, 0) << args;
    EXPECT_NE(o.output.find(names), std::string::npos) << "error should name " << names << ": " << o.output;
    EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << "one line: " << o.output;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
}

}  // namespace
