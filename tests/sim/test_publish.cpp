// stairs-sim publishing over real LCM (UDP multicast on loopback, two
// processes): every depth frame has its ground truth with the same utime and seq.
#include "tests/support/multicast.hpp"
#include "common/lcm_bridge.hpp"

#include <lcm/lcm-cpp.hpp>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <map>
#include <thread>

namespace {

const std::string kUrl = "udpm://239.255.76.67:7689?ttl=0&recv_buf_size=4194304";

struct Collector {
  std::map<int32_t, int64_t> depth, truth;  // seq -> utime
  int invalid = 0;
  void on_depth(const lcm::ReceiveBuffer* rb, const std::string&) {
    stairs::depth_frame_t m;
    stairs::DepthImage img;
    std::string err;
    if (stairs::decode_message(rb->data, rb->data_size, m, err) && stairs::from_lcm(m, img, err))
      depth[img.seq] = img.utime;
    else
      ++invalid;
  }
  void on_truth(const lcm::ReceiveBuffer* rb, const std::string&) {
    stairs::ground_truth_t m;
    std::string err;
    if (stairs::decode_message(rb->data, rb->data_size, m, err)) truth[m.seq] = m.utime;
    else ++invalid;
  }
};

}  // namespace

TEST(SimPublish, DepthAndTruthPairedOverUdpm) {
  if (!stairs::test::ensure_multicast_loopback(kUrl)) GTEST_SKIP() << stairs::test::kMulticastSkipReason;
  lcm::LCM sub(kUrl);
  ASSERT_TRUE(sub.good());
  Collector c;
  sub.subscribe("SIM_DEPTH_TEST", &Collector::on_depth, &c);
  sub.subscribe("SIM_TRUTH_TEST", &Collector::on_truth, &c);
  const int n = 20;
  const std::string cmd = std::string(STAIRS_BINARY_DIR) + "/bin/stairs-sim --resolution 320x240 --frames " +
                          std::to_string(n) + " --lcm-url '" + kUrl +
                          "' --depth-channel SIM_DEPTH_TEST --truth-channel SIM_TRUTH_TEST --status-channel SIM_STATUS_TEST"
                          " 2>/dev/null";
  int rc = -1;
  std::thread publisher([&] { rc = std::system(cmd.c_str()); });
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while ((static_cast<int>(c.depth.size()) < n || static_cast<int>(c.truth.size()) < n) &&
         std::chrono::steady_clock::now() < deadline)
    sub.handleTimeout(100);
  publisher.join();
  EXPECT_EQ(rc, 0);
  EXPECT_EQ(c.invalid, 0);
  ASSERT_EQ(static_cast<int>(c.depth.size()), n);
  EXPECT_EQ(c.truth, c.depth);  // same seq -> same utime, for every frame
  EXPECT_EQ(c.depth.begin()->first, 0);
  EXPECT_EQ(c.depth.rbegin()->first, n - 1);
}
