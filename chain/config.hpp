// The whole chain's config: the one config file (common/config_file.hpp) read
// into both sections, for the programs that run perception and the tracker
// in-process (stairs-eval, stairs-bench, stairs-viewer --render).
#pragma once

#include "perception/config.hpp"
#include "tracker/config.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace stairs {

struct ChainConfig {
  PerceptionConfig perception;
  TrackerConfig tracker;
};

// "" = defaults. Throws std::runtime_error naming the file, the key and its
// allowed range (config_file.hpp, perception/config.hpp, tracker/config.hpp).
ChainConfig load_chain_config(const std::string& path);

// {"perception": {...}, "tracker": {...}}: --print-config, config/default.json.
nlohmann::ordered_json to_json(const ChainConfig& c);

}  // namespace stairs
