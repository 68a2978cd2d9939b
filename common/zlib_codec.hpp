// zlib compression of depth buffers (depth_frame_t ENCODING_ZLIB_U16LE).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace stairs {

// Compresses bytes with zlib at the given level (1 = fastest .. 9 = smallest).
std::vector<uint8_t> zlib_compress(const uint8_t* data, size_t size, int level = 1);

// Inflates a zlib stream that must expand to exactly expected_size bytes into `out` (expected_size
// bytes, the caller's: a depth image's own buffer, no copy and no allocation per frame). Returns
// false and sets error on a truncated, corrupt or wrongly sized stream.
bool zlib_decompress(const uint8_t* data, size_t size, uint8_t* out, size_t expected_size, std::string& error);

}  // namespace stairs
