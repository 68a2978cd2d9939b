#include "tools/downsample.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace stairs::eval {
namespace {

DepthImage image_4x2(std::vector<uint16_t> depth) {
  DepthImage img;
  img.K = {4, 2, 100.0, 100.0, 1.5, 0.5};
  img.depth = std::move(depth);
  return img;
}

TEST(EvalDownsample, BlockMeanKeepsForegroundAtEdges) {
  // Left block: one surface (1000, 1010, 1020, hole); right block: 1000 in front of 3000.
  const DepthImage out = downsample(image_4x2({1000, 1010, 1000, 3000, 1020, 0, 3000, 3000}), 2);
  ASSERT_EQ(out.K.width, 2);
  ASSERT_EQ(out.K.height, 1);
  EXPECT_EQ(out.depth[0], 1010);
  EXPECT_EQ(out.depth[1], 1000);
  EXPECT_DOUBLE_EQ(out.K.fx, 50.0);
  EXPECT_DOUBLE_EQ(out.K.cx, 0.5);  // block centres: (1.5 + 0.5) / 2 - 0.5
  EXPECT_DOUBLE_EQ(out.K.cy, 0.0);
}

TEST(EvalDownsample, FactorAndResolutionParsing) {
  Intrinsics K{640, 480, 525, 525, 319.5, 239.5};
  EXPECT_EQ(downsample_factor(K, 320, 240), 2);
  EXPECT_EQ(downsample_factor(K, 640, 480), 1);
  EXPECT_THROW(downsample_factor(K, 300, 240), std::invalid_argument);
  EXPECT_THROW(downsample_factor(K, 320, 480), std::invalid_argument);
  int w = 0, h = 0;
  parse_resolution("320x240", w, h);
  EXPECT_EQ(w, 320);
  EXPECT_EQ(h, 240);
  EXPECT_THROW(parse_resolution("320", w, h), std::invalid_argument);
  EXPECT_THROW(parse_resolution("320x240x", w, h), std::invalid_argument);
}

}  // namespace
}  // namespace stairs::eval
