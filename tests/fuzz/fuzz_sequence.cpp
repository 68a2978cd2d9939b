// libFuzzer target: the sequence-directory parser (camera.json, depth.txt,
// groundtruth.json, and the optional imu.txt and odometry.txt). The input is
// split at NUL bytes into the five files; a file past the input's end is absent.
#include "common/sequence.hpp"

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace fs = std::filesystem;
  static const fs::path dir = fs::temp_directory_path() / ("stairs_fuzz_seq_" + std::to_string(::getpid()));
  fs::create_directories(dir / "depth");
  const std::string in(reinterpret_cast<const char*>(data), size);
  const char* names[] = {"camera.json", "depth.txt", "groundtruth.json", "imu.txt", "odometry.txt"};
  size_t start = 0;
  for (int i = 0; i < 5; ++i) {
    const size_t end = std::min(in.find('\0', start), in.size());
    fs::remove(dir / names[i]);
    if (start <= in.size()) std::ofstream(dir / names[i], std::ios::binary) << in.substr(start, end - start);
    start = end + 1;
  }
  try {
    stairs::SequenceReader reader(dir.string());
    for (const stairs::ImuSample& s : reader.imu())
      if (!s.specific_force_mps2.allFinite() || !s.angular_rate_radps.allFinite()) std::abort();
    for (size_t i = 1; i < reader.odometry().size(); ++i)  // promised: in time order, finite
      if (reader.odometry()[i].utime < reader.odometry()[i - 1].utime ||
          !reader.odometry()[i].position_m.allFinite())
        std::abort();
    for (size_t i = 0; i < reader.size() && i < 4; ++i) {
      try {
        reader.read(i);
      } catch (const std::runtime_error&) {
      }
    }
  } catch (const std::runtime_error&) {
  }
  return 0;
}
