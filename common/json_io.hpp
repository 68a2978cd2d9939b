// JSON (nlohmann-json) for camera.json and groundtruth.json (DESIGN.md).
#pragma once

#include "common/types.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace stairs {

nlohmann::json to_json(const Intrinsics& K, double depth_scale);
nlohmann::json to_json(const GroundTruth& gt);
nlohmann::json step_to_json(const Step& s);  // DESIGN.md step keys; nosing as [x, z]

// Parse; throw std::runtime_error naming `what` (usually the file) and the key.
void intrinsics_from_json(const nlohmann::json& j, const std::string& what, Intrinsics& K,
                          double& depth_scale);
GroundTruth ground_truth_from_json(const nlohmann::json& j, const std::string& what);

// Reads and parses a JSON file; throws std::runtime_error "FILE: reason".
nlohmann::json read_json_file(const std::string& path);
// Writes atomically (temp file + rename), so a crash never leaves a half file.
void write_json_file(const std::string& path, const nlohmann::json& j);

}  // namespace stairs
