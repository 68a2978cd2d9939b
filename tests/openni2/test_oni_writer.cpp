// The .oni writer, proven by OpenNI2's own file player: every frame written
// comes back bit-exact, in order, with its timestamp, video mode and field of view.
#include "drivers/openni2/oni_writer.hpp"

#include <OpenNI.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

namespace {

stairs::DepthImage synthetic_frame(int w, int h, int i) {
  stairs::DepthImage img;
  img.K = {w, h, 0.5 * w / std::tan(0.5 * 1.0144686), 0.5 * h / std::tan(0.5 * 0.7898094), w / 2.0 - 0.5,
           h / 2.0 - 0.5};
  img.depth_scale = 0.001;
  img.utime = 1'700'000'000'000'000 + i * 33'333;
  img.seq = i;
  img.depth.resize(static_cast<size_t>(w) * h);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)  // every bit pattern matters: holes, near, far, > 10 m
      img.depth[static_cast<size_t>(v) * w + u] =
          static_cast<uint16_t>(((u + 7 * v) % 13 == 0) ? 0 : 400 + ((u * 131 + v * 17 + i * 1009) % 65000));
  return img;
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("stairs_openni2_" + std::to_string(getpid()) + "_" + name))
      .string();
}

class OpenNI2Env : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_EQ(openni::OpenNI::initialize(), openni::STATUS_OK) << openni::OpenNI::getExtendedError(); }
  void TearDown() override { openni::OpenNI::shutdown(); }
};

// Plays `path` through OpenNI2 and returns the frames read (never blocks: waits with a timeout).
struct Played {
  std::vector<std::vector<uint16_t>> depth;
  std::vector<int> index;
  std::vector<uint64_t> timestamp_us;
  openni::VideoMode mode;
  float hfov = 0, vfov = 0;
};

Played play(const std::string& path, size_t expected) {
  Played out;
  openni::Device dev;
  EXPECT_EQ(dev.open(path.c_str()), openni::STATUS_OK) << openni::OpenNI::getExtendedError();
  EXPECT_TRUE(dev.isFile());
  openni::PlaybackControl* pb = dev.getPlaybackControl();
  EXPECT_NE(pb, nullptr);
  if (!pb) return out;
  // Repeat on: the (n+1)-th read must be frame 1 again, which proves there
  // are exactly n frames. (With repeat off OpenNI2's player thread spins
  // unlocked over its stream list after the end and races with destroy().)
  EXPECT_EQ(pb->setRepeatEnabled(true), openni::STATUS_OK);
  EXPECT_EQ(pb->setSpeed(-1.0f), openni::STATUS_OK);  // manual: one frame per read, none dropped
  openni::VideoStream depth;
  EXPECT_EQ(depth.create(dev, openni::SENSOR_DEPTH), openni::STATUS_OK) << openni::OpenNI::getExtendedError();
  EXPECT_EQ(pb->getNumberOfFrames(depth), static_cast<int>(expected));
  EXPECT_EQ(depth.start(), openni::STATUS_OK);
  out.mode = depth.getVideoMode();
  out.hfov = depth.getHorizontalFieldOfView();
  out.vfov = depth.getVerticalFieldOfView();
  openni::VideoStream* streams[] = {&depth};
  for (size_t tries = 0; tries < expected + 5 && out.depth.size() < expected + 1; ++tries) {
    int ready = -1;
    if (openni::OpenNI::waitForAnyStream(streams, 1, &ready, 2000) != openni::STATUS_OK) break;
    openni::VideoFrameRef f;
    if (depth.readFrame(&f) != openni::STATUS_OK) break;
    const auto* px = static_cast<const uint16_t*>(f.getData());
    out.depth.emplace_back(px, px + f.getDataSize() / 2);
    out.index.push_back(f.getFrameIndex());
    out.timestamp_us.push_back(f.getTimestamp());
  }
  depth.stop();
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // see OpenNICamera::close()
  depth.destroy();
  dev.close();
  return out;
}

TEST_F(OpenNI2Env, OniWriterFramesPlayBackBitExact) {
  const int w = 160, h = 120, n = 12;
  const std::string path = temp_path("writer.oni");
  std::vector<stairs::DepthImage> frames;
  {
    stairs::OniWriter writer(path, w, h, 30);
    for (int i = 0; i < n; ++i) {
      frames.push_back(synthetic_frame(w, h, i));
      writer.write(frames.back());
    }
    EXPECT_FALSE(std::filesystem::exists(path)) << "complete before close()";
    writer.close();
  }
  ASSERT_TRUE(std::filesystem::exists(path));
  const Played p = play(path, n);
  ASSERT_EQ(p.depth.size(), static_cast<size_t>(n + 1));
  EXPECT_EQ(p.index[n], 1) << "frame " << n + 1 << " read: the recording has more than " << n << " frames";
  EXPECT_EQ(p.mode.getResolutionX(), w);
  EXPECT_EQ(p.mode.getResolutionY(), h);
  EXPECT_EQ(p.mode.getFps(), 30);
  EXPECT_EQ(p.mode.getPixelFormat(), openni::PIXEL_FORMAT_DEPTH_1_MM);
  EXPECT_NEAR(p.hfov, 1.0144686, 1e-5);
  EXPECT_NEAR(p.vfov, 0.7898094, 1e-5);
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(p.index[i], i + 1);
    EXPECT_EQ(p.timestamp_us[i], static_cast<uint64_t>(i * 33'333));
    EXPECT_TRUE(p.depth[i] == frames[i].depth) << "frame " << i << " differs";
  }
  std::remove(path.c_str());
}

TEST_F(OpenNI2Env, OniWriterConvertsDepthScaleToMillimetres) {
  const int w = 32, h = 24;
  const std::string path = temp_path("scale.oni");
  stairs::DepthImage img = synthetic_frame(w, h, 0);
  std::vector<uint16_t> mm(img.depth.size());
  for (size_t i = 0; i < img.depth.size(); ++i) {
    img.depth[i] = static_cast<uint16_t>(img.depth[i] % 20000);  // units of 0.1 mm
    mm[i] = static_cast<uint16_t>(std::lround(img.depth[i] * 0.1));
  }
  img.depth_scale = 0.0001;
  {
    stairs::OniWriter writer(path, w, h, 30);
    writer.write(img);
  }
  const Played p = play(path, 1);
  ASSERT_EQ(p.depth.size(), 2u);
  EXPECT_TRUE(p.depth[0] == mm);
  std::remove(path.c_str());
}

TEST(OpenNI2OniWriter, RejectsWrongSizeAndBackwardsTime) {
  const std::string path = temp_path("reject.oni");
  stairs::OniWriter writer(path, 32, 24, 30);
  EXPECT_THROW(writer.write(synthetic_frame(31, 24, 0)), std::invalid_argument);
  writer.write(synthetic_frame(32, 24, 5));
  EXPECT_THROW(writer.write(synthetic_frame(32, 24, 4)), std::invalid_argument);
  writer.close();
  EXPECT_TRUE(std::filesystem::exists(path));
  std::remove(path.c_str());
}

TEST(OpenNI2OniWriter, NoFramesLeavesNoFile) {
  const std::string path = temp_path("empty.oni");
  stairs::OniWriter writer(path, 32, 24, 30);
  EXPECT_THROW(writer.close(), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
}

}  // namespace
