// stairs-tracker: STAIRS_OBSERVATION in, STAIRS_MODEL (and its steps-only twin
// STAIRS_MODEL_STEPS) out on every observation; reset on STAIRS_TRACKER_COMMAND.
// Thin: decode, validate, Tracker::update, encode, publish, report status.
#include "common/config_file.hpp"
#include "common/daemon.hpp"
#include "common/lcm_bridge.hpp"
#include "tracker/config.hpp"
#include "tracker/tracker.hpp"

#include <lcm/lcm-cpp.hpp>

#include <iostream>

namespace {

struct Handler {
  stairs::Tracker* tracker;
  lcm::LCM* lcm;
  stairs::StatusReporter* status;
  std::string model_channel;
  std::string steps_channel;  // empty = not published

  void on_observation(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    status->received();
    stairs::stair_observation_t msg;
    stairs::Observation obs;
    std::string error;
    if (!stairs::decode_message(rbuf->data, rbuf->data_size, msg, error) || !stairs::from_lcm(msg, obs, error)) {
      status->invalid(error);
      return;
    }
    const int64_t dropped_before = tracker->dropped_out_of_order(), jumps_before = tracker->time_jumps();
    const stairs::StairModel& model = tracker->update(obs);
    if (tracker->time_jumps() > jumps_before) status->event(model.status);
    if (tracker->dropped_out_of_order() > dropped_before) {
      status->dropped("out-of-order observation (utime " + std::to_string(obs.source_utime) + ")");
      return;
    }
    const stairs::stair_model_t out = stairs::to_lcm(model, stairs::now_utime(), obs.source_utime, obs.source_seq);
    lcm->publish(model_channel, &out);
    if (!steps_channel.empty()) {
      const stairs::stair_model_t steps = stairs::steps_only(out);
      lcm->publish(steps_channel, &steps);
    }
    status->published(model.update_latency_ms);
  }

  void on_command(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    stairs::tracker_command_t msg;
    std::string error;
    if (!stairs::decode_message(rbuf->data, rbuf->data_size, msg, error)) {
      status->invalid("command: " + error);
      return;
    }
    if (msg.command != stairs::tracker_command_t::COMMAND_RESET) {
      status->invalid("command: unknown command " + std::to_string(msg.command) + " (1 = reset)");
      return;
    }
    tracker->reset();
    status->event("model reset on request" + (msg.reason.empty() ? std::string() : ": " + msg.reason));
  }

  void on_odometry(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    stairs::pose_t msg;
    stairs::OdometrySample o;
    std::string error;
    if (!stairs::decode_message(rbuf->data, rbuf->data_size, msg, error) || !stairs::from_lcm(msg, o, error)) {
      status->invalid("odometry: " + error);
      return;
    }
    const int64_t dropped_before = tracker->dropped_odometry();
    tracker->add_odometry(o);
    if (tracker->dropped_odometry() > dropped_before)
      status->dropped("odometry going back in time (utime " + std::to_string(o.utime) + ")");
  }
};

}  // namespace

int main(int argc, char** argv) {
  stairs::Options opts("stairs-tracker",
                       "Fuses stair observations into an incremental stair model (thesis chapter 5) and publishes "
                       "it on every observation.");
  opts.add("lcm-url", "URL", "LCM URL (empty = LCM's default)", "")
      .add("observation-channel", "NAME", "channel of stair_observation_t input", "STAIRS_OBSERVATION")
      .add("model-channel", "NAME", "channel of stair_model_t output", "STAIRS_MODEL")
      .add("steps-channel", "NAME",
           "channel of the same model without plane samples (about 1 KB, for Wi-Fi links); empty = off",
           "STAIRS_MODEL_STEPS")
      .add("command-channel", "NAME", "channel of tracker_command_t requests (reset)", "STAIRS_TRACKER_COMMAND")
      .add("odometry-channel", "NAME", "channel of optional odometry (pose_t, bot_core.pose_t's layout)",
           "STAIRS_ODOMETRY")
      .add("status-channel", "NAME", "channel of daemon_status_t", "STAIRS_STATUS")
      .config_options("\"stair\", \"mount\" (the robot's base in the models) and \"tracker\"")
      .add("reset-after-s", "S", "a model lost this long is dropped when a stair is in view again (overrides --config)", "")
      .add("verbose", "", "print the status line once a second even without a terminal");
  opts.parse(argc, argv);

  stairs::TrackerConfig config;
  try {
    config = stairs::load_tracker_config(opts.get("config"));
    if (opts.has("reset-after-s")) config.lifecycle.reset_after_s = opts.get_double("reset-after-s");
    stairs::validate(config);
  } catch (const std::exception& e) {
    std::cerr << "stairs-tracker: " << e.what() << "\n";
    return 2;
  }

  if (opts.flag("print-config")) {
    stairs::print_config(std::cout, {{"stair", stairs::config_to_json(stairs::stair_definition(config))},
                                     {"mount", stairs::config_to_json(config.mount)},
                                     {"tracker", stairs::to_json(config)}});
    return 0;
  }
  lcm::LCM lcm(opts.get("lcm-url"));
  if (!lcm.good()) {
    std::cerr << "stairs-tracker: cannot open LCM URL '" << opts.get("lcm-url") << "'\n";
    return 1;
  }
  stairs::install_stop_signals();
  stairs::Tracker tracker(config);
  stairs::StatusReporter status(&lcm, "stairs-tracker", opts.get("status-channel"), opts.flag("verbose"));
  Handler handler{&tracker, &lcm, &status, opts.get("model-channel"), opts.get("steps-channel")};
  lcm.subscribe(opts.get("observation-channel"), &Handler::on_observation, &handler);
  lcm.subscribe(opts.get("odometry-channel"), &Handler::on_odometry, &handler);
  lcm.subscribe(opts.get("command-channel"), &Handler::on_command, &handler);
  while (!stairs::stop_requested()) {
    // A stop signal interrupts the wait: that is no failure.
    if (lcm.handleTimeout(100) < 0 && !stairs::stop_requested()) {
      std::cerr << "stairs-tracker: LCM receive failed\n";
      break;
    }
    status.tick();
  }
  status.final_report();
  return 0;
}
