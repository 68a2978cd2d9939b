// Writes OpenNI .oni recordings of depth images, without OpenNI2: one depth
// node, uncompressed ('NONE' codec), DEPTH_1_MM, with the properties the
// OpenNI2 file player needs (xnCropping, xnFOV, xnMapOutputMode, ...), a seek
// table and the end record. Files play back through openni::Device::open(path).
#pragma once

#include "common/types.hpp"

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace stairs {

class OniWriter {
 public:
  // Writes PATH.partial; close() completes the file and renames it to PATH.
  // The field of view written to the file is taken from the first frame's
  // intrinsics (hfov = 2 atan(width / 2 / fx)). Throws "PATH: reason".
  OniWriter(const std::string& path, int width, int height, int fps);
  // Depth is stored in mm (converted from frame.depth_scale, rounded, clamped
  // to 65535). The timestamp is frame.utime relative to the first frame, us.
  // Throws on a size mismatch, a decreasing utime, or a write error.
  void write(const DepthImage& frame);
  void close();
  ~OniWriter();

  OniWriter(const OniWriter&) = delete;
  OniWriter& operator=(const OniWriter&) = delete;

 private:
  struct SeekEntry {
    uint64_t timestamp_us;
    uint64_t position;
  };
  void write_preamble(const Intrinsics& K);
  void write_bytes(const void* data, size_t size);
  uint64_t tell() const;

  std::string path_;
  int width_, height_, fps_;
  std::FILE* file_ = nullptr;
  bool started_ = false;
  int64_t first_utime_ = 0;
  uint64_t last_timestamp_us_ = 0;
  uint64_t node_added_pos_ = 0;
  uint64_t last_data_pos_ = 0;
  std::vector<SeekEntry> seek_;
  std::vector<uint16_t> mm_;  // conversion buffer
};

}  // namespace stairs
