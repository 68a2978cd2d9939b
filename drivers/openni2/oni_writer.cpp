#include "drivers/openni2/oni_writer.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace stairs {

// Record layout of OpenNI's file format 1.0.1.0 (Source/Drivers/OniFile in
// OpenNI2): little-endian, packed, every record starts with a 28-byte header.
namespace {

constexpr uint32_t kRecordMagic = 0x0052494E;  // "NIR\0"
enum RecordType : uint32_t {
  kIntProperty = 0x03,
  kGeneralProperty = 0x06,
  kNodeDataBegin = 0x08,
  kNodeStateReady = 0x09,
  kNewData = 0x0A,
  kEnd = 0x0B,
  kNodeAdded = 0x0D,
  kSeekTable = 0x0E,
};
constexpr uint32_t kNodeId = 1;          // OpenNI's recorder numbers nodes from 1
constexpr uint32_t kNodeTypeDepth = 2;   // XN_NODE_TYPE_DEPTH
constexpr uint32_t kCodecNone = 'N' | ('O' << 8) | ('N' << 16) | (static_cast<uint32_t>('E') << 24);
constexpr uint64_t kPixelFormatDepth1mm = 100;  // ONI_PIXEL_FORMAT_DEPTH_1_MM
constexpr uint64_t kXnPixelFormatGray16 = 4;    // XN_PIXEL_FORMAT_GRAYSCALE_16_BIT
constexpr uint64_t kMaxDepthMm = 65535;
constexpr size_t kRecordHeaderBytes = 28;

// Appends little-endian scalars and strings to a byte buffer (x86/ARM hosts).
struct Bytes {
  std::vector<uint8_t> b;
  template <class T>
  Bytes& put(T v) {
    const auto* p = reinterpret_cast<const uint8_t*>(&v);
    b.insert(b.end(), p, p + sizeof(T));
    return *this;
  }
  Bytes& raw(const void* data, size_t size) {
    const auto* p = static_cast<const uint8_t*>(data);
    b.insert(b.end(), p, p + size);
    return *this;
  }
  Bytes& str(const char* s) {  // u32 size including the terminating 0, then the bytes
    const uint32_t n = static_cast<uint32_t>(std::strlen(s) + 1);
    put(n);
    return raw(s, n);
  }
};

// A record: header, then `fields` (counted in fieldsSize), then `payload_size` bytes.
Bytes record(RecordType type, uint32_t node, const Bytes& fields, uint32_t payload_size, uint64_t undo_pos) {
  Bytes r;
  r.put(kRecordMagic).put(static_cast<uint32_t>(type)).put(node);
  r.put(static_cast<uint32_t>(kRecordHeaderBytes + fields.b.size())).put(payload_size).put(undo_pos);
  r.raw(fields.b.data(), fields.b.size());
  return r;
}

Bytes file_header(uint64_t max_timestamp_us) {
  Bytes h;
  h.raw("NI10", 4).put(uint8_t{1}).put(uint8_t{0}).put(uint16_t{1}).put(uint32_t{0});
  h.put(max_timestamp_us).put(kNodeId);  // max node id
  return h;
}

Bytes node_added(uint32_t frames, uint64_t max_timestamp_us, uint64_t seek_table_pos) {
  Bytes f;
  f.str("Depth").put(kNodeTypeDepth).put(kCodecNone).put(frames);
  f.put(uint64_t{0}).put(max_timestamp_us).put(seek_table_pos);  // min timestamp, max, seek table
  return record(kNodeAdded, kNodeId, f, 0, 0);
}

Bytes int_property(const char* name, uint64_t value) {
  Bytes f;
  f.str(name).put(uint32_t{sizeof(value)}).put(value);
  return record(kIntProperty, kNodeId, f, 0, 0);
}

Bytes general_property(const char* name, const Bytes& value) {
  Bytes f;
  f.str(name).put(static_cast<uint32_t>(value.b.size())).raw(value.b.data(), value.b.size());
  return record(kGeneralProperty, kNodeId, f, 0, 0);
}

Bytes data_begin(uint32_t frames, uint64_t max_timestamp_us) {
  Bytes f;
  f.put(frames).put(max_timestamp_us);
  return record(kNodeDataBegin, kNodeId, f, 0, 0);
}

}  // namespace

OniWriter::OniWriter(const std::string& path, int width, int height, int fps)
    : path_(path), width_(width), height_(height), fps_(fps) {
  if (width <= 0 || height <= 0 || width > 65535 || height > 65535 || fps <= 0)
    throw std::invalid_argument(path + ": bad .oni stream size " + std::to_string(width) + "x" +
                                std::to_string(height) + "@" + std::to_string(fps));
  file_ = std::fopen((path + ".partial").c_str(), "wb");
  if (!file_) throw std::runtime_error(path + ".partial: cannot open for writing: " + std::strerror(errno));
  const Bytes h = file_header(UINT64_MAX);  // patched on close
  write_bytes(h.b.data(), h.b.size());
}

OniWriter::~OniWriter() {
  try {
    close();
  } catch (...) {  // a destructor must not throw; close() explicitly to see errors
  }
}

void OniWriter::write_bytes(const void* data, size_t size) {
  if (std::fwrite(data, 1, size, file_) != size)
    throw std::runtime_error(path_ + ".partial: write failed: " + std::strerror(errno));
}

uint64_t OniWriter::tell() const { return static_cast<uint64_t>(ftello(file_)); }

