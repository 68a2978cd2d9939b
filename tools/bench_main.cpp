// stairs-bench: our full pipeline against PCL's organized plane extraction on
// the same frames in the same run; latency as medians, p95 and a ratio.
#include "common/config_file.hpp"
#include "common/daemon.hpp"
#include "tools/downsample.hpp"
#include "tools/pcl_peer.hpp"
#include "tools/replay.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

namespace {

using stairs::eval::LatencyStats;

std::string ms_pair(const LatencyStats& l) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1f / %.1f", l.median_ms, l.p95_ms);
  return buf;
}

std::string opt(const std::optional<double>& v, const char* f) {
  if (!v) return "n/a";
  char buf[32];
  std::snprintf(buf, sizeof buf, f, *v);
  return buf;
}

const char* kHeader =
    "| sequence | resolution | frames | perception ms (median / p95) | tracker ms (median / p95) "
    "| PCL planes ms (median / p95) | ours / PCL (median) | step detection (all visible / nosing in view / tracked) "
    "| model steps (detected/real) | riser err cm (signed / abs) | tread err cm (signed / abs) "
    "| false steps (frames / model) | pitch / roll err deg | height err cm (surface beneath in view) |\n"
    "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";

// One markdown row: input, latencies (ours, PCL's), their ratio, the scores.
void print_row(const std::string& name, int width, int height, const stairs::eval::RunResult& result,
               const stairs::eval::LatencyStats& peer, const stairs::eval::LatencyStats& ours) {
  const auto stages = stairs::eval::latency_by_stage(result.frames);
  std::cout << "| " << name << " | " << width << "x" << height << " | " << result.frames_processed << " | "
            << ms_pair(stages.at("perception")) << " | " << ms_pair(stages.at("tracker")) << " | " << ms_pair(peer)
            << " | "
            << opt(peer.median_ms > 0 ? std::optional<double>(ours.median_ms / peer.median_ms) : std::nullopt, "%.2f")
            << " | ";
  if (!result.score) {
    std::cout << "n/a | n/a | n/a | n/a | n/a | n/a | n/a |\n";
    return;
  }
  const stairs::eval::Score& s = *result.score;
  auto percent = [](const std::optional<double>& v) {
    return opt(v ? std::optional<double>(100 * *v) : std::nullopt, "%.1f %%");
  };
  std::cout << percent(s.frame_step_detection) << " / " << percent(s.frame_step_detection_nosing_in_view) << " / "
            << percent(s.frame_step_detection_tracked) << " | " << s.model_steps_detected << "/" << s.model_steps_real
            << " | " << opt(s.riser_error_cm.mean_signed, "%+.2f") << " / " << opt(s.riser_error_cm.mean_abs, "%.2f")
            << " | " << opt(s.tread_error_cm.mean_signed, "%+.2f") << " / " << opt(s.tread_error_cm.mean_abs, "%.2f")
            << " | " << s.frame_false_steps << " / " << s.model_false_steps << " | "
            << opt(s.pitch_error_deg.mean_abs, "%.2f") << " / " << opt(s.roll_error_deg.mean_abs, "%.2f") << " | "
            << opt(s.height_error_beneath_visible_cm.mean_abs, "%.2f") << " |\n";
}

}  // namespace

int main(int argc, char** argv) {
  stairs::Options opts("stairs-bench",
                       "Runs our pipeline (perception + tracker) and PCL's IntegralImageNormalEstimation + "
                       "OrganizedMultiPlaneSegmentation on the same frames of INPUT and prints one markdown "
                       "table row: latencies (median / p95), our latency as a ratio to PCL's, and the scores.");
  opts.positional("INPUT", "LCM log or sequence directory", false)
      .add("resolution", "WxH", "downsample the input by an integer factor to WxH (e.g. 320x240)")
      .add("max-frames", "N", "process at most N frames (0 = all)", "0")
      .config_options("\"stair\", \"mount\", \"perception\" and \"tracker\"")
      .add("header", "", "print the table header (and nothing else when no INPUT is given)");
  opts.parse(argc, argv);
  if (opts.flag("print-config")) {
    try {
      stairs::print_config(std::cout, stairs::to_json(stairs::load_chain_config(opts.get("config"))));
      return 0;
    } catch (const std::exception& e) {
      std::cerr << "stairs-bench: " << e.what() << "\n";
      return 1;
    }
  }
  if (opts.flag("header")) std::cout << kHeader;
  if (opts.positionals().empty()) {
    if (opts.flag("header")) return 0;
    std::cerr << "stairs-bench: missing INPUT (see --help)\n";
    return 2;
  }
  try {
    stairs::eval::ReplayOptions options;
    options.max_frames = opts.get_int("max-frames");
    if (opts.has("resolution")) stairs::eval::parse_resolution(opts.get("resolution"), options.width, options.height);
    options.config = stairs::load_chain_config(opts.get("config"));
    const std::string input = opts.positionals().at(0);

    stairs::eval::PclPeer peer;
    std::vector<double> peer_ms, ours_ms;
    int width = 0, height = 0;
    const auto result = stairs::eval::replay(input, options, [&](const stairs::DepthImage& image) {
      width = image.K.width;
      height = image.K.height;
      const auto t0 = std::chrono::steady_clock::now();
      peer.extract_planes(image);
      peer_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    });
    for (const auto& f : result.frames) {
      double total = 0.0;
      for (const auto& l : f.latency)
        if (l.name == "perception" || l.name == "tracker") total += l.ms;
      ours_ms.push_back(total);
    }
    std::filesystem::path path(input);
    if (path.filename().empty()) path = path.parent_path();  // "dir/"
    print_row(path.stem().string(), width, height, result, stairs::eval::latency_stats(peer_ms),
              stairs::eval::latency_stats(ours_ms));
  } catch (const std::exception& e) {
    std::cerr << "stairs-bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
