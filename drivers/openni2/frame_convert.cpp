#include "drivers/openni2/frame_convert.hpp"

#include "common/lcm_bridge.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace stairs {

Intrinsics intrinsics_from_fov(int width, int height, double hfov_rad, double vfov_rad) {
  if (width <= 0 || height <= 0 || !(hfov_rad > 0 && hfov_rad < M_PI) || !(vfov_rad > 0 && vfov_rad < M_PI))
    throw std::invalid_argument("field of view " + std::to_string(hfov_rad) + " x " + std::to_string(vfov_rad) +
                                " rad for " + std::to_string(width) + "x" + std::to_string(height) +
                                " is not a camera's");
  Intrinsics K;
  K.width = width;
  K.height = height;
  K.fx = width / 2.0 / std::tan(hfov_rad / 2.0);
  K.fy = height / 2.0 / std::tan(vfov_rad / 2.0);
  K.cx = (width - 1) / 2.0;
  K.cy = (height - 1) / 2.0;
  return K;
}

namespace {
void check_buffer(const FrameBuffer& b, int bytes_per_pixel, const char* what) {
  if (!b.data || b.width <= 0 || b.height <= 0 || b.stride_bytes < b.width * bytes_per_pixel)
    throw std::invalid_argument(std::string(what) + " buffer " + std::to_string(b.width) + "x" +
                                std::to_string(b.height) + " stride " + std::to_string(b.stride_bytes) +
                                " is inconsistent");
}
}  // namespace

depth_frame_t depth_frame_from_openni(const FrameBuffer& depth, const Intrinsics& K, int64_t utime,
                                      int64_t device_timestamp_us, int32_t seq, int zlib_level,
                                      const FrameBuffer* color) {
  check_buffer(depth, 2, "depth");
  if (depth.width != K.width || depth.height != K.height)
    throw std::invalid_argument("depth buffer " + std::to_string(depth.width) + "x" + std::to_string(depth.height) +
                                " does not match intrinsics " + std::to_string(K.width) + "x" +
                                std::to_string(K.height));
  if (depth.width > depth_frame_t::MAX_WIDTH || depth.height > depth_frame_t::MAX_HEIGHT)
    throw std::invalid_argument("depth frame larger than depth_frame_t allows");
  DepthImage img;
  img.K = K;
  img.depth_scale = 0.001;  // DEPTH_1_MM
  img.utime = utime;
  img.seq = seq;
  img.depth.resize(static_cast<size_t>(depth.width) * depth.height);
  const auto* src = static_cast<const uint8_t*>(depth.data);
  for (int v = 0; v < depth.height; ++v)
    std::memcpy(&img.depth[static_cast<size_t>(v) * depth.width], src + static_cast<size_t>(v) * depth.stride_bytes,
                static_cast<size_t>(depth.width) * 2);
  depth_frame_t msg = to_lcm(img, zlib_level, "camera_depth_optical_frame");
  msg.device_timestamp_us = device_timestamp_us;
  if (color) {
    check_buffer(*color, 3, "colour");
    const size_t row = static_cast<size_t>(color->width) * 3;
    if (row * color->height > static_cast<size_t>(depth_frame_t::MAX_COLOR_BYTES))
      throw std::invalid_argument("colour image larger than depth_frame_t allows");
    msg.color_encoding = depth_frame_t::COLOR_RGB8;
    msg.color_width = color->width;
    msg.color_height = color->height;
    msg.color_data.resize(row * color->height);
    const auto* c = static_cast<const uint8_t*>(color->data);
    for (int v = 0; v < color->height; ++v)
      std::memcpy(&msg.color_data[row * v], c + static_cast<size_t>(v) * color->stride_bytes, row);
    msg.color_size = static_cast<int32_t>(msg.color_data.size());
  }
  return msg;
}

int64_t DeviceClock::to_utime(uint64_t device_us, int64_t host_now_utime) {
  if (!anchored_ || device_us < last_device_us_) {
    if (anchored_) ++resyncs_;
    offset_us_ = host_now_utime - static_cast<int64_t>(device_us);
    anchored_ = true;
  }
  last_device_us_ = device_us;
  return static_cast<int64_t>(device_us) + offset_us_;
}

}  // namespace stairs
