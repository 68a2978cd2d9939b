// Scores a recorded live run: the observations and models the daemons
// published, as they ran (issue 18 item 4), instead of running perception and
// the tracker again. A frame the live chain never answered counts as missed.
#pragma once

#include "common/channels.hpp"
#include "tools/result_json.hpp"

#include <string>

namespace stairs::eval {

struct RecordedOptions {
  ChainChannels channels;
  int max_frames = 0;     // frames to score, 0 = all
  bool progress = false;  // progress bar on stderr
};

// Throws std::runtime_error naming the file when the log is unreadable, holds
// no valid depth frame, or holds no observation at all (nothing was recorded).
RunResult score_recorded(const std::string& log, const RecordedOptions& options);

}  // namespace stairs::eval
