// Runs stairs-viewer from the build tree and reads what it wrote.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <string>

namespace stairs::viewer::test {

inline std::string viewer_program() { return std::string(STAIRS_BINARY_DIR) + "/bin/stairs-viewer"; }

// Exit code of `stairs-viewer ARGS` (stderr to `log`), -1 if it did not exit normally.
inline int run_viewer(const std::string& args, const std::string& log) {
  const int rc = std::system((viewer_program() + " " + args + " 2>" + log).c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

}  // namespace stairs::viewer::test
