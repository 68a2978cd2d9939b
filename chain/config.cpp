#include "chain/config.hpp"

#include "common/config_file.hpp"
#include "common/config_json.hpp"

namespace stairs {

ChainConfig load_chain_config(const std::string& path) {
  const ConfigSections s = read_config_file(path);
  return {perception_config_from_sections(s, path), tracker_config_from_sections(s, path)};
}

nlohmann::ordered_json to_json(const ChainConfig& c) {
  return {{"stair", config_to_json(stair_definition(c.perception))},
          {"mount", config_to_json(c.perception.mount)},
          {"perception", to_json(c.perception)},
          {"tracker", to_json(c.tracker)}};
}

}  // namespace stairs
