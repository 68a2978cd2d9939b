#include "perception/config.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

namespace stairs {
namespace {

// One file per process: ctest runs this binary's tests side by side. Removed when the process
// ends (each ctest run left one in the build directory).
std::string write_temp(const std::string& text) {
  struct RemovedAtExit {
    std::string path =
        std::string(STAIRS_BINARY_DIR) + "/perception_config_test." + std::to_string(::getpid()) + ".json";
    ~RemovedAtExit() { std::remove(path.c_str()); }
  };
  static const RemovedAtExit file;
  std::ofstream(file.path) << text;
  return file.path;
}

std::string load_error(const std::string& text) {
  try {
    load_perception_config(write_temp(text));
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(PerceptionConfig, LoadsKnownKeysOfTheSectionedFile) {
  const PerceptionConfig c = load_perception_config(write_temp(
      R"({"perception": {"normals": {"grid_cell_px": 2, "smooth": false}, "stair": {"riser_max_m": 0.21}},
          "tracker": {"confirmation": {"min_confirmations": 3}}})"));
  EXPECT_EQ(c.normals.grid_cell_px, 2);
  EXPECT_FLOAT_EQ(c.stair.riser_max_m, 0.21f);
  EXPECT_FALSE(c.normals.smooth);
  EXPECT_FLOAT_EQ(c.stair.tread_min_m, PerceptionConfig{}.stair.tread_min_m);  // untouched default
}

TEST(PerceptionConfig, UnknownKeyIsAnErrorNamingItsFullPath) {
  const std::string e = load_error(R"({"perception": {"normals": {"grid_cell_pix": 2}}})");
  EXPECT_NE(e.find("'perception.normals.grid_cell_pix'"), std::string::npos) << e;
  EXPECT_NE(e.find("perception_config_test"), std::string::npos) << "names the file: " << e;
}

// A flat file of the old layout is refused, not read as defaults (issue 16).
TEST(PerceptionConfig, AFlatFileIsRefusedWithAHint) {
  const std::string top = load_error(R"({"riser_max_m": 0.21})");
  EXPECT_NE(top.find("'riser_max_m'"), std::string::npos) << top;
  EXPECT_NE(top.find("\"perception\" and \"tracker\""), std::string::npos) << top;
  const std::string inner = load_error(R"({"perception": {"riser_max_m": 0.21}})");
  EXPECT_NE(inner.find("'perception.riser_max_m'"), std::string::npos) << inner;
  EXPECT_NE(inner.find("grouped by stage"), std::string::npos) << inner;
}

TEST(PerceptionConfig, WrongTypeAndRangeNameTheKeyAndTheAllowedRange) {
  const std::string type = load_error(R"({"perception": {"normals": {"grid_cell_px": "four"}}})");
  EXPECT_NE(type.find("'perception.normals.grid_cell_px' must be an integer"), std::string::npos) << type;
  const std::string range = load_error(R"({"perception": {"normals": {"grid_cell_px": 0}}})");
  EXPECT_NE(range.find("'perception.normals.grid_cell_px' = 0 is out of range: allowed 1..64"), std::string::npos)
      << range;
  const std::string order = load_error(R"({"perception": {"stair": {"riser_min_m": 0.3}}})");
  EXPECT_NE(order.find("'perception.stair.riser_min_m' must be at most stair.riser_max_m"), std::string::npos) << order;
  EXPECT_NE(load_error("[1, 2]").find("object"), std::string::npos);
  EXPECT_NE(load_error("{").find("bad JSON"), std::string::npos);
  EXPECT_THROW(load_perception_config("/nonexistent/perception.json"), std::runtime_error);
}

// What perception and the tracker share is one top-level key, not a copy in each section.
TEST(PerceptionConfig, TheLandingDepthIsTheTopLevelStairKey) {
  const PerceptionConfig c = load_perception_config(write_temp(R"({"stair": {"landing_min_depth_m": 0.8}})"));
  EXPECT_FLOAT_EQ(c.stair.landing_min_depth_m, 0.8f);
  EXPECT_FLOAT_EQ(stair_definition(c).landing_min_depth_m, 0.8f);
  const std::string moved = load_error(R"({"perception": {"stair": {"landing_min_depth_m": 0.8}}})");
  EXPECT_NE(moved.find("unknown key 'perception.stair.landing_min_depth_m'"), std::string::npos) << moved;
  const std::string range = load_error(R"({"stair": {"landing_min_depth_m": -1}})");
  EXPECT_NE(range.find("'stair.landing_min_depth_m' = -1 is out of range"), std::string::npos) << range;
}

// The camera's mount on a robot is the top-level "mount" object (issue 15).
TEST(PerceptionConfig, TheMountIsTheTopLevelMountObject) {
  const PerceptionConfig c =
      load_perception_config(write_temp(R"({"mount": {"height_m": 0.45, "pitch_deg": -20}})"));
  EXPECT_FLOAT_EQ(c.mount.height_m, 0.45f);
  EXPECT_FLOAT_EQ(c.mount.pitch_deg, -20.0f);
  EXPECT_TRUE(c.mount.configured());
  EXPECT_FALSE(PerceptionConfig{}.mount.configured());
  const std::string e = load_error(R"({"mount": {"height": 0.45}})");
  EXPECT_NE(e.find("unknown key 'mount.height'"), std::string::npos) << e;
}

// --print-config's JSON read back gives the same values: one field list serves both.
TEST(PerceptionConfig, PrintedConfigReadsBackToTheSameValues) {
  PerceptionConfig c;
  c.normals.grid_cell_px = 3;
  c.verification.widths = false;
  c.imu.to_camera_pitch_deg = -90.0f;
  const auto printed = to_json(c);
  EXPECT_EQ(printed["normals"]["grid_cell_px"], 3);
  const PerceptionConfig back = perception_config_from_json(printed, "printed");
  EXPECT_EQ(to_json(back), printed);
  EXPECT_EQ(back.normals.grid_cell_px, 3);
  EXPECT_FALSE(back.verification.widths);
}

// The shipped config/default.json holds every key, at its default.
TEST(PerceptionConfig, ShippedDefaultsAreTheDefaults) {
  const std::string path = std::string(STAIRS_SOURCE_DIR) + "/config/default.json";
  EXPECT_EQ(to_json(load_perception_config(path)), to_json(PerceptionConfig{}));
}

}  // namespace
}  // namespace stairs
