// A daemon as a real subprocess for the integration tests (start, crash it,
// stop it cleanly), LCM pumping with a deadline, and the latest daemon_status_t
// of one daemon.
#pragma once

#include <lcm/lcm-cpp.hpp>
#include <stairs/daemon_status_t.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace stairs::test {

// Exit code of a child process, 128 + the signal if one ended it, or -1 (after
// SIGKILL) if it did not end within timeout_s.
inline int wait_exit(pid_t pid, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

class DaemonProcess {
 public:
  // Runs STAIRS_BINARY_DIR/bin/<program> with `args`; its stderr goes to
  // `stderr_file` when one is given (then it is no terminal).
  DaemonProcess(const std::string& program, const std::vector<std::string>& args, const std::string& stderr_file = "") {
    const std::string exe = std::string(STAIRS_BINARY_DIR) + "/bin/" + program;
    pid_ = fork();
    if (pid_ == 0) {
      if (!stderr_file.empty()) {
        const int fd = open(stderr_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd < 0) _exit(126);
        dup2(fd, STDERR_FILENO);
        close(fd);
      }
      std::vector<char*> argv{const_cast<char*>(exe.c_str())};
      for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      execv(exe.c_str(), argv.data());
      _exit(127);
    }
  }
  DaemonProcess(const DaemonProcess&) = delete;
  DaemonProcess& operator=(const DaemonProcess&) = delete;
  ~DaemonProcess() {
    if (running()) kill_hard();
  }

  pid_t pid() const { return pid_; }
  bool running() {
    if (pid_ <= 0 || exited_) return false;
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) != pid_) return true;
    exited_ = true;
    status_ = status;
    return false;
  }
  // A crash: SIGKILL, no chance to clean up.
  void kill_hard() { signal_and_wait(SIGKILL); }
  // SIGTERM and wait; true when the daemon exited normally with status 0.
  bool stop_cleanly() {
    signal_and_wait(SIGTERM);
    return WIFEXITED(status_) && WEXITSTATUS(status_) == 0;
  }

 private:
  void signal_and_wait(int sig) {
    if (!running()) return;
    kill(pid_, sig);
    waitpid(pid_, &status_, 0);
    exited_ = true;
  }
  pid_t pid_ = -1;
  bool exited_ = false;
  int status_ = -1;
};

// Channel names of this test process only: ctest runs the tests of one program
// as separate processes side by side on the same multicast group.
inline std::string channel(const std::string& name) { return "T" + std::to_string(getpid()) + "_" + name; }

inline void pump(lcm::LCM& lcm, int ms) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
  while (std::chrono::steady_clock::now() < end) lcm.handleTimeout(20);
}

// Handles messages until `done` or `timeout_ms` has passed; returns done().
// The timeout only bounds a failing test: nothing is asserted about speed.
inline bool pump_until(lcm::LCM& lcm, const std::function<bool()>& done, int timeout_ms = 20000) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  while (!done() && std::chrono::steady_clock::now() < end) lcm.handleTimeout(20);
  return done();
}

// The newest daemon_status_t from the daemon called `name`.
struct StatusWatch {
  std::string name;
  std::optional<daemon_status_t> last;
  void on_status(const lcm::ReceiveBuffer*, const std::string&, const daemon_status_t* s) {
    if (s->name == name) last = *s;
  }
};

// Starts `program` with `args` and waits for its first status message on
// `status`, which a daemon sends once it has subscribed; null if none came.
// Its stderr goes to `stderr_file` when one is given.
inline std::unique_ptr<DaemonProcess> start_daemon(lcm::LCM& lcm, StatusWatch& status, const std::string& program,
                                                   const std::vector<std::string>& args,
                                                   const std::string& stderr_file = "") {
  status.last.reset();
  auto d = std::make_unique<DaemonProcess>(program, args, stderr_file);
  if (!pump_until(lcm, [&] { return status.last && status.last->received == 0; })) return nullptr;
  return d;
}

}  // namespace stairs::test
