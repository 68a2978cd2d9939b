// The one config file every program takes as --config FILE:
//   {"stair": {...}, "mount": {...}, "perception": {"normals": {...}, ...}, "tracker": {...}}
// The top-level "stair" object is what perception and the tracker share,
// "mount" where the camera sits on a robot. All four objects and every key in them are optional (defaults otherwise);
// config/default.json ships every key with its default, and each program's
// --print-config prints the values it runs with.
#pragma once

#include <nlohmann/json.hpp>

#include <iosfwd>
#include <string>

namespace stairs {

struct ConfigSections {
  nlohmann::json stair = nlohmann::json::object();  // what both share (common/stair_definition.hpp)
  nlohmann::json mount = nlohmann::json::object();  // the camera on its robot (common/mount.hpp)
  nlohmann::json perception = nlohmann::json::object();
  nlohmann::json tracker = nlohmann::json::object();
};

// "" = defaults. Throws std::runtime_error "FILE: reason" on a missing file,
// bad JSON, a non-object, or a top-level key other than the four (a flat file
// of perception or tracker keys is refused, not read as defaults).
ConfigSections read_config_file(const std::string& path);

// --print-config: the effective values as the config file's JSON, on `out`.
void print_config(std::ostream& out, const nlohmann::ordered_json& effective);

}  // namespace stairs
