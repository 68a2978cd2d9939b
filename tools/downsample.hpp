// Integer-factor downsampling of depth images, so one recording can be
// benchmarked at 640x480 and 320x240.
#pragma once

#include "common/types.hpp"

#include <string>

namespace stairs::eval {

// Parses "WxH" (e.g. 320x240); throws std::invalid_argument naming "--resolution".
void parse_resolution(const std::string& text, int& width, int& height);

// The factor that takes K to width x height; throws std::invalid_argument
// naming "--resolution" when it is not a whole divisor of both sides.
int downsample_factor(const Intrinsics& K, int width, int height);

// Each factor x factor block becomes one pixel: the mean of its valid depths
// within 5% of the block's nearest one, so a depth edge keeps its foreground
// instead of inventing a point between two surfaces. Intrinsics follow the
// block centres (common/cloud.hpp scale_intrinsics).
DepthImage downsample(const DepthImage& in, int factor);

}  // namespace stairs::eval
