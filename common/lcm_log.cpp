#include "common/lcm_log.hpp"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace stairs {

LogReader::LogReader(const std::string& path) : path_(path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw std::runtime_error(path + ": no such file");
  size_ = std::filesystem::file_size(path, ec);
  log_ = std::make_unique<lcm::LogFile>(path, "r");
  if (!log_->good()) throw std::runtime_error(path + ": cannot open as an LCM log");
}

uint64_t LogReader::bytes_read() const {
  FILE* f = log_->getFilePtr();
  const long pos = f ? std::ftell(f) : -1;
  return pos < 0 ? 0 : static_cast<uint64_t>(pos);
}

bool LogReader::next(LogEvent& ev) {
  const uint64_t start = bytes_read();
  const lcm::LogEvent* e = log_->readNextEvent();
  if (!e) {
    if (start < size_)
      throw std::runtime_error(path_ + ": truncated or corrupt LCM log at byte " + std::to_string(start) + " of " +
                               std::to_string(size_));
    return false;
  }
  // lcm::LogFile silently skips bytes until the next sync word; an event that
  // does not start where the previous one ended means the file is corrupt.
  const uint64_t header = 4 + 8 + 8 + 4 + 4;
  const uint64_t expected_end = start + header + e->channel.size() + static_cast<uint64_t>(e->datalen);
  if (bytes_read() != expected_end)
    throw std::runtime_error(path_ + ": corrupt LCM log: " + std::to_string(bytes_read() - expected_end) +
                             " unreadable bytes at byte " + std::to_string(start));
  ev.timestamp_us = e->timestamp;
  ev.channel = e->channel;
  const auto* p = static_cast<const uint8_t*>(e->data);
  ev.data.assign(p, p + e->datalen);
  return true;
}

LogWriter::LogWriter(const std::string& path) : path_(path) {
  log_ = std::make_unique<lcm::LogFile>(path + ".partial", "w");
  if (!log_->good()) throw std::runtime_error(path + ": cannot create LCM log");
}

LogWriter::~LogWriter() = default;  // without close() the .partial file stays

void LogWriter::write(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) {
  lcm::LogEvent e{};
  e.eventnum = static_cast<int64_t>(events_++);
  e.timestamp = timestamp_us;
  e.channel = channel;
  e.datalen = static_cast<int32_t>(size);
  e.data = const_cast<void*>(data);
  if (log_->writeEvent(&e) != 0) throw std::runtime_error(path_ + ": write failed");
}

void LogWriter::close() {
  if (!log_) return;
  log_.reset();
  std::error_code ec;
  std::filesystem::rename(path_ + ".partial", path_, ec);
  if (ec) throw std::runtime_error(path_ + ": rename failed: " + ec.message());
}

}  // namespace stairs
