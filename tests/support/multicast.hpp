// UDP multicast on loopback for the integration tests: probes that a message
// published on `url` comes back, adding the multicast route if it does not.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <cstdlib>
#include <string>

namespace stairs::test {

inline bool multicast_loops_back(const std::string& url) {
  lcm::LCM lcm(url);
  if (!lcm.good()) return false;
  bool got = false;
  struct Handler {
    bool* got;
    void on(const lcm::ReceiveBuffer*, const std::string&) { *got = true; }
  } handler{&got};
  lcm.subscribe("STAIRS_TEST_PROBE", &Handler::on, &handler);
  const uint8_t byte = 1;
  for (int i = 0; i < 10 && !got; ++i) {
    lcm.publish("STAIRS_TEST_PROBE", &byte, 1);
    lcm.handleTimeout(100);
  }
  return got;
}

// True when multicast works on `url`, after adding "224.0.0.0/4 dev lo" if
// needed (root or CAP_NET_ADMIN). Callers skip with kMulticastSkipReason otherwise.
inline bool ensure_multicast_loopback(const std::string& url) {
  return multicast_loops_back(url) ||
         (std::system("ip route add 224.0.0.0/4 dev lo 2>/dev/null") == 0 && multicast_loops_back(url));
}

inline constexpr const char* kMulticastSkipReason =
    "UDP multicast does not loop back here and no route could be added "
    "(run as root: ip route add 224.0.0.0/4 dev lo)";

}  // namespace stairs::test
