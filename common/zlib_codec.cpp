#include "common/zlib_codec.hpp"

#include <zlib.h>

#include <stdexcept>

namespace stairs {

std::vector<uint8_t> zlib_compress(const uint8_t* data, size_t size, int level) {
  uLongf bound = compressBound(static_cast<uLong>(size));
  std::vector<uint8_t> out(bound);
  if (compress2(out.data(), &bound, data, static_cast<uLong>(size), level) != Z_OK)
    throw std::runtime_error("zlib compress2 failed");
  out.resize(bound);
  return out;
}

bool zlib_decompress(const uint8_t* data, size_t size, uint8_t* out, size_t expected_size, std::string& error) {
  z_stream zs{};
  if (inflateInit(&zs) != Z_OK) {
    error = "zlib inflateInit failed";
    return false;
  }
  zs.next_in = const_cast<Bytef*>(data);
  zs.avail_in = static_cast<uInt>(size);
  zs.next_out = out;
  zs.avail_out = static_cast<uInt>(expected_size);
  const int rc = inflate(&zs, Z_FINISH);
  const size_t produced = expected_size - zs.avail_out;
  inflateEnd(&zs);
  if (rc == Z_STREAM_END && produced == expected_size) return true;
  if (rc == Z_BUF_ERROR && zs.avail_out == 0)
    error = "zlib stream expands beyond the declared " + std::to_string(expected_size) + " bytes";
  else if (rc == Z_BUF_ERROR || (rc == Z_STREAM_END && produced < expected_size))
    error = "zlib stream truncated: " + std::to_string(produced) + " of " +
            std::to_string(expected_size) + " bytes";
  else
    error = std::string("zlib stream corrupt: ") + (zs.msg ? zs.msg : "inflate error");
  return false;
}

}  // namespace stairs
