#include "perception/config.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

namespace stairs {
namespace {

// One file per process: ctest runs this binary's tests side by side.
std::string write_temp(const std::string& text) {
  const std::string path =
      std::string(STAIRS_BINARY_DIR) + "/perception_config_test." + std::to_string(::getpid()) + ".json";
  std::ofstream(path) << text;
  return path;
}

std::string load_error(const std::string& text) {
  try {
    load_perception_config(write_temp(text));
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(PerceptionConfig, LoadsKnownKeys) {
  const PerceptionConfig c =
      load_perception_config(write_temp(R"({"grid_cell_px": 2, "riser_max_m": 0.21, "smooth_normals": false})"));
  EXPECT_EQ(c.grid_cell_px, 2);
  EXPECT_FLOAT_EQ(c.riser_max_m, 0.21f);
  EXPECT_FALSE(c.smooth_normals);
  EXPECT_FLOAT_EQ(c.tread_min_m, PerceptionConfig{}.tread_min_m);  // untouched default
}

TEST(PerceptionConfig, UnknownKeyIsAnErrorNamingIt) {
  EXPECT_NE(load_error(R"({"grid_cell_pix": 2})").find("grid_cell_pix"), std::string::npos);
}

TEST(PerceptionConfig, WrongTypeAndRangeAndMissingFile) {
  EXPECT_NE(load_error(R"({"grid_cell_px": "four"})").find("grid_cell_px"), std::string::npos);
  EXPECT_NE(load_error(R"({"grid_cell_px": 0})").find("out of range"), std::string::npos);
  EXPECT_NE(load_error("[1, 2]").find("object"), std::string::npos);
  EXPECT_NE(load_error("{").find("invalid JSON"), std::string::npos);
  EXPECT_THROW(load_perception_config("/nonexistent/perception.json"), std::runtime_error);
}

}  // namespace
}  // namespace stairs
