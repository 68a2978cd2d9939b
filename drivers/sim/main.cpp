// stairs-sim: a simulated Kinect v1 on parametric staircases with exact ground
// truth. Publishes STAIRS_DEPTH + STAIRS_GROUND_TRUTH on LCM at the frame rate,
// or writes an LCM log, a sequence directory or an .oni recording.
#include "drivers/sim/imu.hpp"
#include "drivers/sim/odometry.hpp"
#include "drivers/sim/render.hpp"
#include "drivers/sim/sim_setup.hpp"

#include "common/daemon.hpp"
#include "common/json_io.hpp"
#include "common/lcm_bridge.hpp"
#include "common/lcm_log.hpp"
#include "common/sequence.hpp"
#include "drivers/openni2/oni_writer.hpp"

#include <lcm/lcm-cpp.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <thread>

using namespace stairs;
using namespace stairs::sim;

namespace {

// Where frames go: files (--log, --seq, --oni) and/or LCM.
struct Outputs {
  std::unique_ptr<LogWriter> log;
  std::unique_ptr<SequenceWriter> seq;
  std::string seq_dir;
  std::unique_ptr<OniWriter> oni;
  std::unique_ptr<lcm::LCM> lcm;
  bool to_files = false, publish = false;
};

Outputs open_outputs(const Options& o, const SimSetup& setup) {
  Outputs out;
  out.to_files = o.has("log") || o.has("seq") || o.has("oni");
  out.publish = !out.to_files || o.flag("publish");
  if (o.has("log")) out.log = std::make_unique<LogWriter>(o.get("log"));
  if (o.has("seq")) {
    out.seq_dir = o.get("seq");
    out.seq = std::make_unique<SequenceWriter>(out.seq_dir, setup.K, 0.001);
  }
  if (o.has("oni"))
    out.oni = std::make_unique<OniWriter>(o.get("oni"), setup.K.width, setup.K.height,
                                          static_cast<int>(std::lround(setup.trajectory.fps)));
  if (out.publish) {
    out.lcm = std::make_unique<lcm::LCM>(o.get("lcm-url"));
    if (!out.lcm->good()) throw std::runtime_error("cannot open LCM with URL '" + o.get("lcm-url") + "'");
  }
  return out;
}

// --gap START_S:LENGTH_S: no depth frame in that interval of the trajectory.
struct Gap {
  double start_s = 0.0, length_s = 0.0;
  bool contains(double t_s) const { return t_s >= start_s && t_s < start_s + length_s; }
};

Gap parse_gap(const Options& o) {
  Gap g;
  if (!o.has("gap")) return g;
  char colon = 0, extra = 0;
  if (std::sscanf(o.get("gap").c_str(), "%lf%c%lf%c", &g.start_s, &colon, &g.length_s, &extra) != 3 || colon != ':' ||
      !(g.start_s >= 0) || !(g.length_s > 0))
    throw std::runtime_error("--gap '" + o.get("gap") + "': expected START_S:LENGTH_S, e.g. 3:5");
  return g;
}

// Renders one trajectory frame and sends depth and ground truth to every output.
class FrameSender {
 public:
  FrameSender(const Options& o, Renderer& renderer, const Trajectory& traj, Outputs& out, StatusReporter& status)
      : renderer_(renderer),
        traj_(traj),
        out_(out),
        status_(status),
        depth_channel_(o.get("depth-channel")),
        truth_channel_(o.get("truth-channel")),
        zlib_(o.get_int("zlib")),
        stair_(renderer.stair_truth()),
        sequence_truth_(stair_) {}

  void send(int f, double t_s, int64_t utime, int32_t seq) {
    const auto t0 = std::chrono::steady_clock::now();
    const Eigen::Isometry3d T = traj_.pose(f);
    const DepthImage img = renderer_.render(T, utime, seq);
    const GroundTruthFrame truth = renderer_.truth(T, t_s, img);
    const depth_frame_t depth_msg = to_lcm(img, zlib_);
    const ground_truth_t truth_msg = to_lcm(stair_, truth, utime, seq);
    if (out_.log) {
      out_.log->write_message(depth_channel_, utime, depth_msg);
      out_.log->write_message(truth_channel_, utime, truth_msg);
    }
    if (out_.seq) {
      out_.seq->write(img, t_s);
      sequence_truth_.frames.push_back(truth);
    }
    if (out_.oni) out_.oni->write(img);
    if (out_.publish) {
      out_.lcm->publish(depth_channel_, &depth_msg);
      out_.lcm->publish(truth_channel_, &truth_msg);
      status_.published(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      status_.tick();
    }
  }

  // Completes the files (an interrupted run leaves FILE.partial and a sequence
  // directory without depth.txt: nothing that looks complete).
  void finish(bool complete, const SimSetup& setup) {
    if (complete && out_.log) out_.log->close();
    if (complete && out_.seq) {
      nlohmann::json gt = to_json(sequence_truth_);
      gt["generator"] = setup_to_json(setup);
      gt["visible_min_pixels"] = renderer_.visible_min_pixels();
      for (size_t i = 0; i < gt["frames"].size(); ++i) gt["frames"][i]["seq"] = i;
      write_json_file(out_.seq_dir + "/groundtruth.json", gt);
      out_.seq->finish();
    }
    if (out_.oni) out_.oni->close();
  }

 private:
  Renderer& renderer_;
  const Trajectory& traj_;
  Outputs& out_;
  StatusReporter& status_;
  const std::string depth_channel_, truth_channel_;
  const int zlib_;
  const GroundTruth stair_;
  GroundTruth sequence_truth_;
};

// Publishing at the frame rate: sleeps until the next frame is due; a sender
// that fell far behind starts again from now instead of bursting.
class Pacer {
 public:
  explicit Pacer(double fps) : period_(std::chrono::duration<double>(1.0 / fps)) {}
  void wait(StatusReporter& status) {
    next_ += std::chrono::duration_cast<std::chrono::steady_clock::duration>(period_);
    const auto now = std::chrono::steady_clock::now();
    if (next_ > now) std::this_thread::sleep_until(next_);
    else if (now - next_ > std::chrono::seconds(1)) next_ = now;
    else status.dropped("behind the frame rate");
  }

