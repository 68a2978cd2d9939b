#include "common/daemon.hpp"

#include <stairs/daemon_status_t.hpp>

#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>

namespace stairs {

namespace {
std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop = true; }
}  // namespace

void install_stop_signals() {
  struct sigaction sa{};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}
bool stop_requested() { return g_stop; }
void request_stop() { g_stop = true; }

int64_t now_utime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

Options::Options(std::string program, std::string summary)
    : program_(std::move(program)), summary_(std::move(summary)) {
  add("help", "", "show this help and exit (also -h)");
  add("version", "", "print the version and exit");
}

Options& Options::add(const std::string& name, const std::string& value_name, const std::string& help,
                      const std::string& default_value) {
  order_.push_back(name);
  opts_[name] = {value_name, help, default_value};
  return *this;
}

Options& Options::config_options(const std::string& sections) {
  add("config", "FILE",
      "config file {\"stair\": {...}, \"mount\": {...}, \"perception\": {...}, \"tracker\": {...}}, any subset of the keys (config/default.json "
      "has them all); this program reads " + sections);
  return add("print-config", "", "print the effective config as JSON (the file's layout) and exit");
}

Options& Options::positional(const std::string& name, const std::string& help, bool required) {
  positional_help_.push_back({name, help});
  if (required) ++required_positionals_;
  return *this;
}

std::string Options::help() const {
  std::ostringstream s;
  s << "Usage: " << program_ << " [options]";
  for (const auto& [name, h] : positional_help_) s << " " << name;
  s << "\n\n" << summary_ << "\n\n";
  for (const auto& [name, h] : positional_help_) s << "  " << name << "\n      " << h << "\n";
  if (!positional_help_.empty()) s << "\n";
  s << "Options:\n";
  for (const std::string& name : order_) {
    const Opt& o = opts_.at(name);
    s << "  --" << name << (o.value_name.empty() ? "" : " " + o.value_name) << "\n      " << o.help;
    if (!o.default_value.empty()) s << " (default: " << o.default_value << ")";
    s << "\n";
  }
  return s.str();
}

void Options::parse(int argc, char** argv) {
  auto die = [&](const std::string& msg) {
    std::cerr << program_ << ": " << msg << " (see --help)\n";
    std::exit(2);
  };
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "-h") a = "--help";
    if (a.rfind("--", 0) != 0 || a == "--") {
      positional_values_.push_back(a);
      continue;
    }
    std::string name = a.substr(2), value;
    const bool has_eq = name.find('=') != std::string::npos;
    if (has_eq) {
      value = name.substr(name.find('=') + 1);
      name = name.substr(0, name.find('='));
    }
    auto it = opts_.find(name);
    if (it == opts_.end()) die("unknown option --" + name);
    if (it->second.value_name.empty()) {
      if (has_eq) die("--" + name + " takes no value");
      value = "1";
    } else if (!has_eq) {
      if (i + 1 >= argc) die("--" + name + " needs a value " + it->second.value_name);
      value = argv[++i];
    }
    values_[name] = value;
  }
  if (values_.count("help")) {
    std::cout << help();
    std::exit(0);
  }
  if (values_.count("version")) {
    std::cout << program_ << " " << STAIRS_VERSION << "\n";
    std::exit(0);
  }
  if (positional_values_.size() < required_positionals_) die("missing " + positional_help_[positional_values_.size()].first);
  if (positional_values_.size() > positional_help_.size()) die("unexpected argument " + positional_values_.back());
}

std::string Options::get(const std::string& name) const {
  if (auto it = values_.find(name); it != values_.end()) return it->second;
  return opts_.at(name).default_value;
}

double Options::get_double(const std::string& name) const {
  const std::string v = get(name);
  char* end = nullptr;
  const double d = std::strtod(v.c_str(), &end);
  if (v.empty() || *end != '\0') {
    std::cerr << program_ << ": --" << name << " expects a number, got '" << v << "'\n";
    std::exit(2);
  }
  return d;
}

int Options::get_int(const std::string& name) const { return static_cast<int>(get_double(name)); }
bool Options::flag(const std::string& name) const { return values_.count(name) > 0; }
bool Options::has(const std::string& name) const { return values_.count(name) > 0; }

StatusReporter::StatusReporter(lcm::LCM* lcm, std::string name, std::string channel, bool verbose)
    : lcm_(lcm), name_(std::move(name)), channel_(std::move(channel)), verbose_(verbose),
      tty_(isatty(STDERR_FILENO) != 0), last_tick_(std::chrono::steady_clock::now()), last_log_line_(last_tick_) {}

void StatusReporter::received() { ++received_; }

void StatusReporter::published(double latency_ms) {
  ++published_;
  std::lock_guard<std::mutex> lock(m_);
  latencies_.push_back(latency_ms);
}

void StatusReporter::dropped(const std::string& reason) {
  ++dropped_;
  std::lock_guard<std::mutex> lock(m_);
  last_error_ = reason;
}

void StatusReporter::event(const std::string& what) {
  std::lock_guard<std::mutex> lock(m_);
  last_error_ = what;
  std::cerr << name_ << ": " << what << "\n";
}

void StatusReporter::invalid(const std::string& reason) {
  ++invalid_;
  std::lock_guard<std::mutex> lock(m_);
  last_error_ = reason;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_error_log_ > std::chrono::seconds(1)) {  // at most one line a second
    std::cerr << name_ << ": rejected message: " << reason << " (" << invalid_ << " rejected so far)\n";
    last_error_log_ = now;
  }
}

void StatusReporter::tick() {
  const auto now = std::chrono::steady_clock::now();
  const double dt = std::chrono::duration<double>(now - last_tick_).count();
  if (dt < 1.0) return;
  last_tick_ = now;
  daemon_status_t msg{};
  {
    std::lock_guard<std::mutex> lock(m_);
    std::vector<double> lat = std::move(latencies_);
    latencies_.clear();
    if (!lat.empty()) {
      std::nth_element(lat.begin(), lat.begin() + lat.size() / 2, lat.end());
      msg.latency_ms = static_cast<float>(lat[lat.size() / 2]);
    }
    msg.last_error = last_error_;
  }
  msg.utime = now_utime();
  msg.name = name_;
  msg.received = received_;
  msg.published = published_;
  msg.dropped = dropped_;
  msg.invalid = invalid_;
  msg.rate_hz = static_cast<float>((published_ - published_at_last_tick_) / dt);
  published_at_last_tick_ = published_;
  if (lcm_) lcm_->publish(channel_, &msg);
  // On a terminal (or --verbose) once a second; under systemd/journald, off a
  // terminal, every kLogPeriod so the journal shows the daemon alive.
  if (tty_ || verbose_ || now - last_log_line_ >= kLogPeriod) {
    last_log_line_ = now;
    std::fprintf(stderr, "%s: %lld in, %lld out, %.1f Hz, %.2f ms median, %lld dropped, %lld invalid\n",
                 name_.c_str(), static_cast<long long>(msg.received), static_cast<long long>(msg.published),
                 msg.rate_hz, msg.latency_ms, static_cast<long long>(msg.dropped),
                 static_cast<long long>(msg.invalid));
  }
}

void StatusReporter::final_report() {
  std::fprintf(stderr, "%s: stopped: %lld received, %lld published, %lld dropped, %lld invalid\n", name_.c_str(),
               static_cast<long long>(received_), static_cast<long long>(published_),
               static_cast<long long>(dropped_), static_cast<long long>(invalid_));
}

}  // namespace stairs
