// The two modes of stairs-viewer (main.cpp parses the options).
#pragma once

#include "common/daemon.hpp"

namespace stairs::viewer {

// Live window over LCM; returns the exit code.
int run_live(const Options& opts);
// Headless: --render INPUT --out DIR|FILE.mp4|FILE.png; returns the exit code.
int run_render(const Options& opts);

}  // namespace stairs::viewer
