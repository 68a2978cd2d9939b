// stairs-viewer: see what the pipeline sees, live (LCM + a window) or headless.
#include "viewer/app.hpp"

#include "chain/config.hpp"
#include "common/config_file.hpp"

#include <exception>
#include <iostream>

int main(int argc, char** argv) {
  stairs::Options opts("stairs-viewer",
                       "Live: subscribes to depth, observations, models and ground truth and shows one window\n"
                       "(image panel, side view, top view, status bar). Keys: n = depth/normal image, q/Esc = quit.\n"
                       "Headless: --render INPUT --out DIR|FILE.mp4|FILE.png draws the same panels from an LCM log\n"
                       "or a sequence directory, with no display. A log holding observations/models is drawn as\n"
                       "recorded; otherwise perception and the tracker run in-process on its depth frames.");
  opts.add("render", "INPUT", "headless: LCM log or sequence directory to draw")
      .add("out", "PATH", "headless output: a directory (one PNG per frame), FILE.mp4/.avi, or FILE.png (last frame)")
      .add("frame", "N", "headless: draw only frame N (0-based; frames before it still go through the tracker)")
      .add("every", "K", "headless: draw every K-th frame", "1")
      .add("max-frames", "N", "headless: stop after N input frames (0 = all)", "0")
      .add("video-fps", "HZ", "headless: frame rate of a video output", "15")
      .config_options("\"stair\", \"mount\", \"perception\" and \"tracker\" (headless, for depth-only inputs)")
      .add("normals", "", "start with the normal image instead of the depth image")
      .add("lcm-url", "URL", "live: LCM URL (empty = LCM's default)")
      .add("depth-channel", "NAME", "depth frames", "STAIRS_DEPTH")
      .add("observation-channel", "NAME", "perception's observations", "STAIRS_OBSERVATION")
      .add("model-channel", "NAME", "tracker's models", "STAIRS_MODEL")
      .add("truth-channel", "NAME", "ground truth (simulator only)", "STAIRS_GROUND_TRUTH")
      .add("max-fps", "HZ", "live: redraw at most this often", "30")
      .add("screenshot", "FILE", "live: write the window's image to FILE (PNG) after --screenshot-after updates")
      .add("screenshot-after", "N", "live: updates before the screenshot", "10")
      .add("exit-after", "N", "live: quit after N window updates (0 = run until closed)", "0")
      .add("window", "NAME", "live: window title", "stairs-viewer")
      .add("verbose", "", "print the status line once a second even when stderr is not a terminal");
  opts.parse(argc, argv);
  try {
    if (opts.flag("print-config")) {
      stairs::print_config(std::cout, stairs::to_json(stairs::load_chain_config(opts.get("config"))));
      return 0;
    }
    return opts.has("render") ? stairs::viewer::run_render(opts) : stairs::viewer::run_live(opts);
  } catch (const std::exception& e) {
    std::cerr << "stairs-viewer: " << e.what() << "\n";
    return 1;
  }
}