void OniWriter::write_preamble(const Intrinsics& K) {
  if (!(K.fx > 0) || !(K.fy > 0))
    throw std::invalid_argument(path_ + ": first frame has no intrinsics (fx, fy), cannot write the field of view");
  node_added_pos_ = tell();
  Bytes out = node_added(UINT32_MAX, UINT64_MAX, 0);  // patched on close, like OpenNI's recorder
  const Bytes props[] = {
      int_property("oniRequiredFrameSize", static_cast<uint64_t>(width_) * height_ * 2),
      int_property("xnIsGenerating", 1),
      int_property("xnDeviceMaxDepth", kMaxDepthMm),
      general_property("xnMapOutputMode",
                       Bytes{}.put(static_cast<uint32_t>(width_)).put(static_cast<uint32_t>(height_)).put(
                           static_cast<uint32_t>(fps_))),
      int_property("xnPixelFormat", kXnPixelFormatGray16),
      int_property("oniPixelFormat", kPixelFormatDepth1mm),
      general_property("xnFOV", Bytes{}
                                    .put(2.0 * std::atan(width_ / 2.0 / K.fx))
                                    .put(2.0 * std::atan(height_ / 2.0 / K.fy))),
      // Without xnCropping the player delivers no frame at all (PlayerStream).
      general_property("xnCropping", Bytes{}.put(int32_t{0}).put(uint16_t{0}).put(uint16_t{0}).put(uint16_t{0}).put(
                                         uint16_t{0})),
      int_property("xnMirror", 0),
      record(kNodeStateReady, kNodeId, Bytes{}, 0, 0),
      data_begin(UINT32_MAX, UINT64_MAX),
  };
  for (const Bytes& p : props) out.raw(p.b.data(), p.b.size());
  write_bytes(out.b.data(), out.b.size());
}

void OniWriter::write(const DepthImage& frame) {
  if (!file_) throw std::logic_error(path_ + ": write after close");
  const size_t n = static_cast<size_t>(width_) * height_;
  if (frame.K.width != width_ || frame.K.height != height_ || frame.depth.size() != n)
    throw std::invalid_argument(path_ + ": frame " + std::to_string(frame.seq) + " is " +
                                std::to_string(frame.K.width) + "x" + std::to_string(frame.K.height) + " with " +
                                std::to_string(frame.depth.size()) + " pixels, the recording is " +
                                std::to_string(width_) + "x" + std::to_string(height_));
  if (!started_) {
    write_preamble(frame.K);
    first_utime_ = frame.utime;
    started_ = true;
  }
  if (frame.utime < first_utime_ + static_cast<int64_t>(last_timestamp_us_))
    throw std::invalid_argument(path_ + ": frame " + std::to_string(frame.seq) + " utime " +
                                std::to_string(frame.utime) + " goes backwards");
  const uint64_t ts = static_cast<uint64_t>(frame.utime - first_utime_);

  const uint16_t* mm = frame.depth.data();
  if (std::abs(frame.depth_scale - 0.001) > 1e-12) {
    mm_.resize(n);
    const double to_mm = frame.depth_scale * 1000.0;
    for (size_t i = 0; i < n; ++i)
      mm_[i] = static_cast<uint16_t>(std::min<double>(kMaxDepthMm, std::lround(frame.depth[i] * to_mm)));
    mm = mm_.data();
  }
  const uint64_t pos = tell();
  const Bytes head = record(kNewData, kNodeId, Bytes{}.put(ts).put(static_cast<uint32_t>(seek_.size() + 1)),
                            static_cast<uint32_t>(n * 2), last_data_pos_);
  write_bytes(head.b.data(), head.b.size());
  write_bytes(mm, n * 2);
  seek_.push_back({ts, pos});
  last_data_pos_ = pos;
  last_timestamp_us_ = ts;
}

void OniWriter::close() {
  if (!file_) return;
  std::FILE* f = file_;
  const std::string partial = path_ + ".partial";
  try {
    if (seek_.empty()) throw std::runtime_error(path_ + ": no frames written, no recording made");
    const uint64_t seek_pos = tell();
    // Seek table: an empty entry for frame 0, then {timestamp, configuration 0, position} per frame.
    Bytes table;
    table.put(uint64_t{0}).put(uint32_t{0}).put(uint64_t{0});
    for (const SeekEntry& e : seek_) table.put(e.timestamp_us).put(uint32_t{0}).put(e.position);
    Bytes tail = record(kSeekTable, kNodeId, Bytes{}, static_cast<uint32_t>(table.b.size()), 0);
    tail.raw(table.b.data(), table.b.size());
    const Bytes end = record(kEnd, 0, Bytes{}, 0, 0);
    tail.raw(end.b.data(), end.b.size());
    write_bytes(tail.b.data(), tail.b.size());

    const uint32_t frames = static_cast<uint32_t>(seek_.size());
    const Bytes h = file_header(last_timestamp_us_);
    const Bytes na = node_added(frames, last_timestamp_us_, seek_pos);
    if (fseeko(f, 0, SEEK_SET) != 0) throw std::runtime_error(partial + ": seek failed");
    write_bytes(h.b.data(), h.b.size());
    if (fseeko(f, static_cast<off_t>(node_added_pos_), SEEK_SET) != 0) throw std::runtime_error(partial + ": seek failed");
    write_bytes(na.b.data(), na.b.size());
  } catch (...) {
    std::fclose(f);
    file_ = nullptr;
    std::remove(partial.c_str());
    throw;
  }
  file_ = nullptr;
  if (std::fclose(f) != 0) throw std::runtime_error(partial + ": close failed: " + std::strerror(errno));
  if (std::rename(partial.c_str(), path_.c_str()) != 0)
    throw std::runtime_error(path_ + ": cannot rename from .partial: " + std::strerror(errno));
}

}  // namespace stairs
