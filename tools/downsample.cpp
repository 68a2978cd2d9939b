#include "tools/downsample.hpp"

#include "common/cloud.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace stairs::eval {

void parse_resolution(const std::string& text, int& width, int& height) {
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &width, &x, &height, &extra) != 3 || x != 'x' || width <= 0 ||
      height <= 0)
    throw std::invalid_argument("--resolution '" + text + "': expected WxH, e.g. 320x240");
}

int downsample_factor(const Intrinsics& K, int width, int height) {
  if (width <= 0 || height <= 0 || K.width % width != 0 || K.height % height != 0 ||
      K.width / width != K.height / height)
    throw std::invalid_argument("--resolution " + std::to_string(width) + "x" + std::to_string(height) +
                                ": not a whole fraction of the input's " + std::to_string(K.width) + "x" +
                                std::to_string(K.height));
  return K.width / width;
}

DepthImage downsample(const DepthImage& in, int factor) {
  if (factor <= 1) return in;
  DepthImage out;
  out.K = scale_intrinsics(in.K, in.K.width / factor, in.K.height / factor);
  out.depth_scale = in.depth_scale;
  out.utime = in.utime;
  out.seq = in.seq;
  out.depth.assign(static_cast<size_t>(out.K.width) * out.K.height, 0);
  for (int v = 0; v < out.K.height; ++v) {
    for (int u = 0; u < out.K.width; ++u) {
      uint16_t nearest = 0;
      for (int dv = 0; dv < factor; ++dv)
        for (int du = 0; du < factor; ++du) {
          const uint16_t d = in.depth[static_cast<size_t>(v * factor + dv) * in.K.width + u * factor + du];
          if (d && (!nearest || d < nearest)) nearest = d;
        }
      if (!nearest) continue;
      const uint32_t limit = nearest + nearest / 20;
      uint32_t sum = 0, n = 0;
      for (int dv = 0; dv < factor; ++dv)
        for (int du = 0; du < factor; ++du) {
          const uint16_t d = in.depth[static_cast<size_t>(v * factor + dv) * in.K.width + u * factor + du];
          if (d && d <= limit) {
            sum += d;
            ++n;
          }
        }
      out.depth[static_cast<size_t>(v) * out.K.width + u] = static_cast<uint16_t>((sum + n / 2) / n);
    }
  }
  return out;
}

}  // namespace stairs::eval
