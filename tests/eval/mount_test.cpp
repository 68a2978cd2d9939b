// The camera's mount as a prior (issue 15), through the real stairs-sim program
// and the offline chain (tools/replay) with the shipped robot config
// (config/stairs-sim-robot.json: stairs-sim's robot mount, 0.45 m, -20 deg).
#include "tools/replay.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace stairs {
namespace {

namespace fs = std::filesystem;

// An open-sided flight (no side walls, the room 4 m wide): on the flight the
// floor beside the steps is in view, a level below the tread beneath the
// robot, and one frame cannot tell which of the two it stands on. The mount
// names the ground only where the robot is level and the level lies at the
// mount's height: perception gives a height on the level floor and the landing,
// none on the flight, and never the floor beside's.
TEST(Mount, OnAnOpenSidedFlightTheFloorBesideIsNeverTheGround) {
  const fs::path log = fs::path(STAIRS_BINARY_DIR) / "mount-logs" / "open_sides_robot.lcmlog";
  fs::create_directories(log.parent_path());
  const std::string cmd = std::string(STAIRS_BINARY_DIR) +
                          "/bin/stairs-sim --preset open_sides --carrier robot --resolution 320x240 --fps 10 "
                          "--seed 5 --log '" + log.string() + "' > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  eval::ReplayOptions opt;
  opt.config = load_chain_config(std::string(STAIRS_SOURCE_DIR) + "/config/stairs-sim-robot.json");
  const eval::RunResult r = eval::replay(log.string(), opt);
  fs::remove(log);
  ASSERT_TRUE(r.score);
  int with_height = 0, on_flight = 0;
  double worst_m = 0;
  for (const eval::FrameResult& f : r.frames) {
    if (!f.camera.height_m || !f.truth) continue;
    ++with_height;
    worst_m = std::max(worst_m, std::abs(*f.camera.height_m - f.truth->height_m));
    on_flight += std::abs(f.truth->pitch_deg - (-20.0)) > 3.0;  // the robot tilted on the flight
  }
  const eval::Score& s = *r.score;
  std::printf("open_sides robot: %d frames with a height (%d tilted), worst error %.2f cm, mean %.2f cm; tracked "
              "height %.2f cm, right step %.1f %%\n",
              with_height, on_flight, 100 * worst_m, s.height_error_cm.mean_abs.value_or(-1),
              s.tracked_height_error_cm.mean_abs.value_or(-1), 100 * s.tracked_step_index_accuracy.value_or(0));
  EXPECT_GE(with_height, 20);
  EXPECT_EQ(on_flight, 0);
  // Half a rise would be another level's height: none is given.
  EXPECT_LT(worst_m, 0.09);
  ASSERT_TRUE(s.height_error_cm.mean_abs);
  EXPECT_LE(*s.height_error_cm.mean_abs, 2.0);
  EXPECT_EQ(s.model_steps_detected, s.model_steps_real);
  EXPECT_EQ(s.model_false_steps, 0);
  ASSERT_TRUE(s.tracked_height_error_cm.mean_abs && s.tracked_step_index_accuracy);
  EXPECT_LE(*s.tracked_height_error_cm.mean_abs, 2.0);
  EXPECT_GE(*s.tracked_step_index_accuracy, 0.98);
}

}  // namespace
}  // namespace stairs
