#include "chain/config.hpp"

#include "common/config_file.hpp"

namespace stairs {

ChainConfig load_chain_config(const std::string& path) {
  const ConfigSections s = read_config_file(path);
  return {perception_config_from_json(s.perception, path), tracker_config_from_json(s.tracker, path)};
}

nlohmann::ordered_json to_json(const ChainConfig& c) {
  return {{"perception", to_json(c.perception)}, {"tracker", to_json(c.tracker)}};
}

}  // namespace stairs
