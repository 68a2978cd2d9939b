// Faults around stairs-perception as a real subprocess over UDP multicast on
// loopback: killed (SIGKILL) and restarted mid-stream it resumes from the next
// frame; a stalled consumer makes it drop the oldest frames, each counted, and
// process the newest.
#include "tests/support/daemon_process.hpp"
#include "tests/support/multicast.hpp"
#include "common/lcm_bridge.hpp"
#include "synthetic.hpp"

#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <memory>

namespace stairs {
namespace {

const std::string kUrl = "udpm://239.255.76.67:7694?ttl=0&recv_buf_size=4194304";

struct ObservationSeqs {
  std::vector<int32_t> seqs;  // source_seq of every observation, in arrival order
  int bad = 0;
  void on_obs(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    stair_observation_t msg;
    Observation obs;
    std::string error;
    if (decode_message(rbuf->data, rbuf->data_size, msg, error) && from_lcm(msg, obs, error))
      seqs.push_back(obs.source_seq);
    else
      ++bad;
  }
  bool has(int32_t seq) const { return std::find(seqs.begin(), seqs.end(), seq) != seqs.end(); }
};

class PerceptionFaults : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::ensure_multicast_loopback(kUrl)) GTEST_SKIP() << test::kMulticastSkipReason;
    ASSERT_TRUE(lcm_.good());
    lcm_.subscribe(test::channel("OBS"), &ObservationSeqs::on_obs, &obs_);
    lcm_.subscribe(test::channel("STATUS"), &test::StatusWatch::on_status, &status_);
  }

  // Starts a daemon and waits for its first status message, sent once it has subscribed.
  void start(std::unique_ptr<test::DaemonProcess>& d) {
    d = test::start_daemon(lcm_, status_, "stairs-perception",
                           {"--lcm-url", kUrl, "--depth-channel", test::channel("DEPTH"), "--observation-channel",
                            test::channel("OBS"), "--status-channel", test::channel("STATUS")});
    ASSERT_TRUE(d) << "no status from the new daemon";
  }

  void send(int32_t seq) {
    frame_.seq = seq;
    frame_.utime = 1'000'000 + seq * 33'333;
    const depth_frame_t msg = to_lcm(frame_, 1);
    lcm_.publish(test::channel("DEPTH"), &msg);
  }

  // One frame at a time: the observation of each arrives before the next is sent.
  void send_and_expect(int32_t from, int32_t to) {
    for (int32_t seq = from; seq < to; ++seq) {
      send(seq);
      ASSERT_TRUE(test::pump_until(lcm_, [&] { return obs_.has(seq); })) << "no observation of frame " << seq;
    }
  }

  lcm::LCM lcm_{kUrl};
  ObservationSeqs obs_;
  test::StatusWatch status_{"stairs-perception", {}};
  DepthImage frame_ = test::render_stairs(320, 240, -35, 0, 1.0, 4, 1.2);
};

TEST_F(PerceptionFaults, KilledAndRestartedResumesFromTheNextFrame) {
  std::unique_ptr<test::DaemonProcess> first, second;
  ASSERT_NO_FATAL_FAILURE(start(first));
  ASSERT_NO_FATAL_FAILURE(send_and_expect(0, 10));
  first->kill_hard();
  for (int32_t seq = 10; seq < 15; ++seq) send(seq);  // nobody listens: these are gone
  test::pump(lcm_, 200);

  ASSERT_NO_FATAL_FAILURE(start(second));
  ASSERT_NO_FATAL_FAILURE(send_and_expect(15, 25));
  ASSERT_TRUE(test::pump_until(lcm_, [&] { return status_.last->published == 10; }));
  EXPECT_EQ(status_.last->received, 10);
  EXPECT_EQ(status_.last->dropped, 0);
  EXPECT_TRUE(second->stop_cleanly());

  // Exactly the frames sent while a daemon was up, once each and in order.
  std::vector<int32_t> expected;
  for (int32_t seq = 0; seq < 25; ++seq)
    if (seq < 10 || seq >= 15) expected.push_back(seq);
  EXPECT_EQ(obs_.seqs, expected);
  EXPECT_EQ(obs_.bad, 0);
}

TEST_F(PerceptionFaults, StalledConsumerDropsTheOldestFramesCountedAndProcessesTheNewest) {
  std::unique_ptr<test::DaemonProcess> d;
  ASSERT_NO_FATAL_FAILURE(start(d));
  ASSERT_NO_FATAL_FAILURE(send_and_expect(0, 1));
  // While the daemon is stopped the frames wait in its socket; on SIGCONT they
  // all arrive faster than the worker processes them.
  kill(d->pid(), SIGSTOP);
  const int32_t last = 10;
  for (int32_t seq = 1; seq <= last; ++seq) send(seq);
  test::pump(lcm_, 200);
  kill(d->pid(), SIGCONT);

  ASSERT_TRUE(test::pump_until(lcm_, [&] { return obs_.has(last); })) << "the newest frame was not processed";
  // Idle again: every frame received was either processed or dropped.
  ASSERT_TRUE(test::pump_until(lcm_, [&] {
    return status_.last->received == last + 1 &&
           status_.last->published + status_.last->dropped + status_.last->invalid == status_.last->received;
  })) << "received " << status_.last->received << ", published " << status_.last->published << ", dropped "
      << status_.last->dropped;
  EXPECT_GE(status_.last->dropped, 1);
  EXPECT_EQ(status_.last->invalid, 0);
  EXPECT_EQ(static_cast<int64_t>(obs_.seqs.size()), status_.last->published);
  EXPECT_NE(status_.last->last_error.find("older depth frame replaced"), std::string::npos)
      << status_.last->last_error;
  EXPECT_TRUE(std::is_sorted(obs_.seqs.begin(), obs_.seqs.end()));
  EXPECT_EQ(obs_.seqs.back(), last);
  EXPECT_TRUE(d->stop_cleanly());
}

}  // namespace
}  // namespace stairs
