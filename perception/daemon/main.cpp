// stairs-perception: STAIRS_DEPTH in, STAIRS_OBSERVATION out. Thin: decode,
// validate, hand the newest frame to a worker (older ones are dropped and
// counted), Pipeline::process, encode, publish, report status.
#include "common/config_file.hpp"
#include "common/daemon.hpp"
#include "common/lcm_bridge.hpp"
#include "perception/config.hpp"
#include "perception/pipeline.hpp"

#include <lcm/lcm-cpp.hpp>

#include <iostream>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace {

// IMU samples from the receive thread to the worker, which feeds them to the
// pipeline before each frame. Capped: a worker that stalls drops the oldest.
class ImuQueue {
 public:
  static constexpr size_t kCap = 4096;  // 10 s at 400 Hz
  void push(const stairs::ImuSample& s) {
    std::lock_guard<std::mutex> lock(m_);
    if (samples_.size() >= kCap) samples_.erase(samples_.begin());
    samples_.push_back(s);
  }
  std::vector<stairs::ImuSample> take() {
    std::lock_guard<std::mutex> lock(m_);
    return std::exchange(samples_, {});
  }

 private:
  std::mutex m_;
  std::vector<stairs::ImuSample> samples_;
};

struct Receiver {
  stairs::LatestSlot<stairs::DepthImage>* slot;
  stairs::StatusReporter* status;
  ImuQueue* imu;
  Eigen::Matrix3d imu_to_camera;

  void on_imu(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    stairs::imu_t msg;
    stairs::ImuSample s;
    std::string error;
    if (!stairs::decode_message(rbuf->data, rbuf->data_size, msg, error) || !stairs::from_lcm(msg, s, error)) {
      status->invalid("IMU: " + error);
      return;
    }
    imu->push(stairs::turned(s, imu_to_camera));
  }

  // Reused frame to frame: the message's data and the image's depth keep their buffers (a fresh
  // 600 KB image and its inflate buffer cost more than perception itself, in page faults).
  stairs::depth_frame_t msg;
  stairs::DepthImage img;

  void on_depth(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    status->received();
    std::string error;
    if (!stairs::decode_message(rbuf->data, rbuf->data_size, msg, error) || !stairs::from_lcm(msg, img, error)) {
      status->invalid(error);
      return;
    }
    if (slot->put(img)) status->dropped("worker busy: older depth frame replaced");
  }
};

}  // namespace

int main(int argc, char** argv) {
  stairs::Options opts("stairs-perception",
                       "Finds staircases in depth frames (thesis chapters 3-4) and publishes one stair "
                       "observation per processed frame.");
  opts.add("lcm-url", "URL", "LCM URL (empty = LCM's default)", "")
      .add("depth-channel", "NAME", "channel of depth_frame_t input", "STAIRS_DEPTH")
      .add("observation-channel", "NAME", "channel of stair_observation_t output", "STAIRS_OBSERVATION")
      .add("status-channel", "NAME", "channel of daemon_status_t", "STAIRS_STATUS")
      .add("imu-channel", "NAME", "channel of optional IMU samples (imu_t; config imu.to_camera_* turns them)",
           "STAIRS_IMU")
      .config_options("\"stair\", \"mount\" and \"perception\"")
      .add("verbose", "", "print the status line once a second even without a terminal");
  opts.parse(argc, argv);

  stairs::PerceptionConfig config;
  try {
    config = stairs::load_perception_config(opts.get("config"));
  } catch (const std::exception& e) {
    std::cerr << "stairs-perception: " << e.what() << "\n";
    return 2;
  }
  if (opts.flag("print-config")) {
    stairs::print_config(std::cout, {{"stair", stairs::config_to_json(stairs::stair_definition(config))},
                                     {"mount", stairs::config_to_json(config.mount)},
                                     {"perception", stairs::to_json(config)}});
    return 0;
  }
  lcm::LCM lcm(opts.get("lcm-url"));
  if (!lcm.good()) {
    std::cerr << "stairs-perception: cannot open LCM URL '" << opts.get("lcm-url") << "'\n";
    return 1;
  }
  stairs::install_stop_signals();
  stairs::StatusReporter status(&lcm, "stairs-perception", opts.get("status-channel"), opts.flag("verbose"));
  stairs::LatestSlot<stairs::DepthImage> slot;
  ImuQueue imu;
  Receiver receiver{&slot, &status, &imu, stairs::imu_to_camera(config.imu), {}, {}};
  lcm.subscribe(opts.get("depth-channel"), &Receiver::on_depth, &receiver);
  lcm.subscribe(opts.get("imu-channel"), &Receiver::on_imu, &receiver);

  const std::string out_channel = opts.get("observation-channel");
  std::thread worker([&] {
    stairs::Pipeline pipeline(config);
    stairs::DepthImage frame;
    while (!stairs::stop_requested()) {
      if (!slot.take(frame, std::chrono::milliseconds(100))) continue;
      for (const stairs::ImuSample& s : imu.take()) pipeline.add_imu(s);
      const stairs::Observation obs = pipeline.process(frame);
      const stairs::stair_observation_t msg = stairs::to_lcm(obs, stairs::now_utime());
      lcm.publish(out_channel, &msg);
      status.published(obs.latency_ms);
    }
  });
  while (!stairs::stop_requested()) {
    // A stop signal interrupts the wait: that is no failure.
    if (lcm.handleTimeout(100) < 0 && !stairs::stop_requested()) {
      std::cerr << "stairs-perception: LCM receive failed\n";
      stairs::request_stop();
      break;
    }
    status.tick();
  }
  worker.join();
  status.final_report();
  return 0;
}
