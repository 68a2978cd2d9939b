// libFuzzer target: the sequence-directory parser (camera.json, depth.txt,
// groundtruth.json). The input is split at NUL bytes into the three files.
#include "common/sequence.hpp"

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace fs = std::filesystem;
  static const fs::path dir = fs::temp_directory_path() / ("stairs_fuzz_seq_" + std::to_string(::getpid()));
  fs::create_directories(dir / "depth");
  const std::string in(reinterpret_cast<const char*>(data), size);
  const char* names[] = {"camera.json", "depth.txt", "groundtruth.json"};
  size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const size_t end = std::min(in.find('\0', start), in.size());
    fs::remove(dir / names[i]);
    if (start <= in.size()) std::ofstream(dir / names[i], std::ios::binary) << in.substr(start, end - start);
    start = end + 1;
  }
  try {
    stairs::SequenceReader reader(dir.string());
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
