#include "common/json_io.hpp"

#include "common/file_util.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace stairs {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& what, const std::string& msg) {
  throw std::runtime_error(what + ": " + msg);
}

double number(const json& j, const char* key, const std::string& what) {
  auto it = j.find(key);
  if (it == j.end()) fail(what, std::string("missing key '") + key + "'");
  if (!it->is_number()) fail(what, std::string("'") + key + "' is not a number");
  const double v = it->get<double>();
  if (!std::isfinite(v)) fail(what, std::string("'") + key + "' is not finite");
  return v;
}

std::optional<double> optional_number(const json& j, const char* key, const std::string& what) {
  auto it = j.find(key);
  if (it == j.end() || it->is_null()) return std::nullopt;
  return number(j, key, what);
}

json optional_to_json(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

// `key` as n finite numbers, or nullopt when absent or null; anything else is
// the reader's own error naming the field (never a raw JSON type error).
std::optional<std::vector<double>> numbers(const json& j, const char* key, size_t n, const std::string& what) {
  auto it = j.find(key);
  if (it == j.end() || it->is_null()) return std::nullopt;
  if (!it->is_array() || it->size() != n) fail(what, std::string("'") + key + "' is not an array of " + std::to_string(n));
  std::vector<double> out;
  for (const json& v : *it) {
    if (!v.is_number() || !std::isfinite(v.get<double>())) fail(what, std::string("'") + key + "' holds a non-number");
    out.push_back(v.get<double>());
  }
  return out;
}

const json& object_at(const json& array, size_t i, const std::string& what) {
  if (!array[i].is_object()) fail(what, "is not an object");
  return array[i];
}

// Calls f(element, "WHAT<sep>KEY[i]") for each object of parent's array `key`;
// a missing array is an error when `required`.
template <class F>
void for_each_object(const json& parent, const char* key, const std::string& what, const char* sep, bool required,
                     F f) {
  const auto arr = parent.find(key);
  if (arr == parent.end() || (!required && arr->is_null())) {
    if (required) fail(what, std::string("missing array '") + key + "'");
    return;
  }
  if (!arr->is_array()) fail(what, std::string("'") + key + "' is not an array");
  for (size_t i = 0; i < arr->size(); ++i) {
    const std::string w = what + sep + key + "[" + std::to_string(i) + "]";
    f(object_at(*arr, i, w), w);
  }
}

}  // namespace

json to_json(const Intrinsics& K, double depth_scale) {
  return {{"width", K.width}, {"height", K.height}, {"fx", K.fx}, {"fy", K.fy},
          {"cx", K.cx},       {"cy", K.cy},         {"depth_scale", depth_scale}};
}

json step_to_json(const Step& s) {
  json j = {{"riser_height_m", optional_to_json(s.riser_height_m)},
            {"tread_depth_m", optional_to_json(s.tread_depth_m)},
            {"width_m", s.width_m},
            {"landing", s.landing},
            {"nosing_m", {s.nosing_m.x(), s.nosing_m.z()}}};
  // Optional (README "Contract extensions"): what was inferred rather than seen.
  if (s.inferred) {
    json names = json::array();
    for (const auto& [bit, name] : {std::pair<uint8_t, const char*>{kStepRiserInferred, "riser_height_m"},
                                    {kStepNosingInferred, "nosing_height"},
                                    {kStepWidthPartial, "width_partial"},
                                    {kStepTreadPartial, "tread_partial"}})
      if (s.inferred & bit) names.push_back(name);
    j["inferred"] = names;
  }
  return j;
}

json to_json(const GroundTruth& gt) {
  json flights = json::array();
  for (const Flight& f : gt.flights) {
    json steps = json::array();
    for (const Step& s : f.steps) steps.push_back(step_to_json(s));
    json jf = {{"steps", steps}, {"width_m", f.width_m}};
    if (!f.steps.empty() && f.steps.back().tread_depth_m)
      jf["top_landing_depth_m"] = *f.steps.back().tread_depth_m;
    flights.push_back(jf);
  }
  json frames = json::array();
  for (const GroundTruthFrame& fr : gt.frames) {
    const Eigen::Quaterniond& q = fr.orientation;
    frames.push_back({{"timestamp", fr.timestamp},
                      {"pitch_deg", fr.pitch_deg},
                      {"roll_deg", fr.roll_deg},
                      {"height_m", fr.height_m},
                      {"distance_m", optional_to_json(fr.distance_m)},
                      {"position_m", {fr.position_m.x(), fr.position_m.y(), fr.position_m.z()}},
                      {"quaternion_wxyz", {q.w(), q.x(), q.y(), q.z()}},
                      {"visible_steps", fr.visible_steps}});
  }
  json out = {{"flights", flights}, {"frames", frames}};
  if (!gt.scene.empty()) out["scene"] = gt.scene;
  return out;
}

