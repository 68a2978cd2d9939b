// stairs-openni2: depth frames from an OpenNI2 device or .oni recording,
// published as depth_frame_t on STAIRS_DEPTH and/or written to an LCM log.
#include "common/daemon.hpp"
#include "common/lcm_log.hpp"
#include "drivers/openni2/frame_convert.hpp"
#include "drivers/openni2/openni_camera.hpp"

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <thread>

namespace {

constexpr const char* kName = "stairs-openni2";
constexpr int kDefaultZlibLevel = 1;        // see README: measured size and CPU per level
constexpr double kReconnectPeriod_s = 1.0;  // s between attempts to reopen a lost device

bool parse_mode(const std::string& s, stairs::CameraConfig& c) {
  if (s == "640x480") c.width = 640, c.height = 480, c.fps = 30;
  else if (s == "320x240") c.width = 320, c.height = 240, c.fps = 30;
  else if (s == "160x120") c.width = 160, c.height = 120, c.fps = 30;
  else return false;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  stairs::Options opt(kName,
                      "Publishes depth frames (mm, intrinsics from the field of view) of an OpenNI2 camera\n"
                      "(Kinect v1, Xtion, Astra) or of an .oni recording as depth_frame_t.");
  opt.add("uri", "URI", "open this OpenNI2 device instead of the first one")
      .add("oni", "FILE", "play this .oni recording instead of a device")
      .add("fast", "", "recordings: as fast as frames are consumed, none dropped (default: recorded speed)")
      .add("loop", "", "recordings: start again at the end")
      .add("mode", "WxH", "depth mode of a device: 640x480, 320x240 or 160x120 (30 Hz)", "640x480")
      .add("color", "", "also publish the registered RGB888 colour image")
      .add("zlib", "LEVEL", "zlib level of the depth data, 0 = raw", std::to_string(kDefaultZlibLevel))
      .add("lcm-url", "URL", "LCM URL (empty = LCM default)", "")
      .add("depth-channel", "NAME", "depth channel (as every program names it)", "STAIRS_DEPTH")
      .add("status-channel", "NAME", "status channel", "STAIRS_STATUS")
      .add("log", "FILE", "also record the frames to this LCM log (FILE.partial until a clean stop)")
      .add("no-publish", "", "do not publish, only record (--log)")
      .add("max-frames", "N", "stop after N frames (0 = no limit)", "0")
      .add("timeout-ms", "MS", "ms without a frame before a device counts as lost", "2000")
      .add("verbose", "", "print the status line every second even when stderr is not a terminal");
  opt.parse(argc, argv);

  stairs::CameraConfig cfg;
  if (!parse_mode(opt.get("mode"), cfg)) {
    std::fprintf(stderr, "%s: --mode must be 640x480, 320x240 or 160x120, got '%s'\n", kName, opt.get("mode").c_str());
    return 2;
  }
  cfg.uri = opt.get("uri");
  cfg.oni_file = opt.get("oni");
  if (!cfg.oni_file.empty() && !std::filesystem::is_regular_file(cfg.oni_file)) {
    std::fprintf(stderr, "%s: cannot open recording %s: no such file\n", kName, cfg.oni_file.c_str());
    return 1;
  }
  cfg.fast = opt.flag("fast");
  cfg.loop = opt.flag("loop");
  cfg.color = opt.flag("color");
  cfg.frame_timeout_ms = opt.get_int("timeout-ms");
  const int zlib_level = opt.get_int("zlib");
  const long max_frames = static_cast<long>(opt.get_double("max-frames"));
  const bool publish = !opt.flag("no-publish");
  if (zlib_level < 0 || zlib_level > 9 || cfg.frame_timeout_ms <= 0 || max_frames < 0) {
    std::fprintf(stderr, "%s: --zlib must be 0..9, --timeout-ms > 0, --max-frames >= 0\n", kName);
    return 2;
  }
  if (!cfg.uri.empty() && !cfg.oni_file.empty()) {
    std::fprintf(stderr, "%s: give --uri or --oni, not both\n", kName);
    return 2;
  }
  if (!publish && !opt.has("log")) {
    std::fprintf(stderr, "%s: --no-publish without --log would do nothing\n", kName);
    return 2;
  }

  stairs::install_stop_signals();
  lcm::LCM lcm(opt.get("lcm-url"));
  if (!lcm.good()) {
    std::fprintf(stderr, "%s: cannot open LCM URL '%s'\n", kName, opt.get("lcm-url").c_str());
    return 1;
  }
  stairs::StatusReporter status(&lcm, kName, opt.get("status-channel"), opt.flag("verbose"));

  if (openni::OpenNI::initialize() != openni::STATUS_OK) {
    std::fprintf(stderr, "%s: OpenNI2 failed to initialise: %s\n", kName, openni::OpenNI::getExtendedError());
    return 1;
  }
  int rc = 0;
  {
    stairs::OpenNICamera camera(cfg);
    std::string error;
    if (!camera.open(error)) {
      std::fprintf(stderr, "%s: %s\n", kName, error.c_str());
      camera.close();
      openni::OpenNI::shutdown();
      return 1;
    }
    std::fprintf(stderr, "%s: streaming %s%s\n", kName, camera.description().c_str(),
                 camera.recording_frames() > 0 ? (" (" + std::to_string(camera.recording_frames()) + " frames)").c_str()
                                               : "");
    std::optional<stairs::LogWriter> log;
    try {
      if (opt.has("log")) log.emplace(opt.get("log"));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", kName, e.what());
      camera.close();
      openni::OpenNI::shutdown();
      return 1;
    }

    const std::string channel = opt.get("depth-channel");
    stairs::DeviceClock clock;
    int last_index = -1;
    int32_t seq = 0;
    long frames = 0;
    auto lost_since = std::chrono::steady_clock::now();
    int reconnect_attempts = 0;
    openni::VideoFrameRef depth, color;
    while (!stairs::stop_requested()) {
      status.tick();
      if (!camera.is_open()) {  // lost: retry, saying so at every attempt
        const double lost_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - lost_since).count();
        if (lost_s < kReconnectPeriod_s * reconnect_attempts) {
          std::this_thread::sleep_for(std::chrono::milliseconds(50));
          continue;
        }
        ++reconnect_attempts;
        if (camera.open(error)) {
          std::fprintf(stderr, "%s: reconnected to %s after %.1f s\n", kName, camera.description().c_str(), lost_s);
          last_index = -1;
        } else {
          std::fprintf(stderr, "%s: still no frames (%.0f s): reconnect attempt %d failed: %s\n", kName, lost_s,
                       reconnect_attempts, error.c_str());
        }
        continue;
      }
      const auto r = camera.read(depth, color);
      if (r == stairs::OpenNICamera::Read::End) break;
      if (r == stairs::OpenNICamera::Read::Timeout) {
        std::fprintf(stderr, "%s: no depth frame from %s for %d ms; closing it and reconnecting\n", kName,
                     camera.description().c_str(), cfg.frame_timeout_ms);
        status.dropped("no frame for " + std::to_string(cfg.frame_timeout_ms) + " ms from " + camera.description());
        camera.close();
        lost_since = std::chrono::steady_clock::now();
        reconnect_attempts = 0;
        continue;
      }
      const auto t0 = std::chrono::steady_clock::now();
      status.received();
      const int index = depth.getFrameIndex();
      if (last_index >= 0 && index > last_index + 1)
        for (int k = last_index + 1; k < index; ++k) status.dropped("frame " + std::to_string(k) + " not read in time");
      // A looping recording starts again at 1; OpenNI's player delivers the
      // rewound first frame right after the last one, which may replace it.
      if (last_index >= 0 && index <= last_index && camera.recording_frames() > 0)
        for (int k = last_index + 1; k <= camera.recording_frames(); ++k)
          status.dropped("frame " + std::to_string(k) + " replaced at the loop's wrap");
      last_index = index;
      const openni::VideoMode mode = depth.getVideoMode();
      if (mode.getPixelFormat() != openni::PIXEL_FORMAT_DEPTH_1_MM) {
        status.invalid("depth pixel format " + std::to_string(mode.getPixelFormat()) + " is not DEPTH_1_MM");
        continue;
      }
      try {
        const stairs::Intrinsics K =
            stairs::intrinsics_from_fov(depth.getWidth(), depth.getHeight(), camera.hfov_rad(), camera.vfov_rad());
        const stairs::FrameBuffer d{depth.getData(), depth.getWidth(), depth.getHeight(), depth.getStrideInBytes()};
        const stairs::FrameBuffer c{color.isValid() ? color.getData() : nullptr, color.isValid() ? color.getWidth() : 0,
                                    color.isValid() ? color.getHeight() : 0,
                                    color.isValid() ? color.getStrideInBytes() : 0};
        const uint64_t device_us = depth.getTimestamp();
        const int64_t utime = clock.to_utime(device_us, stairs::now_utime());
        const stairs::depth_frame_t msg = stairs::depth_frame_from_openni(
            d, K, utime, static_cast<int64_t>(device_us), seq++, zlib_level, color.isValid() ? &c : nullptr);
        if (publish) lcm.publish(channel, &msg);
        if (log) log->write_message(channel, utime, msg);
      } catch (const std::exception& e) {
        status.invalid(e.what());
        continue;
      }
      status.published(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      if (max_frames > 0 && ++frames >= max_frames) break;
      if (camera.recording_frames() > 0 && !cfg.loop && index >= camera.recording_frames()) break;
    }
    camera.close();
    try {
      if (log) log->close();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", kName, e.what());
      rc = 1;
    }
    status.final_report();
  }
  openni::OpenNI::shutdown();
  return rc;
}
