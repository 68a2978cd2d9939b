// stairs-sim the program: a log it writes reads back through the frame source
// with a ground-truth frame per depth frame, and the same seed gives the same bytes.
#include "common/frame_source.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

namespace fs = std::filesystem;

namespace {

std::string sim() { return std::string(STAIRS_BINARY_DIR) + "/bin/stairs-sim"; }

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), {}};
}

int run(const std::string& args) { return std::system((sim() + " " + args + " 2>/dev/null").c_str()); }

}  // namespace

TEST(SimProgram, LogReadsBackWithTruthPerFrameAndSameSeedSameBytes) {
  const fs::path dir = fs::temp_directory_path() / ("sim_program_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string common = "--preset two_flights --situation flight --resolution 160x120 --frames 12 --zlib 1";
  ASSERT_EQ(run(common + " --seed 5 --log " + (dir / "a.lcmlog").string()), 0);
  ASSERT_EQ(run(common + " --seed 5 --log " + (dir / "b.lcmlog").string()), 0);
  ASSERT_EQ(run(common + " --seed 6 --log " + (dir / "c.lcmlog").string()), 0);
  EXPECT_EQ(slurp(dir / "a.lcmlog"), slurp(dir / "b.lcmlog"));
  EXPECT_NE(slurp(dir / "a.lcmlog"), slurp(dir / "c.lcmlog"));

  auto src = stairs::open_frame_source((dir / "a.lcmlog").string());
  stairs::SourceFrame fr;
  int n = 0;
  while (src->next(fr)) {
    EXPECT_EQ(fr.image.seq, n);
    EXPECT_EQ(fr.image.K.width, 160);
    ASSERT_TRUE(fr.truth.has_value());
    EXPECT_NEAR(fr.truth->timestamp, fr.image.utime * 1e-6, 1e-9);
    EXPECT_FALSE(fr.truth->visible_steps.empty());
    ++n;
  }
  EXPECT_EQ(n, 12);
  ASSERT_TRUE(src->ground_truth().has_value());
  EXPECT_EQ(src->ground_truth()->flights.size(), 2u);
  EXPECT_EQ(src->ground_truth()->scene, "two_flights");
  EXPECT_EQ(src->invalid(), 0u);

  // Bad input: a clear error naming the option, non-zero exit.
  EXPECT_NE(run("--preset spiral --frames 1 --log " + (dir / "d.lcmlog").string()), 0);
  EXPECT_FALSE(fs::exists(dir / "d.lcmlog"));
  fs::remove_all(dir);
}

TEST(SimProgram, SequenceDirectoryHasGroundTruthWithVisibleSteps) {
  const fs::path dir = fs::temp_directory_path() / ("sim_seq_" + std::to_string(::getpid()));
  ASSERT_EQ(run("--preset straight_down --situation approach --resolution 320x240 --frames 5 --seq " + dir.string()), 0);
  auto src = stairs::open_frame_source(dir.string());
  stairs::SourceFrame fr;
  int n = 0;
  while (src->next(fr)) {
    ASSERT_TRUE(fr.truth.has_value());
    EXPECT_TRUE(fr.truth->distance_m.has_value());  // on the top landing, looking down the flight
    ++n;
  }
  EXPECT_EQ(n, 5);
  const std::string gt = slurp(dir / "groundtruth.json");
  EXPECT_NE(gt.find("\"visible_min_pixels\": 125"), std::string::npos);
  fs::remove_all(dir);
}
