// LCM logs: round trip through the frame source, truncation, partial writes.
#include "common/frame_source.hpp"
#include "common/lcm_bridge.hpp"
#include "common/lcm_log.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace stairs;
namespace fs = std::filesystem;

namespace {

DepthImage image(int seq) {
  DepthImage img;
  img.K = {16, 12, 20, 20, 7.5, 5.5};
  img.depth.assign(16 * 12, static_cast<uint16_t>(1000 + seq));
  img.seq = seq;
  img.utime = 1000 + seq * 33333;
  return img;
}

fs::path write_log(const std::string& name, int frames) {
  const fs::path path = fs::temp_directory_path() / ("stairs_log_" + name + std::to_string(::getpid()) + ".lcmlog");
  LogWriter w(path.string());
  GroundTruth gt;
  gt.scene = "log";
  gt.flights.resize(1);
  gt.flights[0].steps.resize(2);
  for (int i = 0; i < frames; ++i) {
    const DepthImage img = image(i);
    GroundTruthFrame fr;
    fr.height_m = 1.0 + i;
    // Ground truth alternately before and after its frame.
    if (i % 2) w.write_message("STAIRS_GROUND_TRUTH", img.utime, to_lcm(gt, fr, img.utime, img.seq));
    w.write_message("STAIRS_DEPTH", img.utime, to_lcm(img, 1));
    if (!(i % 2)) w.write_message("STAIRS_GROUND_TRUTH", img.utime, to_lcm(gt, fr, img.utime, img.seq));
  }
  w.write("STAIRS_DEPTH", 5, "garbage", 7);  // a corrupt message is skipped and counted
  w.close();
  return path;
}

}  // namespace

TEST(LcmLog, FrameSourceMatchesGroundTruth) {
  const fs::path path = write_log("ok", 5);
  auto src = open_frame_source(path.string());
  SourceFrame f;
  int n = 0;
  while (src->next(f)) {
    EXPECT_EQ(f.image.seq, n);
    EXPECT_EQ(f.image.depth[3], 1000 + n);
    ASSERT_TRUE(f.truth.has_value()) << n;
    EXPECT_DOUBLE_EQ(f.truth->height_m, 1.0 + n);
    ++n;
  }
  EXPECT_EQ(n, 5);
  ASSERT_TRUE(src->ground_truth());
  EXPECT_EQ(src->ground_truth()->flights[0].steps.size(), 2u);
  EXPECT_EQ(src->invalid(), 1u);
  EXPECT_NE(src->last_error().find("STAIRS_DEPTH"), std::string::npos);
  EXPECT_DOUBLE_EQ(src->progress(), 1.0);
  fs::remove(path);
}

TEST(LcmLog, TruncatedLogNamesTheFile) {
  const fs::path path = write_log("trunc", 3);
  fs::resize_file(path, fs::file_size(path) - 100);
  auto src = open_frame_source(path.string());
  SourceFrame f;
  try {
    while (src->next(f)) {
    }
    FAIL() << "truncation not reported";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
  fs::remove(path);
}

TEST(LcmLog, NotALog) {
  const fs::path path = fs::temp_directory_path() / "stairs_not_a_log.txt";
  { std::ofstream(path) << "hello, this is not an LCM log at all\n"; }
  auto src = open_frame_source(path.string());
  SourceFrame f;
  EXPECT_THROW(src->next(f), std::runtime_error);
  EXPECT_THROW(open_frame_source("/nonexistent/file.lcmlog"), std::runtime_error);
  fs::remove(path);
}

TEST(LcmLog, UnclosedWriterLeavesOnlyPartial) {
  const fs::path path = fs::temp_directory_path() / ("stairs_partial_" + std::to_string(::getpid()) + ".lcmlog");
  {
    LogWriter w(path.string());
    w.write("X", 1, "abc", 3);
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::exists(path.string() + ".partial"));
  fs::remove(path.string() + ".partial");
}
