// A progress bar on stderr, redrawn at most every 100 ms, only on a terminal.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

namespace stairs::eval {

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled && isatty(fileno(stderr))) {}
  ~ProgressBar() {
    if (enabled_ && drawn_) std::fprintf(stderr, "\r\033[K");
  }
  void update(double fraction, int frames) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    if (drawn_ && now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    drawn_ = true;
    const int width = 40, filled = static_cast<int>(std::min(1.0, std::max(0.0, fraction)) * width);
    const double elapsed_s = std::chrono::duration<double>(now - start_).count();
    std::fprintf(stderr, "\r[%s%s] %3.0f%%  %d frames  %.1f fps", std::string(filled, '#').c_str(),
                 std::string(width - filled, '.').c_str(), 100.0 * fraction, frames,
                 elapsed_s > 0 ? frames / elapsed_s : 0.0);
    std::fflush(stderr);
  }

 private:
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_;
};

}  // namespace stairs::eval
