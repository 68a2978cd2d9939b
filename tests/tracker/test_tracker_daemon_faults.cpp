// Faults around stairs-tracker as a real subprocess over UDP multicast on
// loopback: killed (SIGKILL) and restarted mid-stream it builds a new model from
// the next observation; a 1.2 s gap in the observations is re-localised and an
// out-of-order or repeated utime is dropped and counted, and it keeps publishing;
// odometry on its channel bridges a 5 s gap, and a malformed one is counted;
// the same stream replayed (time back by seconds) resets the model, and so does
// a reset command; every model has a steps-only twin under 2 KB.
#include "tests/support/daemon_process.hpp"
#include "tests/support/multicast.hpp"
#include "common/lcm_bridge.hpp"
#include "drivers/sim/synthetic_observations.hpp"

#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>

namespace stairs {
namespace {

const std::string kUrl = "udpm://239.255.76.67:7695?ttl=0&recv_buf_size=4194304";

struct Models {
  std::map<int32_t, StairModel> by_seq;  // by source_seq
  std::vector<int32_t> order;            // source_seq in arrival order
  std::map<int32_t, std::pair<StairModel, int>> steps_only;  // by source_seq: model, encoded bytes
  int bad = 0;
  void on_steps(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    stair_model_t msg;
    StairModel m;
    std::string error;
    if (!decode_and_convert(rbuf->data, rbuf->data_size, msg, m, error)) ++bad;
    else steps_only[msg.source_seq] = {m, static_cast<int>(rbuf->data_size)};
  }
  void on_model(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    stair_model_t msg;
    StairModel m;
    std::string error;
    if (!decode_and_convert(rbuf->data, rbuf->data_size, msg, m, error)) {
      ++bad;
      return;
    }
    by_seq[msg.source_seq] = m;
    order.push_back(msg.source_seq);
  }
};

class TrackerFaults : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::ensure_multicast_loopback(kUrl)) GTEST_SKIP() << test::kMulticastSkipReason;
    ASSERT_TRUE(lcm_.good());
    lcm_.subscribe(test::channel("MODEL"), &Models::on_model, &models_);
    lcm_.subscribe(test::channel("STEPS"), &Models::on_steps, &models_);
    lcm_.subscribe(test::channel("STATUS"), &test::StatusWatch::on_status, &status_);
  }

  // Starts a daemon and waits for its first status message, sent once it has subscribed.
  void start(std::unique_ptr<test::DaemonProcess>& d, const std::string& stderr_file = "") {
    d = test::start_daemon(lcm_, status_, "stairs-tracker",
                           {"--lcm-url", kUrl, "--observation-channel", test::channel("OBS"), "--model-channel",
                            test::channel("MODEL"), "--status-channel", test::channel("STATUS"),
                            "--odometry-channel", test::channel("ODOM"), "--steps-channel", test::channel("STEPS"),
                            "--command-channel", test::channel("CMD")},
                           stderr_file);
    ASSERT_TRUE(d) << "no status from the new daemon";
  }

  // The observation from walk position `k` at that position's utime, tagged `seq`.
  void send(size_t k, int32_t seq, int64_t utime) {
    Observation obs = maker_.make(cams_.at(k), utime);
    obs.source_seq = seq;
    const stair_observation_t msg = to_lcm(obs, utime);
    lcm_.publish(test::channel("OBS"), &msg);
  }
  void send(size_t k) { send(k, static_cast<int32_t>(k), static_cast<int64_t>(k) * 33'333); }

  // Odometry of walk position k: the camera's optical frame in an odometry
  // frame turned 1 rad and shifted against the stair frame.
  void send_odometry(size_t k) {
    const synthetic::CameraState& c = cams_.at(k);
    const double h = c.heading_rad, p = c.pitch_rad;
    const Eigen::Vector3d z(std::cos(p) * std::cos(h), std::cos(p) * std::sin(h), std::sin(p));
    const Eigen::Vector3d x(std::sin(h), -std::cos(h), 0.0);
    Eigen::Matrix3d optical;
    optical << x, z.cross(x), z;
    const Eigen::AngleAxisd odometry_frame(1.0, Eigen::Vector3d::UnitZ());
    OdometrySample o;
    o.utime = static_cast<int64_t>(k) * 33'333;
    o.position_m = odometry_frame * c.position_m + Eigen::Vector3d(3.0, -2.0, 0.0);
    o.orientation = Eigen::Quaterniond(odometry_frame.toRotationMatrix() * optical);
    const pose_t msg = to_lcm(o);
    lcm_.publish(test::channel("ODOM"), &msg);
  }

  // Walk positions [from, to), one at a time, tagged seq_offset + k: each
  // model arrives before the next observation goes.
  void send_and_expect(size_t from, size_t to, int32_t seq_offset = 0) {
    for (size_t k = from; k < to; ++k) {
      const int32_t seq = seq_offset + static_cast<int32_t>(k);
      send(k, seq, static_cast<int64_t>(k) * 33'333);
      ASSERT_TRUE(test::pump_until(lcm_, [&] { return models_.by_seq.count(seq) > 0; })) << "no model for observation " << seq;
    }
  }


  const StairModel& model(size_t k) { return models_.by_seq.at(static_cast<int32_t>(k)); }

  lcm::LCM lcm_{kUrl};
  Models models_;
  test::StatusWatch status_{"stairs-tracker", {}};
  const synthetic::StairGeometry stair_ = synthetic::make_stair(9, 0.17, 0.28, 1.5);
  synthetic::ObservationMaker maker_{stair_, 21, 256};
  const std::vector<synthetic::CameraState> cams_ = synthetic::walk(stair_, true, 0.6, 30.0);
};

TEST_F(TrackerFaults, KilledAndRestartedBuildsANewModelFromTheNextObservation) {
  std::unique_ptr<test::DaemonProcess> first, second;
  ASSERT_NO_FATAL_FAILURE(start(first));
  ASSERT_NO_FATAL_FAILURE(send_and_expect(0, 30));
  EXPECT_GT(model(29).observations_fused, 15);
  first->kill_hard();
  for (size_t k = 30; k < 40; ++k) send(k);  // nobody listens: these are gone
  test::pump(lcm_, 200);

  ASSERT_NO_FATAL_FAILURE(start(second));
  ASSERT_NO_FATAL_FAILURE(send_and_expect(40, 100));
  // The first observation after the restart seeds the new model, which then tracks.
  EXPECT_EQ(model(40).observations_fused, 1);
  EXPECT_GT(model(99).observations_fused, 30);
  EXPECT_EQ(model(99).state, TrackingState::Ok);
  ASSERT_TRUE(test::pump_until(lcm_, [&] { return status_.last->published == 60; }));
  EXPECT_EQ(status_.last->received, 60);
  EXPECT_EQ(status_.last->dropped, 0);
  EXPECT_TRUE(second->stop_cleanly());
  for (size_t k = 30; k < 40; ++k) EXPECT_EQ(models_.by_seq.count(static_cast<int32_t>(k)), 0u) << k;
  EXPECT_EQ(models_.bad, 0);
}

TEST_F(TrackerFaults, GapAndOutOfOrderUtimesAreHandledCountedAndItKeepsPublishing) {
  std::unique_ptr<test::DaemonProcess> d;
  ASSERT_NO_FATAL_FAILURE(start(d));
  ASSERT_NO_FATAL_FAILURE(send_and_expect(0, 30));
  const int fused_before_gap = model(29).observations_fused;
  // Walk positions 30..65 are never observed: 1.2 s of utimes missing.
  ASSERT_NO_FATAL_FAILURE(send_and_expect(66, 90));
  EXPECT_EQ(model(66).state, TrackingState::Relocalised) << model(66).status;
  EXPECT_EQ(model(89).state, TrackingState::Ok) << model(89).status;
  EXPECT_GT(model(89).observations_fused, fused_before_gap + 15);

  // An old utime and a repeated one: dropped without a model, then the next in-order one is fused.
  send(80, 1001, 80 * 33'333);
  send(89, 1002, 89 * 33'333);
  ASSERT_NO_FATAL_FAILURE(send_and_expect(90, 100));
  EXPECT_EQ(models_.by_seq.count(1001), 0u);
  EXPECT_EQ(models_.by_seq.count(1002), 0u);
  EXPECT_EQ(model(99).state, TrackingState::Ok) << model(99).status;
  EXPECT_GT(model(99).observations_fused, model(89).observations_fused + 5);

  const int64_t sent = 30 + 24 + 2 + 10;
  ASSERT_TRUE(test::pump_until(lcm_, [&] { return status_.last->received == sent; }));
  EXPECT_EQ(status_.last->dropped, 2);
  EXPECT_EQ(status_.last->published, sent - 2);
  EXPECT_EQ(status_.last->invalid, 0);
  EXPECT_NE(status_.last->last_error.find("out-of-order"), std::string::npos) << status_.last->last_error;
  EXPECT_EQ(static_cast<int64_t>(models_.order.size()), sent - 2);
  EXPECT_TRUE(d->stop_cleanly());
}

// Odometry on its channel bridges 5 s without observations: the model is kept
// and the first observation after the gap registers to it (without odometry
// the model is dropped and seeded again, see Tracker.EmptyObservationsLoseThenResetTheModel).
// A malformed odometry message is counted as invalid and changes nothing.
TEST_F(TrackerFaults, OdometryKeepsTheModelAcrossAFiveSecondGap) {
  std::unique_ptr<test::DaemonProcess> d;
  ASSERT_NO_FATAL_FAILURE(start(d));
  for (size_t k = 0; k < 30; ++k) {
    send_odometry(k);
    ASSERT_NO_FATAL_FAILURE(send_and_expect(k, k + 1));
  }
  const int fused_before_gap = model(29).observations_fused;
  for (size_t k = 30; k < 180; ++k) {  // 5 s: odometry only, paced (a burst can overflow a socket buffer)
    send_odometry(k);
    test::pump(lcm_, 2);
  }
  pose_t bad = to_lcm(OdometrySample{});
  bad.orientation[0] = 3.0;
  lcm_.publish(test::channel("ODOM"), &bad);
  for (size_t k = 180; k < 200; ++k) {
    send_odometry(k);
    ASSERT_NO_FATAL_FAILURE(send_and_expect(k, k + 1));
  }
  EXPECT_EQ(model(180).observations_fused, fused_before_gap + 1) << model(180).status;
  EXPECT_EQ(model(181).observations_fused, fused_before_gap + 2) << model(181).status;
  EXPECT_EQ(model(181).status, "ok");
  // Near the top no step is in view any more: odometry alone keeps the camera.
  EXPECT_TRUE(model(199).camera_valid) << model(199).status;
  EXPECT_NEAR(model(199).camera_position_m.x() - model(29).camera_position_m.x(),
              cams_[199].position_m.x() - cams_[29].position_m.x(), 0.05);
  ASSERT_TRUE(test::pump_until(lcm_, [&] { return status_.last->invalid == 1; }));
  EXPECT_NE(status_.last->last_error.find("odometry"), std::string::npos) << status_.last->last_error;
  EXPECT_TRUE(d->stop_cleanly());
}

// Issue 18: the same stream twice (lcm-logplayer run again): time goes back by
// seconds, the daemon resets its model, says so, and every observation of the
// second pass gives a model again.
TEST_F(TrackerFaults, ALogReplayedTwiceGivesAModelForEveryObservationOfTheSecondPass) {
  std::unique_ptr<test::DaemonProcess> d;
  ASSERT_NO_FATAL_FAILURE(start(d));
  ASSERT_NO_FATAL_FAILURE(send_and_expect(0, 60));
  const int fused_first = model(59).observations_fused;
  ASSERT_NO_FATAL_FAILURE(send_and_expect(0, 60, 1000));  // the same utimes again
  EXPECT_EQ(models_.by_seq.at(1000).observations_fused, 1) << models_.by_seq.at(1000).status;
  EXPECT_EQ(models_.by_seq.at(1059).observations_fused, fused_first);
  EXPECT_FALSE(models_.by_seq.at(1059).flights.empty());
  ASSERT_TRUE(test::pump_until(lcm_, [&] { return status_.last->received == 120; }));
  EXPECT_EQ(status_.last->dropped, 0);
  EXPECT_NE(status_.last->last_error.find("time went back"), std::string::npos) << status_.last->last_error;
  EXPECT_TRUE(d->stop_cleanly());
}

// Issue 18 item 1: a reset on request (the robot carried to another stair)
// drops the model, says so in the status, and the next observation starts a
// new one; an unknown command is counted as invalid and changes nothing.
TEST_F(TrackerFaults, AResetCommandDropsTheModelAndSaysSo) {
  std::unique_ptr<test::DaemonProcess> d;
  ASSERT_NO_FATAL_FAILURE(start(d));
  ASSERT_NO_FATAL_FAILURE(send_and_expect(0, 40));
  ASSERT_GT(model(39).observations_fused, 10);
  tracker_command_t cmd{};
  cmd.utime = 1;
  cmd.command = 7;
  lcm_.publish(test::channel("CMD"), &cmd);
  ASSERT_TRUE(test::pump_until(lcm_, [&] { return status_.last && status_.last->invalid == 1; }));
  ASSERT_NO_FATAL_FAILURE(send_and_expect(40, 41));
  EXPECT_EQ(model(40).observations_fused, model(39).observations_fused + 1) << "an unknown command reset the model";
  cmd.command = tracker_command_t::COMMAND_RESET;
  cmd.reason = "operator: new stair";
  lcm_.publish(test::channel("CMD"), &cmd);
  ASSERT_TRUE(test::pump_until(lcm_, [&] {
    return status_.last && status_.last->last_error.find("model reset on request: operator: new stair") != std::string::npos;
  }));
  ASSERT_NO_FATAL_FAILURE(send_and_expect(41, 60));
  EXPECT_EQ(model(41).observations_fused, 1) << model(41).status;
  EXPECT_FALSE(model(59).flights.empty()) << "the new model is confirmed again";
  EXPECT_TRUE(d->stop_cleanly());
}

// Issue 18 item 10: every model also goes out without its plane samples, under
// 2 KB, with the same steps and camera.
TEST_F(TrackerFaults, EveryModelHasAStepsOnlyTwinUnderTwoKilobytes) {
  std::unique_ptr<test::DaemonProcess> d;
  ASSERT_NO_FATAL_FAILURE(start(d));
  ASSERT_NO_FATAL_FAILURE(send_and_expect(0, 60));
  ASSERT_TRUE(test::pump_until(lcm_, [&] { return models_.steps_only.size() == 60; }));
  size_t steps_seen = 0;
  for (int seq = 0; seq < 60; ++seq) {
    const StairModel& full = models_.by_seq.at(seq);
    const auto& [twin, bytes] = models_.steps_only.at(seq);
    EXPECT_LT(bytes, 2048) << "observation " << seq;
    EXPECT_TRUE(twin.planes.empty());
    ASSERT_EQ(twin.flights.size(), full.flights.size());
    for (size_t f = 0; f < full.flights.size(); ++f) {
      ASSERT_EQ(twin.flights[f].steps.size(), full.flights[f].steps.size());
      for (size_t k = 0; k < full.flights[f].steps.size(); ++k) {
        EXPECT_EQ(twin.flights[f].steps[k].nosing_m, full.flights[f].steps[k].nosing_m);
        ++steps_seen;
      }
    }
    EXPECT_EQ(twin.camera_position_m, full.camera_position_m);
  }
  EXPECT_GT(steps_seen, 60u);
  EXPECT_EQ(models_.bad, 0);
  EXPECT_TRUE(d->stop_cleanly());
}

// Issue 18: under systemd or journald stderr is no terminal; the daemon still
// prints a status line every 10 s (and events such as a reset as they happen).
TEST_F(TrackerFaults, OffATerminalAStatusLineEveryTenSeconds) {
  const std::string err = std::string(STAIRS_BINARY_DIR) + "/" + test::channel("tracker_stderr.txt");
  std::unique_ptr<test::DaemonProcess> d;
  ASSERT_NO_FATAL_FAILURE(start(d, err));
  ASSERT_NO_FATAL_FAILURE(send_and_expect(0, 5));
  const auto read_all = [&] {
    std::ifstream in(err);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  test::pump(lcm_, 11'500);
  const std::string text = read_all();
  EXPECT_NE(text.find("stairs-tracker: 5 in, 5 out"), std::string::npos) << text;
  EXPECT_TRUE(d->stop_cleanly());
  std::remove(err.c_str());
}

}  // namespace
}  // namespace stairs

