#include "xvfb.hpp"

#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <thread>

namespace fs = std::filesystem;

namespace stairs::viewer::test {

pid_t spawn(const std::vector<std::string>& argv, const std::string& display, const std::string& err_file) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (!display.empty()) setenv("DISPLAY", display.c_str(), 1);
    if (!std::freopen(err_file.c_str(), "w", stderr)) _exit(126);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  return pid;
}

Xvfb::Xvfb() {
  if (!fs::exists("/usr/bin/Xvfb")) {
    error_ = "/usr/bin/Xvfb not installed";
    return;
  }
  for (int n = 91; n < 130 && !dpy_; ++n) {
    if (fs::exists("/tmp/.X" + std::to_string(n) + "-lock") || fs::exists("/tmp/.X11-unix/X" + std::to_string(n)))
      continue;
    display_ = ":" + std::to_string(n);
    pid_ = spawn({"/usr/bin/Xvfb", display_, "-screen", "0", "1280x800x24", "-nolisten", "tcp"}, "", "/dev/null");
    for (int i = 0; i < 50 && !dpy_; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      dpy_ = XOpenDisplay(display_.c_str());
    }
    if (!dpy_) stop();
  }
  if (!dpy_) error_ = "Xvfb did not start on any display :91..:129";
}

void Xvfb::stop() {
  if (pid_ > 0) {
    kill(pid_, SIGTERM);
    waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }
}

Xvfb::~Xvfb() {
  if (dpy_) XCloseDisplay(static_cast<Display*>(dpy_));
  stop();
}

cv::Mat Xvfb::screenshot() const {
  Display* dpy = static_cast<Display*>(dpy_);
  const Window root = DefaultRootWindow(dpy);
  XWindowAttributes attr;
  XGetWindowAttributes(dpy, root, &attr);
  XImage* img = XGetImage(dpy, root, 0, 0, attr.width, attr.height, AllPlanes, ZPixmap);
  cv::Mat out(attr.height, attr.width, CV_8UC3);
  for (int y = 0; y < attr.height; ++y)
    for (int x = 0; x < attr.width; ++x) {
      const unsigned long p = XGetPixel(img, x, y);
      out.at<cv::Vec3b>(y, x) = {uint8_t(p & img->blue_mask), uint8_t((p & img->green_mask) >> 8),
                                 uint8_t((p & img->red_mask) >> 16)};
    }
  XDestroyImage(img);
  return out;
}

}  // namespace stairs::viewer::test
