// Plumbing shared by the daemons: options, signals, a bounded hand-off slot,
// and a status line once a second (terminal) plus daemon_status_t on LCM.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace stairs {

// --name value / --name=value / --flag options with a generated --help.
class Options {
 public:
  Options(std::string program, std::string summary);
  // Declares an option; `value_name` empty = a flag without value.
  Options& add(const std::string& name, const std::string& value_name, const std::string& help,
               const std::string& default_value = "");
  Options& positional(const std::string& name, const std::string& help, bool required = true);
  // --config FILE (the one config file, common/config_file.hpp) and --print-config,
  // the same in every program; `sections` names what this program reads.
  Options& config_options(const std::string& sections);
  // Parses argv; prints help and exits 0 on --help or -h, the program and the
  // project's version on --version; prints an error and exits 2 on a bad option.
  void parse(int argc, char** argv);
  std::string get(const std::string& name) const;
  double get_double(const std::string& name) const;  // exits 2 naming the option if not a number
  int get_int(const std::string& name) const;
  bool flag(const std::string& name) const;
  bool has(const std::string& name) const;  // given on the command line
  const std::vector<std::string>& positionals() const { return positional_values_; }
  std::string help() const;

 private:
  struct Opt {
    std::string value_name, help, default_value;
  };
  std::string program_, summary_;
  std::vector<std::string> order_;
  std::map<std::string, Opt> opts_;
  std::vector<std::pair<std::string, std::string>> positional_help_;
  size_t required_positionals_ = 0;
  std::map<std::string, std::string> values_;
  std::vector<std::string> positional_values_;
};

// SIGINT/SIGTERM set the flag returned by stop_requested().
void install_stop_signals();
bool stop_requested();
void request_stop();

// Keeps only the newest item: a slow consumer never makes a queue grow; each
// overwritten item is counted as dropped. Items are swapped, not moved, so their
// buffers (a depth image's 600 KB) circulate between the producer, the slot and the
// consumer: nothing is allocated per item in steady state.
template <class T>
class LatestSlot {
 public:
  // Swaps `item` into the slot; `item` gets the slot's previous one (a dropped item, or the
  // consumer's last) to fill next. Returns true if an unconsumed item was overwritten (dropped).
  bool put(T& item) {
    std::lock_guard<std::mutex> lock(m_);
    const bool dropped = full_;
    std::swap(item_, item);
    full_ = true;
    cv_.notify_one();
    return dropped;
  }
  // Waits up to timeout for an item and swaps it into `out` (the slot keeps out's old one for the
  // producer). False if none came.
  bool take(T& out, std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(m_);
    cv_.wait_for(lock, timeout, [&] { return full_; });
    if (!full_) return false;
    std::swap(item_, out);
    full_ = false;
    return true;
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  T item_{};
  bool full_ = false;
};

// Counters of one daemon; tick() prints a status line once a second when stderr
// is a terminal (or always with `verbose`) and publishes daemon_status_t.
class StatusReporter {
 public:
  StatusReporter(lcm::LCM* lcm, std::string name, std::string channel = "STAIRS_STATUS", bool verbose = false);
  void received();
  void published(double latency_ms);
  void dropped(const std::string& reason);
  void invalid(const std::string& reason);  // also logged to stderr, rate-limited
  void event(const std::string& what);      // a reset and the like: logged to stderr as it happens
  void tick();  // call often; once a second: daemon_status_t, and a status line on stderr (on a
                // terminal or with --verbose; otherwise every 10 s, for the journal)
  void final_report();                      // one summary line on exit
  int64_t received_count() const { return received_; }
  int64_t published_count() const { return published_; }
  int64_t dropped_count() const { return dropped_; }
  int64_t invalid_count() const { return invalid_; }

 private:
  lcm::LCM* lcm_;
  std::string name_, channel_;
  bool verbose_, tty_;
  std::mutex m_;
  std::atomic<int64_t> received_{0}, published_{0}, dropped_{0}, invalid_{0};
  int64_t published_at_last_tick_ = 0;
  std::vector<double> latencies_;
  std::string last_error_;
  std::chrono::steady_clock::time_point last_tick_, last_error_log_, last_log_line_;
  static constexpr std::chrono::seconds kLogPeriod{10};  // status line off a terminal
};

int64_t now_utime();

}  // namespace stairs
