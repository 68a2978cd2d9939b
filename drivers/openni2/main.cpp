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
#include <stdexcept>
#include <string>
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

// OpenNI2 initialised for the life of the object (shutdown on every exit path).
class OpenNISession {
 public:
  OpenNISession() {
    if (openni::OpenNI::initialize() != openni::STATUS_OK)
      throw std::runtime_error(std::string("OpenNI2 failed to initialise: ") + openni::OpenNI::getExtendedError());
  }
  ~OpenNISession() { openni::OpenNI::shutdown(); }
  OpenNISession(const OpenNISession&) = delete;
  OpenNISession& operator=(const OpenNISession&) = delete;
};

struct DriverOptions {
  stairs::CameraConfig camera;
  int zlib_level = kDefaultZlibLevel;
  long max_frames = 0;
  bool publish = true;
  std::string log, channel;
};

// Checks the options; throws std::invalid_argument naming the bad one.
DriverOptions driver_options(const stairs::Options& opt) {
  DriverOptions d;
  if (!parse_mode(opt.get("mode"), d.camera))
    throw std::invalid_argument("--mode must be 640x480, 320x240 or 160x120, got '" + opt.get("mode") + "'");
  d.camera.uri = opt.get("uri");
  d.camera.oni_file = opt.get("oni");
  d.camera.fast = opt.flag("fast");
  d.camera.loop = opt.flag("loop");
  d.camera.color = opt.flag("color");
  d.camera.frame_timeout_ms = opt.get_int("timeout-ms");
  d.zlib_level = opt.get_int("zlib");
  d.max_frames = static_cast<long>(opt.get_double("max-frames"));
  d.publish = !opt.flag("no-publish");
  d.log = opt.get("log");
  d.channel = opt.get("depth-channel");
  if (d.zlib_level < 0 || d.zlib_level > 9 || d.camera.frame_timeout_ms <= 0 || d.max_frames < 0)
    throw std::invalid_argument("--zlib must be 0..9, --timeout-ms > 0, --max-frames >= 0");
  if (!d.camera.uri.empty() && !d.camera.oni_file.empty()) throw std::invalid_argument("give --uri or --oni, not both");
  if (!d.publish && d.log.empty()) throw std::invalid_argument("--no-publish without --log would do nothing");
  return d;
}

// The driver loop: read a frame, convert, publish and/or log it, count what was
// dropped; a device that stops delivering is closed and reopened once a second.
class Driver {
 public:
  Driver(const DriverOptions& o, lcm::LCM& lcm, stairs::StatusReporter& status)
      : o_(o), lcm_(lcm), status_(status), camera_(o.camera) {}

  // Opens the camera and the log; false (said on stderr) if either fails.
  bool open() {
    std::string error;
    if (!camera_.open(error)) return fail(error);
    const int n = camera_.recording_frames();
    std::fprintf(stderr, "%s: streaming %s%s\n", kName, camera_.description().c_str(),
                 n > 0 ? (" (" + std::to_string(n) + " frames)").c_str() : "");
    try {
      if (!o_.log.empty()) log_.emplace(o_.log);
    } catch (const std::exception& e) {
      return fail(e.what());
    }
    return true;
  }

  // Until a stop signal, the recording's end or --max-frames; 0, or 1 when the log could not be closed.
  int run() {
    openni::VideoFrameRef depth, color;
    while (!stairs::stop_requested()) {
      status_.tick();
      if (!camera_.is_open()) {
        reconnect();
        continue;
      }
      const auto r = camera_.read(depth, color);
      if (r == stairs::OpenNICamera::Read::End) break;
      if (r == stairs::OpenNICamera::Read::Timeout) {
        lose_device();
        continue;
      }
      const int index = depth.getFrameIndex();
      if (!forward(depth, color)) continue;
      if (o_.max_frames > 0 && ++frames_ >= o_.max_frames) break;
      if (camera_.recording_frames() > 0 && !o_.camera.loop && index >= camera_.recording_frames()) break;
    }
    return close();
  }

 private:
  bool fail(const std::string& error) {
    std::fprintf(stderr, "%s: %s\n", kName, error.c_str());
    camera_.close();
    return false;
  }

