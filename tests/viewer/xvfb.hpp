// An Xvfb server for the live-mode test, and screenshots of it through Xlib
// (kept apart: Xlib's macros clash with GoogleTest).
#pragma once

#include <opencv2/core.hpp>

#include <sys/types.h>

#include <string>
#include <vector>

namespace stairs::viewer::test {

// fork + execv with DISPLAY set (when not empty) and stderr to err_file.
pid_t spawn(const std::vector<std::string>& argv, const std::string& display, const std::string& err_file);

class Xvfb {
 public:
  Xvfb();  // on a free display among :91..:129; running() false when it cannot start
  ~Xvfb();
  bool running() const { return dpy_ != nullptr; }
  const std::string& display() const { return display_; }
  const std::string& error() const { return error_; }
  cv::Mat screenshot() const;  // the whole screen, BGR

 private:
  void stop();
  pid_t pid_ = -1;
  std::string display_, error_;
  void* dpy_ = nullptr;  // Display*
};

}  // namespace stairs::viewer::test
