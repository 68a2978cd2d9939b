// Small file helpers that keep partial output from looking complete.
#pragma once

#include <string>

namespace stairs {

// Writes `contents` to `path` through a temporary file and a rename.
void write_file_atomically(const std::string& path, const std::string& contents);

// Creates a directory and its parents; throws std::runtime_error naming it.
void make_directories(const std::string& path);

}  // namespace stairs