  // Lost: retry once per kReconnectPeriod_s, saying so at every attempt.
  void reconnect() {
    const double lost_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - lost_since_).count();
    if (lost_s < kReconnectPeriod_s * reconnect_attempts_) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      return;
    }
    ++reconnect_attempts_;
    std::string error;
    if (camera_.open(error)) {
      std::fprintf(stderr, "%s: reconnected to %s after %.1f s\n", kName, camera_.description().c_str(), lost_s);
      last_index_ = -1;
    } else {
      std::fprintf(stderr, "%s: still no frames (%.0f s): reconnect attempt %d failed: %s\n", kName, lost_s,
                   reconnect_attempts_, error.c_str());
    }
  }

  void lose_device() {
    const int ms = o_.camera.frame_timeout_ms;
    std::fprintf(stderr, "%s: no depth frame from %s for %d ms; closing it and reconnecting\n", kName,
                 camera_.description().c_str(), ms);
    status_.dropped("no frame for " + std::to_string(ms) + " ms from " + camera_.description());
    camera_.close();
    lost_since_ = std::chrono::steady_clock::now();
    reconnect_attempts_ = 0;
  }

  // Frames the device delivered while we were busy (its index jumped), and
  // those a looping recording's wrap replaced, are dropped: counted.
  void count_skipped(int index) {
    if (last_index_ >= 0 && index > last_index_ + 1)
      for (int k = last_index_ + 1; k < index; ++k) status_.dropped("frame " + std::to_string(k) + " not read in time");
    // A looping recording starts again at 1; OpenNI's player delivers the
    // rewound first frame right after the last one, which may replace it.
    if (last_index_ >= 0 && index <= last_index_ && camera_.recording_frames() > 0)
      for (int k = last_index_ + 1; k <= camera_.recording_frames(); ++k)
        status_.dropped("frame " + std::to_string(k) + " replaced at the loop's wrap");
    last_index_ = index;
  }

  // Converts one frame and publishes and/or logs it; false when it was invalid (counted).
  bool forward(const openni::VideoFrameRef& depth, const openni::VideoFrameRef& color) {
    const auto t0 = std::chrono::steady_clock::now();
    status_.received();
    count_skipped(depth.getFrameIndex());
    const openni::VideoMode mode = depth.getVideoMode();
    if (mode.getPixelFormat() != openni::PIXEL_FORMAT_DEPTH_1_MM) {
      status_.invalid("depth pixel format " + std::to_string(mode.getPixelFormat()) + " is not DEPTH_1_MM");
      return false;
    }
    try {
      const stairs::Intrinsics K =
          stairs::intrinsics_from_fov(depth.getWidth(), depth.getHeight(), camera_.hfov_rad(), camera_.vfov_rad());
      const stairs::FrameBuffer d{depth.getData(), depth.getWidth(), depth.getHeight(), depth.getStrideInBytes()};
      const bool with_color = color.isValid();
      const stairs::FrameBuffer c{with_color ? color.getData() : nullptr, with_color ? color.getWidth() : 0,
                                  with_color ? color.getHeight() : 0, with_color ? color.getStrideInBytes() : 0};
      const uint64_t device_us = depth.getTimestamp();
      const int64_t utime = clock_.to_utime(device_us, stairs::now_utime());
      const stairs::depth_frame_t msg = stairs::depth_frame_from_openni(
          d, K, utime, static_cast<int64_t>(device_us), seq_++, o_.zlib_level, with_color ? &c : nullptr);
      if (o_.publish) lcm_.publish(o_.channel, &msg);
      if (log_) log_->write_message(o_.channel, utime, msg);
    } catch (const std::exception& e) {
      status_.invalid(e.what());
      return false;
    }
    status_.published(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    return true;
  }

  int close() {
    camera_.close();
    int rc = 0;
    try {
      if (log_) log_->close();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", kName, e.what());
      rc = 1;
    }
    status_.final_report();
    return rc;
  }

  const DriverOptions& o_;
  lcm::LCM& lcm_;
  stairs::StatusReporter& status_;
  stairs::OpenNICamera camera_;
  std::optional<stairs::LogWriter> log_;
  stairs::DeviceClock clock_;
  int last_index_ = -1;
  int32_t seq_ = 0;
  long frames_ = 0;
  std::chrono::steady_clock::time_point lost_since_ = std::chrono::steady_clock::now();
  int reconnect_attempts_ = 0;
};

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
  DriverOptions o;
  try {
    o = driver_options(opt);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "%s: %s\n", kName, e.what());
    return 2;
  }
  if (!o.camera.oni_file.empty() && !std::filesystem::is_regular_file(o.camera.oni_file)) {
    std::fprintf(stderr, "%s: cannot open recording %s: no such file\n", kName, o.camera.oni_file.c_str());
    return 1;
  }
  stairs::install_stop_signals();
  lcm::LCM lcm(opt.get("lcm-url"));
  if (!lcm.good()) {
    std::fprintf(stderr, "%s: cannot open LCM URL '%s'\n", kName, opt.get("lcm-url").c_str());
    return 1;
  }
  stairs::StatusReporter status(&lcm, kName, opt.get("status-channel"), opt.flag("verbose"));
  try {
    const OpenNISession session;
    Driver driver(o, lcm, status);
    return driver.open() ? driver.run() : 1;
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "%s: %s\n", kName, e.what());
    return 1;
  }
}
