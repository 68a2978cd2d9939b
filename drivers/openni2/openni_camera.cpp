#include "drivers/openni2/openni_camera.hpp"

#include "common/daemon.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <thread>

namespace stairs {

using Clock = std::chrono::steady_clock;

// Runs OpenNI2 calls that take no timeout (Device::open, stream start/stop,
// close) and reports from a second thread when one does not return: a line
// every few seconds, and on SIGINT/SIGTERM an exit with code 3 (the log stays
// .partial: the close was not clean).
class BlockingCallWatch {
 public:
  static constexpr double kReportAfter_s = 3.0;
  static constexpr double kExitOnStopAfter_s = 2.0;

  BlockingCallWatch() : thread_([this] { watch(); }) {}
  ~BlockingCallWatch() {
    quit_ = true;
    thread_.join();
  }
  template <class F>
  auto run(const std::string& what, F&& f) {
    {
      std::lock_guard<std::mutex> lock(m_);
      what_ = what;
      since_ = Clock::now();
      busy_ = true;
    }
    auto result = f();
    busy_ = false;
    return result;
  }

 private:
  void watch() {
    double reported_s = 0.0;
    while (!quit_) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (!busy_) {
        reported_s = 0.0;
        continue;
      }
      std::lock_guard<std::mutex> lock(m_);
      const double blocked_s = std::chrono::duration<double>(Clock::now() - since_).count();
      if (stop_requested() && blocked_s > kExitOnStopAfter_s) {
        std::fprintf(stderr, "stairs-openni2: stop requested while %s has been blocked for %.0f s; exiting without a clean close\n",
                     what_.c_str(), blocked_s);
        std::_Exit(3);
      }
      if (blocked_s - reported_s > kReportAfter_s) {
        std::fprintf(stderr, "stairs-openni2: %s has not returned for %.0f s (device unplugged or hung?)\n",
                     what_.c_str(), blocked_s);
        reported_s = blocked_s;
      }
    }
  }

  std::mutex m_;
  std::string what_;
  Clock::time_point since_;
  std::atomic<bool> busy_{false}, quit_{false};
  std::thread thread_;
};

OpenNICamera::OpenNICamera(CameraConfig config)
    : config_(std::move(config)), watch_(std::make_unique<BlockingCallWatch>()) {}

OpenNICamera::~OpenNICamera() { close(); }

std::string OpenNICamera::description() const {
  if (!config_.oni_file.empty()) return "recording " + config_.oni_file;
  if (!opened_uri_.empty()) return "device " + opened_uri_;
  return config_.uri.empty() ? "the first OpenNI2 device" : "device " + config_.uri;
}

namespace {
std::string oni_error() {
  std::string e = openni::OpenNI::getExtendedError();
  while (!e.empty() && (e.front() == '\t' || e.front() == ' ')) e.erase(e.begin());
  while (!e.empty() && (e.back() == '\n' || e.back() == ' ')) e.pop_back();
  for (char& c : e)
    if (c == '\n') c = ' ';
  return e.empty() ? "no detail from OpenNI2" : e;
}

// The supported mode with this resolution in mm, preferring the requested rate.
bool pick_mode(const openni::SensorInfo* info, int width, int height, int fps, openni::PixelFormat format,
               openni::VideoMode& out) {
  if (!info) return false;
  const auto& modes = info->getSupportedVideoModes();
  bool found = false;
  for (int i = 0; i < modes.getSize(); ++i) {
    const openni::VideoMode& m = modes[i];
    if (m.getResolutionX() != width || m.getResolutionY() != height || m.getPixelFormat() != format) continue;
    if (!found || (m.getFps() == fps) || (out.getFps() != fps && m.getFps() > out.getFps())) out = m;
    found = true;
  }
  return found;
}
}  // namespace

// The device to open: the recording, the given URI, or the first device.
bool OpenNICamera::resolve_uri(std::string& uri, std::string& error) const {
  uri = config_.oni_file.empty() ? config_.uri : config_.oni_file;
  if (!uri.empty()) return true;
  openni::Array<openni::DeviceInfo> list;
  openni::OpenNI::enumerateDevices(&list);
  if (list.getSize() == 0) {
    error = "no OpenNI2 device found: tried the first device, OpenNI2 enumerated none (camera unplugged, no power, "
            "udev permissions, or no driver for it in the OpenNI2 Drivers directory)";
    return false;
  }
  uri = list[0].getUri();
  return true;
}

// A recording's playback: speed and repeat.
bool OpenNICamera::configure_playback(openni::Device& dev, const std::string& what, std::string& error) const {
  openni::PlaybackControl* pb = dev.getPlaybackControl();
  // With repeat off, OpenNI2's player thread spins over its stream list,
  // unlocked, once past the end, and destroying the stream races with it (a
  // crash in libOniFile seen here). So repeat is on whenever it costs
  // nothing: manual playback (--fast) waits for each read, and read() ends
  // the recording where the frame index wraps. At the recorded speed the
  // rewound first frame would replace the last one, so there repeat follows
  // --loop, and close() waits for the player to idle instead.
  if (!pb || pb->setSpeed(config_.fast ? -1.0f : 1.0f) != openni::STATUS_OK ||
      pb->setRepeatEnabled(config_.loop || config_.fast) != openni::STATUS_OK) {
    error = "cannot control playback of " + what + ": " + oni_error();
    return false;
  }
  return true;
}

