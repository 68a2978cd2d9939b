// OpenNI2 frame buffers -> depth_frame_t, without OpenNI2 headers so that the
// conversion is testable anywhere. OpenNI delivers DEPTH_1_MM pixels in host
// byte order (little-endian on x86/ARM) with a row stride that may exceed the
// width; depth_frame_t carries little-endian rows without padding.
#pragma once

#include "common/types.hpp"

#include <stairs/depth_frame_t.hpp>

#include <cstdint>

namespace stairs {

// Pinhole intrinsics of a width x height image from OpenNI's fields of view:
// fx = width / 2 / tan(hfov / 2), fy likewise, principal point at the centre
// ((width - 1) / 2, cx counted from the centre of the first pixel).
Intrinsics intrinsics_from_fov(int width, int height, double hfov_rad, double vfov_rad);

struct FrameBuffer {
  const void* data = nullptr;
  int width = 0;         // px
  int height = 0;        // px
  int stride_bytes = 0;  // bytes per row, >= width * bytes per pixel
};

// One depth frame (uint16 mm) and optionally its registered RGB888 colour
// image as a depth_frame_t. zlib_level 0 = raw. Throws std::invalid_argument
// on a buffer that does not match its declared size or the message caps.
depth_frame_t depth_frame_from_openni(const FrameBuffer& depth, const Intrinsics& K, int64_t utime,
                                      int64_t device_timestamp_us, int32_t seq, int zlib_level,
                                      const FrameBuffer* color_rgb888 = nullptr);

// Maps a device clock (us) to the host wall clock: the offset is taken at the
// first frame, and again whenever the device clock jumps backwards (device
// reset, a recording that loops).
class DeviceClock {
 public:
  int64_t to_utime(uint64_t device_us, int64_t host_now_utime);
  int resyncs() const { return resyncs_; }

 private:
  bool anchored_ = false;
  uint64_t last_device_us_ = 0;
  int64_t offset_us_ = 0;
  int resyncs_ = 0;
};

}  // namespace stairs