 private:
  std::chrono::duration<double> period_;
  std::chrono::steady_clock::time_point next_ = std::chrono::steady_clock::now();
};

// The optional robot sensors (--odometry, --imu): their samples up to each
// frame's time go to every output before the frame.
class RobotSensors {
 public:
  RobotSensors(const Options& o, const Trajectory& traj, uint64_t seed, bool loop)
      : odometry_channel_(o.get("odometry-channel")), imu_channel_(o.get("imu-channel")) {
    const auto rate = [&](const char* name, double max_hz) {
      if (loop) throw std::runtime_error(std::string("--") + name + " with --loop: the trajectory would jump back");
      const double hz = o.get_double(std::string(name) + "-rate-hz");
      if (!(hz > 0 && hz <= max_hz))
        throw std::runtime_error(std::string("--") + name + "-rate-hz must be within (0, " + std::to_string(max_hz) + "]");
      return hz;
    };
    if (o.flag("odometry")) {
      OdometryNoise noise;
      noise.rate_hz = rate("odometry", 1000);
      odometry_ = std::make_unique<OdometrySim>(traj, noise, seed);
    }
    if (o.flag("imu")) {
      ImuNoise noise;
      noise.rate_hz = rate("imu", 2000);
      imu_ = std::make_unique<ImuSim>(traj, noise, seed);
    }
  }

  // Samples up to trajectory time t_s, which is utime on the output's clock.
  void emit(double t_s, int64_t utime, Outputs& out, bool publish) {
    const int64_t utime0 = utime - std::llround(t_s * 1e6);
    const auto send = [&](const auto& samples, const std::string& channel, auto write_seq) {
      for (const auto& sample : samples) {
        const auto msg = to_lcm(sample);
        if (out.log) out.log->write_message(channel, sample.utime, msg);
        if (out.seq) write_seq(sample);
        if (publish) out.lcm->publish(channel, &msg);
      }
    };
    if (odometry_)
      send(odometry_->until(t_s, utime0), odometry_channel_, [&](const OdometrySample& x) { out.seq->write_odometry(x); });
    if (imu_) send(imu_->until(t_s, utime0), imu_channel_, [&](const ImuSample& x) { out.seq->write_imu(x); });
  }

