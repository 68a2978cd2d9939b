// stairs-eval: replays a log or sequence directory through perception and the
// tracker (or takes what the daemons published, --recorded), scores it against
// ground truth and writes DESIGN.md's Result JSON.
#include "common/config_file.hpp"
#include "common/daemon.hpp"
#include "common/json_io.hpp"
#include "tools/downsample.hpp"
#include "tools/recorded.hpp"
#include "tools/replay.hpp"
#include "tools/report.hpp"

#include <iostream>

int main(int argc, char** argv) {
  stairs::Options opts("stairs-eval",
                       "Replays INPUT (an LCM log or a sequence directory) through perception and the tracker "
                       "as fast as possible, prints the thesis' tables 6.1-6.4 when ground truth is present, the "
                       "final model and per-stage latency. With --recorded it scores a recorded live run instead: the "
                       "observations and models the daemons published, as they ran.");
  opts.positional("INPUT", "LCM log (STAIRS_DEPTH [+ STAIRS_GROUND_TRUTH]) or sequence directory", false)
      .add("json", "FILE", "write DESIGN.md's Result JSON here (atomically)")
      .config_options("\"stair\", \"mount\", \"perception\" and \"tracker\"")
      .add("max-frames", "N", "process at most N frames (0 = all)", "0")
      .add("resolution", "WxH", "downsample the input by an integer factor to WxH (e.g. 320x240)")
      .add("recorded", "",
           "score the STAIRS_OBSERVATION and STAIRS_MODEL messages recorded in the log (lcm-logger next to the "
           "daemons); frames the live chain did not answer count as missed")
      .add("observation-channel", "NAME", "with --recorded: the observations' channel", "STAIRS_OBSERVATION")
      .add("model-channel", "NAME", "with --recorded: the models' channel", "STAIRS_MODEL")
      .add("quiet", "", "no progress bar and no report");
  opts.parse(argc, argv);
  try {
    stairs::eval::ReplayOptions options;
    options.max_frames = opts.get_int("max-frames");
    if (options.max_frames < 0) throw std::invalid_argument("--max-frames must be >= 0");
    if (opts.has("resolution")) stairs::eval::parse_resolution(opts.get("resolution"), options.width, options.height);
    options.config = stairs::load_chain_config(opts.get("config"));
    if (opts.flag("print-config")) {
      stairs::print_config(std::cout, stairs::to_json(options.config));
      return 0;
    }
    if (opts.positionals().empty()) {
      std::cerr << "stairs-eval: missing INPUT (see --help)\n";
      return 2;
    }
    options.progress = !opts.flag("quiet");
    stairs::eval::RunResult result;
    if (opts.flag("recorded")) {
      if (opts.has("config") || opts.has("resolution"))
        throw std::invalid_argument("--recorded scores what the daemons published: --config and --resolution do not apply");
      stairs::eval::RecordedOptions recorded;
      recorded.channels.observation = opts.get("observation-channel");
      recorded.channels.model = opts.get("model-channel");
      recorded.max_frames = options.max_frames;
      recorded.progress = options.progress;
      result = stairs::eval::score_recorded(opts.positionals().at(0), recorded);
    } else {
      result = stairs::eval::replay(opts.positionals().at(0), options);
    }
    if (opts.has("json")) stairs::write_json_file(opts.get("json"), stairs::eval::result_to_json(result));
    if (!opts.flag("quiet")) stairs::eval::print_report(std::cout, result);
  } catch (const std::exception& e) {
    std::cerr << "stairs-eval: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
