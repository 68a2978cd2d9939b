#include "common/config_file.hpp"

#include "common/json_io.hpp"

#include <ostream>
#include <stdexcept>

namespace stairs {

ConfigSections read_config_file(const std::string& path) {
  ConfigSections s;
  if (path.empty()) return s;
  const nlohmann::json j = read_json_file(path);
  if (!j.is_object()) throw std::runtime_error(path + ": a config must be a JSON object");
  for (const auto& [key, value] : j.items()) {
    if (key != "stair" && key != "mount" && key != "perception" && key != "tracker")
      throw std::runtime_error(path + ": unknown key '" + key +
                               "': a config holds the objects \"stair\", \"mount\", \"perception\" and \"tracker\" "
                               "(see config/default.json or any program's --print-config)");
    if (!value.is_object()) throw std::runtime_error(path + ": '" + key + "' must be a JSON object");
  }
  if (j.contains("stair")) s.stair = j["stair"];
  if (j.contains("mount")) s.mount = j["mount"];
  if (j.contains("perception")) s.perception = j["perception"];
  if (j.contains("tracker")) s.tracker = j["tracker"];
  return s;
}

void print_config(std::ostream& out, const nlohmann::ordered_json& effective) { out << effective.dump(2) << "\n"; }

}  // namespace stairs