 private:
  std::string odometry_channel_, imu_channel_;
  std::unique_ptr<OdometrySim> odometry_;
  std::unique_ptr<ImuSim> imu_;
};

void list_presets() {
  for (const std::string& name : preset_names()) std::printf("%-14s %s\n", name.c_str(), preset_summary(name).c_str());
}

// Per-frame render time of `frames` frames: median, p95 and frames/s.
void bench(Renderer& r, const Trajectory& traj, int frames) {
  std::vector<double> ms;
  for (int f = 0; f < frames; ++f) {
    const Eigen::Isometry3d T = traj.pose(f % traj.frames());
    const auto t0 = std::chrono::steady_clock::now();
    const DepthImage img = r.render(T, 0, f);
    r.truth(T, traj.time_s(f), img);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  const double median = ms[ms.size() / 2], p95 = ms[std::min(ms.size() - 1, ms.size() * 95 / 100)];
  std::printf("%dx%d, %d frames (render + truth): median %.2f ms, p95 %.2f ms, %.1f frames/s at the median\n",
              r.intrinsics().width, r.intrinsics().height, frames, median, p95, 1000.0 / median);
}

void add_program_options(Options& o) {
  add_setup_options(o);
  o.add("frames", "N", "stop after N frames (0 = the whole trajectory)", "0")
      .add("log", "FILE", "write an LCM log (depth + ground truth) instead of publishing")
      .add("seq", "DIR", "write a sequence directory with groundtruth.json instead of publishing")
      .add("oni", "FILE", "write an OpenNI .oni recording of the depth instead of publishing")
      .add("publish", "", "publish on LCM even when writing files")
      .add("lcm-url", "URL", "LCM URL (empty = LCM's default)", "")
      .add("depth-channel", "NAME", "depth channel", "STAIRS_DEPTH")
      .add("truth-channel", "NAME", "ground-truth channel", "STAIRS_GROUND_TRUTH")
      .add("odometry", "", "also give the camera's odometry (drifting, DESIGN.md odometry.txt): on the odometry\n"
                           "channel, in the log, and as odometry.txt of a sequence directory")
      .add("odometry-rate-hz", "HZ", "odometry samples per second", "100")
      .add("odometry-channel", "NAME", "odometry channel (pose_t)", "STAIRS_ODOMETRY")
      .add("imu", "", "also give an IMU aligned with the camera (specific force, angular rate, bias and\n"
                      "noise; DESIGN.md imu.txt): on the IMU channel, in the log, and as imu.txt")
      .add("imu-rate-hz", "HZ", "IMU samples per second", "200")
      .add("imu-channel", "NAME", "IMU channel (imu_t)", "STAIRS_IMU")
      .add("gap", "START_S:LENGTH_S", "no depth frame in this interval of the trajectory (odometry goes on): a\n"
                                      "camera that looks away or a dropped stream")
      .add("status-channel", "NAME", "status channel", "STAIRS_STATUS")
      .add("zlib", "LEVEL", "depth compression: 0 = raw, 1..9 = zlib", "1")
      .add("fast", "", "publish as fast as possible instead of at the frame rate")
      .add("loop", "", "when publishing, start the trajectory again at its end")
      .add("start-utime", "US", "utime of the first frame in files (publishing uses the host clock)", "0")
      .add("bench", "N", "render N frames without output and print the time per frame")
      .add("verbose", "", "status line once a second even when stderr is not a terminal");
}

int run(int argc, char** argv) {
  Options o("stairs-sim",
            "Simulated Kinect v1 on parametric staircases with exact ground truth. Without --log/--seq/--oni it\n"
            "publishes depth_frame_t on STAIRS_DEPTH at the frame rate and ground_truth_t on STAIRS_GROUND_TRUTH\n"
            "(same utime and seq). The same --seed gives the same bytes.");
  add_program_options(o);
  o.parse(argc, argv);
  if (o.flag("list")) {
    list_presets();
    return 0;
  }
  const SimSetup setup = setup_from_options(o);
  Renderer renderer(setup.scene, setup.K, setup.sensor, setup.seed);
  const Trajectory traj(setup.scene, setup.trajectory);
  if (o.has("bench")) {
    bench(renderer, traj, std::max(1, o.get_int("bench")));
    return 0;
  }
  int frames = traj.frames();
  if (o.get_int("frames") > 0) frames = std::min(frames, o.get_int("frames"));
  if (o.get_int("zlib") < 0 || o.get_int("zlib") > 9) throw std::runtime_error("--zlib must be within 0..9");
  Outputs out = open_outputs(o, setup);
  const bool loop = out.publish && o.flag("loop");
  const int64_t start_utime = static_cast<int64_t>(o.get_double("start-utime"));
  StatusReporter status(out.lcm.get(), "stairs-sim", o.get("status-channel"), o.flag("verbose"));
  install_stop_signals();
  RobotSensors sensors(o, traj, setup.seed, loop);
  const Gap gap = parse_gap(o);
  FrameSender sender(o, renderer, traj, out, status);
  Pacer pacer(setup.trajectory.fps);
  const bool progress = out.to_files && (isatty(STDERR_FILENO) != 0 || o.flag("verbose"));
  auto last_progress = std::chrono::steady_clock::now();
  int32_t seq = 0;
  for (int f = 0; !stop_requested(); ++f) {
    if (f == frames) {
      if (!loop) break;
      f = 0;
    }
    const double t_s = seq / setup.trajectory.fps;  // sequence time, continues across loops
    const int64_t utime = out.publish && !out.to_files ? now_utime() : start_utime + std::llround(t_s * 1e6);
    sensors.emit(traj.time_s(f), utime, out, out.publish);
    // In a gap the frame is not sent; its sequence number is skipped, so the
    // stream shows what is missing.
    if (!gap.contains(traj.time_s(f))) sender.send(f, t_s, utime, seq);
    ++seq;
    if (progress && std::chrono::steady_clock::now() - last_progress > std::chrono::seconds(1)) {
      last_progress = std::chrono::steady_clock::now();
      std::fprintf(stderr, "\rstairs-sim: frame %d/%d", f + 1, frames);
      std::fflush(stderr);
    }
    if (out.publish && !o.flag("fast")) pacer.wait(status);
  }
  const bool complete = !stop_requested() || loop;
  sender.finish(complete, setup);
  if (progress || (out.to_files && !complete))
    std::fprintf(stderr, "\rstairs-sim: %d frames written%s\n", seq, complete ? "" : " (interrupted: files left incomplete)");
  if (out.publish) status.final_report();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "stairs-sim: " << e.what() << "\n";
    return 1;
  }
}