// The depth stream, in the configured mode on a device (a recording has its own).
bool OpenNICamera::create_depth(openni::Device& dev, bool file, const std::string& what, std::string& error) {
  if (!dev.hasSensor(openni::SENSOR_DEPTH) ||
      watch_->run("VideoStream::create(depth)", [&] { return depth_.create(dev, openni::SENSOR_DEPTH); }) !=
          openni::STATUS_OK) {
    error = what + " has no depth stream: " + oni_error();
    return false;
  }
  if (file) return true;
  openni::VideoMode mode;
  if (!pick_mode(dev.getSensorInfo(openni::SENSOR_DEPTH), config_.width, config_.height, config_.fps,
                 openni::PIXEL_FORMAT_DEPTH_1_MM, mode)) {
    error = what + " has no " + std::to_string(config_.width) + "x" + std::to_string(config_.height) + " depth mode in mm";
    depth_.destroy();
    return false;
  }
  if (depth_.setVideoMode(mode) != openni::STATUS_OK) {
    error = "cannot set the depth mode of " + what + ": " + oni_error();
    depth_.destroy();
    return false;
  }
  depth_.setMirroringEnabled(false);  // unsupported on some devices: their images are not mirrored
  return true;
}

// The optional colour stream, registered to depth; without one, depth only (said once).
void OpenNICamera::start_color(openni::Device& dev, bool file, const std::string& what) {
  if (config_.color && dev.hasSensor(openni::SENSOR_COLOR) &&
      watch_->run("VideoStream::create(colour)", [&] { return color_.create(dev, openni::SENSOR_COLOR); }) ==
          openni::STATUS_OK) {
    if (!file) {
      openni::VideoMode mode;
      if (pick_mode(dev.getSensorInfo(openni::SENSOR_COLOR), config_.width, config_.height, config_.fps,
                    openni::PIXEL_FORMAT_RGB888, mode))
        color_.setVideoMode(mode);
      color_.setMirroringEnabled(false);
      if (dev.isImageRegistrationModeSupported(openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR))
        dev.setImageRegistrationMode(openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR);
      dev.setDepthColorSyncEnabled(true);
    }
    color_on_ = watch_->run("VideoStream::start(colour)", [&] { return color_.start(); }) == openni::STATUS_OK &&
                color_.getVideoMode().getPixelFormat() == openni::PIXEL_FORMAT_RGB888;
  }
  if (config_.color && !color_on_)
    std::fprintf(stderr, "stairs-openni2: %s has no usable RGB888 colour stream; publishing depth only\n",
                 what.c_str());
}

bool OpenNICamera::open(std::string& error) {
  close();
  auto dev = std::make_unique<openni::Device>();
  const bool file = !config_.oni_file.empty();
  std::string uri;
  if (!resolve_uri(uri, error)) return false;
  const std::string what = file ? "recording " + uri : "device " + uri;
  if (watch_->run("Device::open(" + uri + ")", [&] { return dev->open(uri.c_str()); }) != openni::STATUS_OK) {
    error = "cannot open " + what + ": " + oni_error();
    return false;
  }
  if (file && !configure_playback(*dev, what, error)) return false;
  if (!create_depth(*dev, file, what, error)) return false;
  start_color(*dev, file, what);
  if (watch_->run("VideoStream::start(depth)", [&] { return depth_.start(); }) != openni::STATUS_OK) {
    error = "cannot start the depth stream of " + what + ": " + oni_error();
    depth_.destroy();
    return false;
  }
  hfov_rad_ = depth_.getHorizontalFieldOfView();
  vfov_rad_ = depth_.getVerticalFieldOfView();
  recording_frames_ = file ? dev->getPlaybackControl()->getNumberOfFrames(depth_) : 0;
  opened_uri_ = uri;
  last_index_ = -1;
  device_ = std::move(dev);
  return true;
}

void OpenNICamera::close() {
  if (!device_) return;
  last_color_.release();
  if (color_.isValid()) {
    watch_->run("VideoStream::stop(colour)", [&] { color_.stop(); return 0; });
    color_.destroy();
  }
  color_on_ = false;
  watch_->run("VideoStream::stop(depth)", [&] { depth_.stop(); return 0; });
  // OpenNI2's file player walks its stream list without a lock; once no
  // stream is started it does so only every 10 ms, between sleeps.
  if (!config_.oni_file.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  depth_.destroy();
  watch_->run("Device::close(" + opened_uri_ + ")", [&] { device_->close(); return 0; });
  device_.reset();
}

OpenNICamera::Read OpenNICamera::read(openni::VideoFrameRef& depth, openni::VideoFrameRef& color) {
  const bool file = !config_.oni_file.empty();
  openni::VideoStream* streams[] = {&depth_};
  int ready = -1;
  if (openni::OpenNI::waitForAnyStream(streams, 1, &ready, config_.frame_timeout_ms) != openni::STATUS_OK)
    return file && !config_.loop ? Read::End : Read::Timeout;
  if (depth_.readFrame(&depth) != openni::STATUS_OK) return Read::Timeout;
  const int index = depth.getFrameIndex();
  if (file && !config_.loop && last_index_ >= 0 && index <= last_index_) return Read::End;  // wrapped
  last_index_ = index;
  color.release();
  if (color_on_) {
    // Newest colour frame without waiting; kept only if it belongs to this depth frame.
    openni::VideoStream* cs[] = {&color_};
    while (openni::OpenNI::waitForAnyStream(cs, 1, &ready, 0) == openni::STATUS_OK) {
      if (color_.readFrame(&last_color_) != openni::STATUS_OK) break;
    }
    const int64_t period_us = 1'000'000 / std::max(1, depth.getVideoMode().getFps());
    if (last_color_.isValid() &&
        std::llabs(static_cast<long long>(last_color_.getTimestamp()) - static_cast<long long>(depth.getTimestamp())) <
            period_us)
      color = last_color_;
  }
  return Read::Frame;
}

}  // namespace stairs