void intrinsics_from_json(const json& j, const std::string& what, Intrinsics& K, double& depth_scale) {
  if (!j.is_object()) fail(what, "not a JSON object");
  K.width = static_cast<int>(number(j, "width", what));
  K.height = static_cast<int>(number(j, "height", what));
  K.fx = number(j, "fx", what);
  K.fy = number(j, "fy", what);
  K.cx = number(j, "cx", what);
  K.cy = number(j, "cy", what);
  depth_scale = number(j, "depth_scale", what);
  if (K.width <= 0 || K.height <= 0 || K.width > 4096 || K.height > 4096)
    fail(what, "width/height out of range 1..4096");
  if (K.fx <= 0 || K.fy <= 0) fail(what, "fx/fy must be positive");
  if (depth_scale <= 0) fail(what, "depth_scale must be positive");
}

GroundTruth ground_truth_from_json(const json& j, const std::string& what) {
  if (!j.is_object()) fail(what, "not a JSON object");
  GroundTruth gt;
  if (auto it = j.find("scene"); it != j.end() && it->is_string()) gt.scene = it->get<std::string>();
  for_each_object(j, "flights", what, ": ", true, [&](const json& jf, const std::string& wf) {
    Flight f;
    if (auto w = optional_number(jf, "width_m", wf)) f.width_m = *w;
    for_each_object(jf, "steps", wf, ".", true, [&](const json& js, const std::string& ws) {
      Step s;
      s.riser_height_m = optional_number(js, "riser_height_m", ws);
      s.tread_depth_m = optional_number(js, "tread_depth_m", ws);
      if (auto l = js.find("landing"); l != js.end()) {
        if (!l->is_boolean()) fail(ws, "'landing' is not true/false");
        s.landing = l->get<bool>();
      }
      if (auto w = optional_number(js, "width_m", ws)) s.width_m = *w;
      if (auto n = numbers(js, "nosing_m", 2, ws)) s.nosing_m = {(*n)[0], 0.0, (*n)[1]};
      f.steps.push_back(s);
    });
    gt.flights.push_back(std::move(f));
  });
  for_each_object(j, "frames", what, ": ", false, [&](const json& jf, const std::string& wf) {
    GroundTruthFrame fr;
    fr.timestamp = number(jf, "timestamp", wf);
    fr.pitch_deg = number(jf, "pitch_deg", wf);
    fr.roll_deg = number(jf, "roll_deg", wf);
    fr.height_m = number(jf, "height_m", wf);
    fr.distance_m = optional_number(jf, "distance_m", wf);
    if (auto p = numbers(jf, "position_m", 3, wf)) fr.position_m = {(*p)[0], (*p)[1], (*p)[2]};
    if (auto q = numbers(jf, "quaternion_wxyz", 4, wf)) fr.orientation = Eigen::Quaterniond((*q)[0], (*q)[1], (*q)[2], (*q)[3]);
    if (auto v = jf.find("visible_steps"); v != jf.end() && !v->is_null()) {
      if (!v->is_array()) fail(wf, "'visible_steps' is not an array");
      for (const json& k : *v) {
        if (!k.is_number_integer() || k.get<int64_t>() < 0 || k.get<int64_t>() > 32767)
          fail(wf, "'visible_steps' holds a value that is no step index (0..32767)");
        fr.visible_steps.push_back(k.get<int>());
      }
    }
    gt.frames.push_back(std::move(fr));
  });
  return gt;
}

json read_json_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw std::runtime_error(path + ": bad JSON: " + e.what());
  }
}

void write_json_file(const std::string& path, const json& j) {
  write_file_atomically(path, j.dump(1) + "\n");
}

}  // namespace stairs
