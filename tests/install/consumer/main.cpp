// Encodes a steps-only stair model and decodes it again with the installed
// headers; prints the fingerprint so the test can compare it with the build's.
#include <lcm/lcm-cpp.hpp>
#include <stairs/stair_model_t.hpp>

#include <cstdio>
#include <vector>

int main() {
  stairs::stair_model_t m{};
  m.num_flights = 1;
  m.flights.resize(1);
  m.flights[0].num_steps = 2;
  m.flights[0].steps.resize(2);
  m.flights[0].steps[1].riser_height_m = 0.17f;
  m.status = "consumer";
  std::vector<unsigned char> buf(m.getEncodedSize());
  m.encode(buf.data(), 0, static_cast<int>(buf.size()));
  stairs::stair_model_t back;
  if (back.decode(buf.data(), 0, static_cast<int>(buf.size())) < 0 || back.flights[0].steps[1].riser_height_m != 0.17f)
    return 1;
  std::printf("%016llx\n", static_cast<unsigned long long>(stairs::stair_model_t::getHash()));
  lcm::LCM lcm("memq://");  // links against liblcm
  return lcm.good() ? 0 : 1;
}
