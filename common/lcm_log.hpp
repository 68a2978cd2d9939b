// LCM log files (lcm::LogFile) with errors that name the file.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace stairs {

struct LogEvent {
  int64_t timestamp_us = 0;
  std::string channel;
  std::vector<uint8_t> data;
};

class LogReader {
 public:
  explicit LogReader(const std::string& path);  // throws "FILE: reason"
  // Next event; false at the clean end of the file. Throws "FILE: truncated or
  // corrupt at byte N" when the file ends inside an event.
  bool next(LogEvent& ev);
  uint64_t bytes_read() const;
  uint64_t file_size() const { return size_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  uint64_t size_ = 0;
  std::unique_ptr<lcm::LogFile> log_;
};

// Writes PATH.partial and renames it to PATH on close(), so an interrupted
// writer never leaves a file that looks complete.
class LogWriter {
 public:
  explicit LogWriter(const std::string& path);
  ~LogWriter();
  void write(const std::string& channel, int64_t timestamp_us, const void* data, size_t size);
  template <class T>
  void write_message(const std::string& channel, int64_t timestamp_us, const T& msg) {
    std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
    msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
    write(channel, timestamp_us, buf.data(), buf.size());
  }
  void close();
  uint64_t events() const { return events_; }

 private:
  std::string path_;
  std::unique_ptr<lcm::LogFile> log_;
  uint64_t events_ = 0;
};

}  // namespace stairs
