// Fuzz inputs without the 8-byte LCM fingerprint: random bytes almost never
// carry a type's hash, so a target that fed them raw would only ever test the
// hash check. with_fingerprint<T>() prepends T's hash (big-endian, as LCM
// encodes it) so the mutations reach the message body and its validation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace stairs::fuzz {

template <class T>
std::vector<uint8_t> with_fingerprint(const uint8_t* body, size_t size) {
  const uint64_t hash = static_cast<uint64_t>(T::getHash());
  std::vector<uint8_t> out(8 + size);
  for (int i = 0; i < 8; ++i) out[i] = static_cast<uint8_t>(hash >> (56 - 8 * i));
  if (size > 0) std::copy(body, body + size, out.begin() + 8);
  return out;
}

}  // namespace stairs::fuzz
