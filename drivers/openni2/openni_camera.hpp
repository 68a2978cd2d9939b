// One OpenNI2 source: a live device (first one or by URI) or an .oni
// recording, its depth stream and optionally the registered colour stream.
// Every OpenNI2 call that can block either takes a timeout or runs under a
// watchdog that reports it (and exits on a stop request) instead of hanging
// silently.
#pragma once

#include <OpenNI.h>

#include <memory>
#include <string>

namespace stairs {

struct CameraConfig {
  std::string uri;       // "" = first device
  std::string oni_file;  // non-empty = play this recording instead of a device
  int width = 640;       // px, depth mode (live devices)
  int height = 480;      // px
  int fps = 30;          // Hz
  bool color = false;    // also stream registered RGB888 colour
  bool fast = false;     // recordings: as fast as read (manual playback), else recorded speed
  bool loop = false;     // recordings: start again at the end
  int frame_timeout_ms = 2000;  // ms without a depth frame = device lost / recording over
};

class BlockingCallWatch;

class OpenNICamera {
 public:
  explicit OpenNICamera(CameraConfig config);
  ~OpenNICamera();

  // Opens the source and starts the streams; false with a one-line reason
  // naming what was tried.
  bool open(std::string& error);
  void close();
  bool is_open() const { return device_ != nullptr; }

  enum class Read { Frame, Timeout, End };
  // Waits up to frame_timeout_ms for the next depth frame. End: a recording
  // without --loop has delivered its last frame (or stopped delivering).
  Read read(openni::VideoFrameRef& depth, openni::VideoFrameRef& color);

  float hfov_rad() const { return hfov_rad_; }
  float vfov_rad() const { return vfov_rad_; }
  // "device URI" or "recording FILE", for messages.
  std::string description() const;
  int recording_frames() const { return recording_frames_; }

 private:
  bool resolve_uri(std::string& uri, std::string& error) const;
  bool configure_playback(openni::Device& dev, const std::string& what, std::string& error) const;
  bool create_depth(openni::Device& dev, bool file, const std::string& what, std::string& error);
  void start_color(openni::Device& dev, bool file, const std::string& what);

  CameraConfig config_;
  std::unique_ptr<BlockingCallWatch> watch_;
  std::unique_ptr<openni::Device> device_;
  openni::VideoStream depth_, color_;
  openni::VideoFrameRef last_color_;
  bool color_on_ = false;
  float hfov_rad_ = 0.0f, vfov_rad_ = 0.0f;
  int recording_frames_ = 0;
  int last_index_ = -1;  // frame index last read
  std::string opened_uri_;
};

}  // namespace stairs
