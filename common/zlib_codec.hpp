// zlib compression of depth buffers (depth_frame_t ENCODING_ZLIB_U16LE).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace stairs {

// Compresses bytes with zlib at the given level (1 = fastest .. 9 = smallest).
std::vector<uint8_t> zlib_compress(const uint8_t* data, size_t size, int level = 1);

// Inflates a zlib stream that must expand to exactly expected_size bytes; never
// allocates more than expected_size. Returns false and sets error on a
// truncated, corrupt or wrongly sized stream.
bool zlib_decompress(const uint8_t* data, size_t size, size_t expected_size,
                     std::vector<uint8_t>& out, std::string& error);

}  // namespace stairs
