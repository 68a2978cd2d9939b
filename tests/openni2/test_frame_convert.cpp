// OpenNI frame buffer + field of view -> depth_frame_t: intrinsics, byte
// order, row stride, colour, and the device-clock mapping.
#include "common/lcm_bridge.hpp"
#include "drivers/openni2/frame_convert.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace stairs;

namespace {
constexpr double kHfov = 1.0144686;  // rad, Kinect v1 depth (58.1 deg)
constexpr double kVfov = 0.7898094;  // rad (45.3 deg)
}  // namespace

TEST(OpenNI2FrameConvert, IntrinsicsFromFieldOfView) {
  const Intrinsics K = intrinsics_from_fov(640, 480, kHfov, kVfov);
  EXPECT_NEAR(K.fx, 320.0 / std::tan(kHfov / 2), 1e-9);
  EXPECT_NEAR(K.fy, 240.0 / std::tan(kVfov / 2), 1e-9);
  EXPECT_NEAR(K.fx, 575.8, 0.1);  // the Kinect v1 focal length OpenNI reports
  EXPECT_DOUBLE_EQ(K.cx, 319.5);
  EXPECT_DOUBLE_EQ(K.cy, 239.5);
  const Intrinsics q = intrinsics_from_fov(160, 120, kHfov, kVfov);
  EXPECT_NEAR(q.fx * 4, K.fx, 1e-9);  // same optics at a quarter of the resolution
  EXPECT_THROW(intrinsics_from_fov(640, 480, 0.0, kVfov), std::invalid_argument);
  EXPECT_THROW(intrinsics_from_fov(640, 480, kHfov, NAN), std::invalid_argument);
}

TEST(OpenNI2FrameConvert, PaddedRowsBecomeLittleEndianRowsWithoutPadding) {
  const int w = 5, h = 3, stride_px = 8;  // 3 pixels of padding per row
  std::vector<uint16_t> buf(static_cast<size_t>(stride_px) * h, 0xDEAD);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) buf[v * stride_px + u] = static_cast<uint16_t>(0x0102 * (v * w + u + 1));
  const Intrinsics K = intrinsics_from_fov(w, h, kHfov, kVfov);
  const depth_frame_t m =
      depth_frame_from_openni({buf.data(), w, h, stride_px * 2}, K, 1234567, 890, 42, 0);
  ASSERT_EQ(m.encoding, +depth_frame_t::ENCODING_RAW_U16LE);
  ASSERT_EQ(m.data_size, w * h * 2);
  for (int i = 0; i < w * h; ++i) {
    const uint16_t v = static_cast<uint16_t>(0x0102 * (i + 1));
    EXPECT_EQ(m.data[2 * i], v & 0xFF) << "low byte first, pixel " << i;
    EXPECT_EQ(m.data[2 * i + 1], v >> 8) << "high byte second, pixel " << i;
  }
  EXPECT_EQ(m.width, w);
  EXPECT_EQ(m.height, h);
  EXPECT_FLOAT_EQ(m.fx, static_cast<float>(K.fx));
  EXPECT_FLOAT_EQ(m.cy, 1.0f);
  EXPECT_FLOAT_EQ(m.depth_scale, 0.001f);
  EXPECT_EQ(m.utime, 1234567);
  EXPECT_EQ(m.device_timestamp_us, 890);
  EXPECT_EQ(m.seq, 42);
  EXPECT_EQ(m.color_encoding, +depth_frame_t::COLOR_NONE);
}

TEST(OpenNI2FrameConvert, ZlibAndColourSurviveEncodeAndDecode) {
  const int w = 64, h = 48;
  std::vector<uint16_t> depth(w * h);
  for (int i = 0; i < w * h; ++i) depth[i] = static_cast<uint16_t>(i % 7 ? 500 + i : 0);
  std::vector<uint8_t> rgb(static_cast<size_t>(w * 3 + 4) * h);  // 4 bytes row padding
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<uint8_t>(i * 31);
  const FrameBuffer color{rgb.data(), w, h, w * 3 + 4};
  const depth_frame_t m = depth_frame_from_openni({depth.data(), w, h, w * 2},
                                                  intrinsics_from_fov(w, h, kHfov, kVfov), 1, 1, 0, 6, &color);
  EXPECT_EQ(m.encoding, +depth_frame_t::ENCODING_ZLIB_U16LE);
  EXPECT_LT(m.data_size, w * h * 2);
  ASSERT_EQ(m.color_encoding, +depth_frame_t::COLOR_RGB8);
  ASSERT_EQ(m.color_size, w * h * 3);
  for (int v = 0; v < h; ++v)
    for (int i = 0; i < w * 3; ++i) ASSERT_EQ(m.color_data[v * w * 3 + i], rgb[v * (w * 3 + 4) + i]);

  std::vector<uint8_t> wire(m.getEncodedSize());
  m.encode(wire.data(), 0, static_cast<int>(wire.size()));
  depth_frame_t back;
  DepthImage img;
  std::string error;
  ASSERT_TRUE(decode_message(wire.data(), wire.size(), back, error)) << error;
  ASSERT_TRUE(from_lcm(back, img, error)) << error;
  EXPECT_EQ(img.depth, depth);
}

TEST(OpenNI2FrameConvert, RejectsInconsistentBuffers) {
  std::vector<uint16_t> d(100);
  const Intrinsics K = intrinsics_from_fov(10, 10, kHfov, kVfov);
  EXPECT_THROW(depth_frame_from_openni({d.data(), 10, 10, 19}, K, 0, 0, 0, 0), std::invalid_argument);
  EXPECT_THROW(depth_frame_from_openni({nullptr, 10, 10, 20}, K, 0, 0, 0, 0), std::invalid_argument);
  EXPECT_THROW(depth_frame_from_openni({d.data(), 10, 9, 20}, K, 0, 0, 0, 0), std::invalid_argument);
}

TEST(OpenNI2FrameConvert, DeviceClockKeepsDeviceSpacingAndResyncsOnJumpBack) {
  DeviceClock clock;
  EXPECT_EQ(clock.to_utime(5'000'000, 1'700'000'000'000'000), 1'700'000'000'000'000);
  // Host jitter does not matter: the device clock's spacing is kept exactly.
  EXPECT_EQ(clock.to_utime(5'033'333, 1'700'000'000'090'000), 1'700'000'000'033'333);
  EXPECT_EQ(clock.resyncs(), 0);
  // A recording that loops starts its clock again: re-anchored to the host clock.
  EXPECT_EQ(clock.to_utime(0, 1'700'000'001'000'000), 1'700'000'001'000'000);
  EXPECT_EQ(clock.to_utime(33'333, 1'700'000'001'050'000), 1'700'000'001'033'333);
  EXPECT_EQ(clock.resyncs(), 1);
}
