// Depth frames: zlib and raw round trips, and every validation failure.
#include "common/cloud.hpp"
#include "common/lcm_bridge.hpp"
#include "common/zlib_codec.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace stairs;

namespace {

DepthImage ramp_image(int w = 64, int h = 48) {
  DepthImage img;
  img.K = {w, h, 52.5, 52.5, (w - 1) / 2.0, (h - 1) / 2.0};
  img.depth_scale = 0.001;
  img.utime = 1700000000123456;
  img.seq = 17;
  img.depth.resize(static_cast<size_t>(w) * h);
  std::mt19937 rng(3);
  for (size_t i = 0; i < img.depth.size(); ++i) img.depth[i] = static_cast<uint16_t>(500 + (i % 997) + rng() % 7);
  img.depth[5] = 0;
  img.depth[img.depth.size() - 1] = 65535;
  return img;
}

std::vector<uint8_t> encode(const depth_frame_t& m) {
  std::vector<uint8_t> buf(m.getEncodedSize());
  m.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

bool decode_image(const std::vector<uint8_t>& buf, DepthImage& img, std::string& error) {
  depth_frame_t m;
  return decode_message(buf.data(), buf.size(), m, error) && from_lcm(m, img, error);
}

}  // namespace

TEST(Codec, ZlibAndRawRoundTrip) {
  const DepthImage img = ramp_image();
  for (int level : {0, 1, 6}) {
    const depth_frame_t m = to_lcm(img, level, "cam");
    EXPECT_EQ(m.encoding, level ? +depth_frame_t::ENCODING_ZLIB_U16LE : +depth_frame_t::ENCODING_RAW_U16LE);
    DepthImage back;
    std::string error;
    ASSERT_TRUE(decode_image(encode(m), back, error)) << error;
    EXPECT_EQ(back.depth, img.depth);
    EXPECT_EQ(back.utime, img.utime);
    EXPECT_EQ(back.seq, img.seq);
    EXPECT_EQ(back.K.width, 64);
    EXPECT_FLOAT_EQ(static_cast<float>(back.K.cx), 31.5f);
    EXPECT_FLOAT_EQ(static_cast<float>(back.depth_scale), 0.001f);
  }
}

TEST(Codec, RawIsLittleEndian) {
  DepthImage img = ramp_image(4, 2);
  img.depth[0] = 0x1234;
  const depth_frame_t m = to_lcm(img, 0);
  EXPECT_EQ(m.data[0], 0x34);
  EXPECT_EQ(m.data[1], 0x12);
}

TEST(Codec, TruncatedZlibIsRejected) {
  depth_frame_t m = to_lcm(ramp_image(), 1);
  m.data.resize(m.data.size() / 2);
  m.data_size = static_cast<int32_t>(m.data.size());
  DepthImage back;
  std::string error;
  EXPECT_FALSE(decode_image(encode(m), back, error));
  EXPECT_NE(error.find("truncated"), std::string::npos) << error;
}

TEST(Codec, CorruptZlibIsRejected) {
  depth_frame_t m = to_lcm(ramp_image(), 1);
  for (size_t i = 2; i < m.data.size(); i += 3) m.data[i] ^= 0x5A;
  DepthImage back;
  std::string error;
  EXPECT_FALSE(decode_image(encode(m), back, error));
}

TEST(Codec, ZlibBombIsCappedAtDeclaredSize) {
  DepthImage big = ramp_image(640, 480);
  depth_frame_t m = to_lcm(big, 1);
  m.width = 64;
  m.height = 48;
  m.uncompressed_size = 64 * 48 * 2;  // the stream inflates to far more than declared
  DepthImage back;
  std::string error;
  EXPECT_FALSE(decode_image(encode(m), back, error));
  EXPECT_NE(error.find("beyond"), std::string::npos) << error;
}

TEST(Codec, ValidationFailures) {
  const DepthImage img = ramp_image();
  auto expect_rejected = [](depth_frame_t m, const std::string& what) {
    DepthImage back;
    std::string error;
    EXPECT_FALSE(decode_image(encode(m), back, error)) << what;
    EXPECT_FALSE(error.empty()) << what;
  };
  depth_frame_t m = to_lcm(img, 0);
  m.width = 65;
  expect_rejected(m, "size mismatch");
  m = to_lcm(img, 0);
  m.width = 5000;
  expect_rejected(m, "width beyond cap");
  m = to_lcm(img, 0);
  m.fx = NAN;
  expect_rejected(m, "NaN intrinsics");
  m = to_lcm(img, 0);
  m.depth_scale = 0;
  expect_rejected(m, "zero depth scale");
  m = to_lcm(img, 0);
  m.encoding = 7;
  expect_rejected(m, "unknown encoding");
  m = to_lcm(img, 0);
  m.data.resize(100);
  m.data_size = 100;
  expect_rejected(m, "short raw data");
  DepthImage zero = img;
  std::fill(zero.depth.begin(), zero.depth.end(), 0);
  expect_rejected(to_lcm(zero, 1), "all-zero depth");
}

TEST(Codec, DeclaredArraySizeBeyondMessageIsRejectedBeforeAllocation) {
  std::vector<uint8_t> buf = encode(to_lcm(ramp_image(), 1));
  // data_size sits at byte 61 (see lcm_bridge.cpp); claim 2 GB.
  buf[61] = 0x7F;
  buf[62] = buf[63] = buf[64] = 0xFF;
  depth_frame_t m;
  std::string error;
  EXPECT_FALSE(decode_message(buf.data(), buf.size(), m, error));
  EXPECT_NE(error.find("beyond"), std::string::npos) << error;
  EXPECT_TRUE(m.data.empty());
}

TEST(Codec, OrganizedCloudAndMats) {
  DepthImage img = ramp_image();
  const int u = 40, v = 10;
  img.depth[static_cast<size_t>(v) * img.K.width + u] = 2000;
  const auto cloud = organized_cloud(img);
  ASSERT_EQ(cloud->width, 64u);
  ASSERT_EQ(cloud->height, 48u);
  EXPECT_FALSE(cloud->is_dense);
  const auto& p = cloud->at(u, v);
  EXPECT_FLOAT_EQ(p.z, 2.0f);
  EXPECT_NEAR(p.x, (u - 31.5) / 52.5 * 2.0, 1e-5);
  EXPECT_NEAR(p.y, (v - 23.5) / 52.5 * 2.0, 1e-5);
  EXPECT_TRUE(std::isnan(cloud->at(5, 0).z));  // depth 0
  const cv::Mat m = depth_metres_mat(img);
  EXPECT_FLOAT_EQ(m.at<float>(v, u), 2.0f);
  EXPECT_TRUE(std::isnan(m.at<float>(0, 5)));
  EXPECT_EQ(depth_raw_mat(img).at<uint16_t>(v, u), 2000);
}

TEST(Codec, ScaleIntrinsicsKeepsPixelCentres) {
  const Intrinsics K{640, 480, 525, 525, 319.5, 239.5};
  const Intrinsics h = scale_intrinsics(K, 320, 240);
  EXPECT_DOUBLE_EQ(h.fx, 262.5);
  EXPECT_DOUBLE_EQ(h.cx, 159.5);
  EXPECT_DOUBLE_EQ(h.cy, 119.5);
}
