#include "drivers/sim/scene.hpp"

#include "drivers/sim/furniture.hpp"

#include <cmath>
#include <map>
#include <stdexcept>

namespace stairs::sim {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& what, const std::string& msg) {
  throw std::runtime_error(what + ": " + msg);
}

double num(const json& j, const char* key, const std::string& what, double fallback) {
  auto it = j.find(key);
  if (it == j.end()) return fallback;
  if (!it->is_number() || !std::isfinite(it->get<double>()))
    fail(what, std::string("'") + key + "' is not a finite number");
  return it->get<double>();
}

double positive(const json& j, const char* key, const std::string& what, double fallback) {
  const double v = num(j, key, what, fallback);
  if (v <= 0.0) fail(what, std::string("'") + key + "' must be positive");
  return v;
}

std::string text(const json& j, const char* key, const std::string& what) {
  const json& v = j.at(key);
  if (!v.is_string()) fail(what, std::string("'") + key + "' is not a string");
  return v.get<std::string>();
}

Eigen::Vector3d vec3(const json& j, const char* key, const std::string& what) {
  auto it = j.find(key);
  if (it == j.end() || !it->is_array() || it->size() != 3)
    fail(what, std::string("'") + key + "' must be an array of 3 numbers");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    if (!(*it)[i].is_number()) fail(what, std::string("'") + key + "' must be an array of 3 numbers");
    v[i] = (*it)[i].get<double>();
  }
  return v;
}

std::vector<double> number_list(const json& j, const char* key, const std::string& what) {
  std::vector<double> out;
  for (const json& v : j.at(key)) {
    if (!v.is_number() || v.get<double>() <= 0.0)
      fail(what, std::string("'") + key + "' must hold positive numbers");
    out.push_back(v.get<double>());
  }
  return out;
}

const std::map<std::string, Walls>& wall_names() {
  static const std::map<std::string, Walls> m = {
      {"none", Walls::None}, {"left", Walls::Left}, {"right", Walls::Right}, {"both", Walls::Both}};
  return m;
}

const std::map<std::string, SceneKind>& kind_names() {
  static const std::map<std::string, SceneKind> m = {
      {"stairs", SceneKind::Stairs}, {"flat_room", SceneKind::FlatRoom}, {"ramp", SceneKind::Ramp}};
  return m;
}

template <class E>
std::string name_of(const std::map<std::string, E>& m, E v) {
  for (const auto& [k, e] : m)
    if (e == v) return k;
  return "?";
}

Scene stair(const std::string& name, std::vector<FlightSpec> flights) {
  Scene s;
  s.name = name;
  s.flights = std::move(flights);
  return s;
}

struct Preset {
  std::string summary;
  Scene (*make)();
};

// Standard German house stair (thesis section 1): 18 cm risers, 25 cm treads.
// The table in two halves, each a function a reader can hold in their head.
void add_presets_first(std::map<std::string, Preset>& m) {
  m.insert({
      {"straight_up",
       {"10 steps 0.18/0.25 m, width 1.2 m, walls both sides, 1.5 m top landing with back wall",
        [] { return stair("straight_up", {uniform_flight(10, 0.18, 0.25, 1.5)}); }}},
      {"straight_down",
       {"as straight_up with a 3 m top landing to approach the descent from",
        [] { return stair("straight_down", {uniform_flight(10, 0.18, 0.25, 3.0)}); }}},
      {"irregular",
       {"8 steps with risers 0.165..0.195 m and treads 0.23..0.29 m, 3 m landing",
        [] {
          FlightSpec f{{0.175, 0.19, 0.165, 0.18, 0.195, 0.17, 0.185, 0.18},
                       {0.25, 0.28, 0.23, 0.26, 0.29, 0.24, 0.27, 3.0}};
          return stair("irregular", {f});
        }}},
      {"steep_nosing",
       {"8 steep steps 0.20/0.24 m with a 3 cm nosing overhang, a wall on the left only, 3 m landing",
        [] {
          Scene s = stair("steep_nosing", {uniform_flight(8, 0.20, 0.24, 3.0)});
          s.nosing_m = 0.03;
          s.walls = Walls::Left;
          return s;
        }}},
      {"dark_treads",
       {"straight_up geometry with dark treads: half their pixels read nothing (any sensor)",
        [] {
          Scene s = stair("dark_treads", {uniform_flight(10, 0.18, 0.25, 3.0)});
          s.dark_treads = true;
          return s;
        }}},
      {"open_risers",
       {"10 steps 0.18/0.26 m with open risers: 4 cm tread slabs, the floor under the flight between them, 3 m landing",
        [] {
          Scene s = stair("open_risers", {uniform_flight(10, 0.18, 0.26, 3.0)});
          s.open_risers = true;
          return s;
        }}},
      {"irregular_step",
       {"10 steps 0.17/0.28 m but the 5th rises 0.21 m (its tread 0.28 m), 3 m landing",
        [] {
          FlightSpec f = uniform_flight(10, 0.17, 0.28, 3.0);
          f.riser_m[4] = 0.21;
          return stair("irregular_step", {f});
        }}},
      {"nosing",
       {"10 steps 0.17/0.28 m with a 3 cm nosing overhang, 3 m landing",
        [] {
          Scene s = stair("nosing", {uniform_flight(10, 0.17, 0.28, 3.0)});
          s.nosing_m = 0.03;
          return s;
        }}}});
}

void add_presets_second(std::map<std::string, Preset>& m) {
  m.insert({
      {"open_sides",
       {"10 steps 0.18/0.25 m, width 1.0 m, no side walls (room 4 m wide), 3 m landing",
        [] {
          Scene s = stair("open_sides", {uniform_flight(10, 0.18, 0.25, 3.0)});
          s.width_m = 1.0;
          s.walls = Walls::None;
          return s;
        }}},
      {"wall_left",
       {"10 steps 0.18/0.25 m, a wall on the left only, handrail on the right, 3 m landing",
        [] {
          Scene s = stair("wall_left", {uniform_flight(10, 0.18, 0.25, 3.0)});
          s.walls = Walls::Left;
          s.cylinders.push_back(handrail(s, 0, -1));
          return s;
        }}},
      {"railings",
       {"open_sides with a handrail on each side on balusters (two per tread, 2.4 cm thick)",
        [] {
          Scene s = stair("railings", {uniform_flight(10, 0.18, 0.25, 3.0)});
          s.width_m = 1.0;
          s.walls = Walls::None;
          for (const int side : {-1, +1}) {
            s.cylinders.push_back(handrail(s, 0, side));
            for (const Cylinder& c : balusters(s, 0, side)) s.cylinders.push_back(c);
          }
          return s;
        }}},
      {"people",
       {"straight_down geometry with two people (0.4 m across, 1.7 m tall): one on the fifth tread, one at "
        "the foot of the flight",
        [] {
          Scene s = stair("people", {uniform_flight(10, 0.18, 0.25, 3.0)});
          s.cylinders.push_back({{1.1, 0.3, 5 * 0.18}, Eigen::Vector3d::UnitZ(), 1.7, 0.2});
          s.cylinders.push_back({{-0.6, -0.35, 0.0}, Eigen::Vector3d::UnitZ(), 1.7, 0.2});
          return s;
        }}},
      {"two_flights",
       {"7 + 7 steps 0.18/0.25 m with a 1.2 m mid landing, 3 m top landing, walls both sides",
        [] {
          return stair("two_flights",
                       {uniform_flight(7, 0.18, 0.25, 1.2), uniform_flight(7, 0.18, 0.25, 3.0)});
        }}},
      {"cluttered",
       {"straight_down geometry with a handrail, a box and a bin on the floor before the stair",
        [] {
          Scene s = stair("cluttered", {uniform_flight(10, 0.18, 0.25, 3.0)});
          s.cylinders.push_back(handrail(s, 0, +1));
          s.boxes.push_back({{-1.6, -0.55, 0.0}, {-1.2, -0.15, 0.35}});
          s.cylinders.push_back({{-0.8, 0.35, 0.0}, Eigen::Vector3d::UnitZ(), 0.5, 0.15});
          return s;
        }}},
      {"flat_room",
       {"no stair: a 9 x 4 m room with a table (0.75 m) and a box",
        [] {
          Scene s;
          s.name = "flat_room";
          s.kind = SceneKind::FlatRoom;
          s.walls = Walls::None;
          const double top = 0.75, leg = 0.05;
          s.boxes.push_back({{1.5, -0.6, top - 0.04}, {2.3, 0.6, top}});
          for (double x : {1.55, 2.25 - leg})
            for (double y : {-0.55, 0.55 - leg}) s.boxes.push_back({{x, y, 0.0}, {x + leg, y + leg, top - 0.04}});
          s.boxes.push_back({{0.3, 0.6, 0.0}, {0.7, 1.0, 0.4}});
          return s;
        }}},
      {"ramp",
       {"no stair: a 3 m ramp rising 0.3 m, 2 m landing, walls both sides",
        [] {
          Scene s;
          s.name = "ramp";
          s.kind = SceneKind::Ramp;
          return s;
        }}},
      {"curb",
       {"a single 0.15 m curb (one riser, a 4 m landing above), open sides",
        [] {
          Scene s = stair("curb", {uniform_flight(1, 0.15, 0.0, 4.0)});
          s.walls = Walls::None;
          s.room_width_m = 6.0;
          s.back_wall = false;
          return s;
        }}}});
}

const std::map<std::string, Preset>& presets() {
  static const std::map<std::string, Preset> m = [] {
    std::map<std::string, Preset> t;
    add_presets_first(t);
    add_presets_second(t);
    return t;
  }();
  return m;
}

}  // namespace

FlightSpec uniform_flight(int steps, double riser_m, double tread_m, double landing_m) {
  FlightSpec f;
  for (int i = 0; i < steps; ++i) {
    f.riser_m.push_back(riser_m);
    f.tread_m.push_back(i + 1 == steps ? landing_m : tread_m);
  }
  return f;
}

Walls walls_from_name(const std::string& name) {
  auto it = wall_names().find(name);
  if (it == wall_names().end()) throw std::invalid_argument("walls must be none, left, right or both, not '" + name + "'");
  return it->second;
}

Scene make_preset(const std::string& name) {
  if (is_furniture(name)) return furniture_scene(name, 0);
  auto it = presets().find(name);
  if (it == presets().end()) {
    std::string known;
    for (const auto& n : preset_names()) known += " " + n;
    throw std::invalid_argument("unknown scene preset '" + name + "' (known:" + known + ")");
  }
  return it->second.make();
}

std::vector<std::string> preset_names() {
  std::vector<std::string> out;
  for (const auto& [name, p] : presets()) out.push_back(name);
  for (const std::string& f : furniture_families()) out.push_back(f);
  return out;
}

std::string preset_summary(const std::string& name) {
  if (is_furniture(name)) return "no stair: " + name + " furniture walked from 3.5 to 0.8 m (sizes drawn from --seed)";
  return presets().at(name).summary;
}

std::vector<StepGeometry> step_geometry(const Scene& s) {
  std::vector<StepGeometry> out;
  if (s.kind != SceneKind::Stairs) return out;
  double x = 0.0, z = 0.0;
  for (size_t f = 0; f < s.flights.size(); ++f) {
    const FlightSpec& fl = s.flights[f];
    for (size_t i = 0; i < fl.riser_m.size(); ++i) {
      StepGeometry g;
      g.flight = static_cast<int>(f);
      g.riser_x_m = x;
      g.bottom_z_m = z;
      g.top_z_m = z + fl.riser_m[i];
      g.end_x_m = x + fl.tread_m[i];
      g.riser_m = fl.riser_m[i];
      g.tread_m = fl.tread_m[i];
      g.landing = i + 1 == fl.riser_m.size();
      out.push_back(g);
      x = g.end_x_m;
      z = g.top_z_m;
    }
  }
  return out;
}

GroundTruth scene_truth(const Scene& s) {
  GroundTruth gt;
  gt.scene = s.name;
  const std::vector<StepGeometry> geo = step_geometry(s);
  for (size_t f = 0; f < s.flights.size() && s.kind == SceneKind::Stairs; ++f) {
    Flight fl;
    fl.width_m = s.width_m;
    for (const StepGeometry& g : geo) {
      if (g.flight != static_cast<int>(f)) continue;
      Step st;
      st.landing = g.landing;
      st.riser_height_m = g.riser_m;
      st.tread_depth_m = g.tread_m;
      st.width_m = s.width_m;
      st.nosing_m = {g.riser_x_m - s.nosing_m, 0.0, g.top_z_m};
      fl.steps.push_back(st);
    }
    gt.flights.push_back(fl);
  }
  return gt;
}

double surface_height_m(const Scene& s, double x_m, double y_m) {
  if (s.kind == SceneKind::FlatRoom) return 0.0;
  if (std::abs(y_m) > 0.5 * s.width_m) return 0.0;  // beside the flight: floor
  if (s.kind == SceneKind::Ramp) {
    if (x_m <= 0.0) return 0.0;
    return x_m >= s.ramp_length_m ? s.ramp_height_m : s.ramp_height_m * x_m / s.ramp_length_m;
  }
  double h = 0.0;
  for (const StepGeometry& g : step_geometry(s))
    if (x_m >= g.riser_x_m - s.nosing_m) h = g.top_z_m;
  return h;
}

double scene_start_x_m(const Scene& s) { return -s.floor_length_m; }

double scene_end_x_m(const Scene& s) {
  switch (s.kind) {
    case SceneKind::FlatRoom: return s.flat_length_m;
    case SceneKind::Ramp: return s.ramp_length_m + s.ramp_landing_m;
    case SceneKind::Stairs: break;
  }
  const std::vector<StepGeometry> geo = step_geometry(s);
  return geo.empty() ? 0.0 : geo.back().end_x_m;
}

Cylinder handrail(const Scene& s, int flight, int side, double height_m) {
  std::vector<StepGeometry> geo;
  for (const StepGeometry& g : step_geometry(s))
    if (g.flight == flight && !g.landing) geo.push_back(g);
  if (geo.size() < 2) throw std::invalid_argument("handrail: flight " + std::to_string(flight) + " has fewer than 2 steps below its landing");
  const double y = side * (0.5 * s.width_m - 0.08);
  const Eigen::Vector3d a(geo.front().riser_x_m - s.nosing_m, y, geo.front().top_z_m + height_m);
  const Eigen::Vector3d b(geo.back().riser_x_m - s.nosing_m, y, geo.back().top_z_m + height_m);
  Cylinder c;
  c.base_m = a;
  c.axis = (b - a).normalized();
  c.length_m = (b - a).norm();
  c.radius_m = 0.025;
  return c;
}

std::vector<Cylinder> balusters(const Scene& s, int flight, int side, double height_m) {
  std::vector<Cylinder> out;
  const double y = side * (0.5 * s.width_m - 0.08);  // under the handrail
  for (const StepGeometry& g : step_geometry(s)) {
    if (g.flight != flight || g.landing) continue;
    for (const double at : {0.25, 0.75}) {
      Cylinder c;
      c.base_m = {g.riser_x_m - s.nosing_m + at * g.tread_m, y, g.top_z_m};
      c.axis = Eigen::Vector3d::UnitZ();
      c.length_m = height_m;
      c.radius_m = 0.012;
      out.push_back(c);
    }
  }
  return out;
}

// "flights": each either explicit per-step lists or a uniform flight.
void flights_from_json(const json& j, const std::string& what, Scene& s) {
  if (auto it = j.find("flights"); it != j.end()) {
    if (!it->is_array()) fail(what, "'flights' must be an array");
    s.flights.clear();
    for (size_t f = 0; f < it->size(); ++f) {
      const json& jf = (*it)[f];
      const std::string w = what + ": flights[" + std::to_string(f) + "]";
      if (jf.contains("risers_m") || jf.contains("treads_m")) {
        FlightSpec fl{number_list(jf, "risers_m", w), number_list(jf, "treads_m", w)};
        if (fl.riser_m.size() != fl.tread_m.size() || fl.riser_m.empty())
          fail(w, "'risers_m' and 'treads_m' must have the same non-zero length");
        s.flights.push_back(fl);
      } else {
        const double steps = num(jf, "steps", w, 10);
        if (steps < 1 || steps > 100 || steps != std::floor(steps)) fail(w, "'steps' must be an integer 1..100");
        s.flights.push_back(uniform_flight(static_cast<int>(steps), positive(jf, "riser_m", w, 0.18),
                                           positive(jf, "tread_m", w, 0.25), positive(jf, "landing_m", w, 1.5)));
      }
    }
  }
}

// "boxes", "cylinders" and "handrails" (furniture, posts, rails; handrails follow a flight).
void obstacles_from_json(const json& j, const std::string& what, Scene& s) {
  if (auto it = j.find("boxes"); it != j.end()) {
    for (const json& b : *it) {
      Box box{vec3(b, "min_m", what + ": boxes"), vec3(b, "max_m", what + ": boxes")};
      if ((box.max_m - box.min_m).minCoeff() <= 0.0) fail(what, "boxes: max_m must exceed min_m");
      s.boxes.push_back(box);
    }
  }
  if (auto it = j.find("cylinders"); it != j.end()) {
    for (const json& c : *it) {
      Cylinder cyl{vec3(c, "base_m", what + ": cylinders"), vec3(c, "axis", what + ": cylinders"),
                   positive(c, "length_m", what + ": cylinders", 1.0),
                   positive(c, "radius_m", what + ": cylinders", 0.05)};
      if (cyl.axis.norm() < 1e-9) fail(what, "cylinders: 'axis' must not be zero");
      cyl.axis.normalize();
      s.cylinders.push_back(cyl);
    }
  }
  if (auto it = j.find("handrails"); it != j.end()) {
    for (const json& h : *it) {
      const std::string side = h.contains("side") ? text(h, "side", what + ": handrails") : "left";
      if (side != "left" && side != "right") fail(what, "handrails: 'side' must be left or right");
      const int flight = static_cast<int>(num(h, "flight", what, 0));
      if (flight < 0 || flight >= static_cast<int>(s.flights.size())) fail(what, "handrails: 'flight' out of range");
      s.cylinders.push_back(handrail(s, flight, side == "left" ? 1 : -1, positive(h, "height_m", what, 0.9)));
    }
  }
}

Scene scene_from_json(const json& j, const std::string& what) {
  if (!j.is_object()) fail(what, "not a JSON object");
  Scene s;
  if (auto it = j.find("preset"); it != j.end()) {
    if (!it->is_string()) fail(what, "'preset' is not a string");
    try {
      s = make_preset(it->get<std::string>());
    } catch (const std::invalid_argument& e) {
      fail(what, e.what());
    }
  }
  if (j.contains("name")) s.name = text(j, "name", what);
  if (auto it = j.find("kind"); it != j.end()) {
    auto k = kind_names().find(text(j, "kind", what));
    if (k == kind_names().end()) fail(what, "'kind' must be stairs, flat_room or ramp");
    s.kind = k->second;
  }
  if (auto it = j.find("walls"); it != j.end()) {
    try {
      s.walls = walls_from_name(text(j, "walls", what));
    } catch (const std::invalid_argument& e) {
      fail(what, std::string("'walls': ") + e.what());
    }
  }
  s.width_m = positive(j, "width_m", what, s.width_m);
  s.nosing_m = num(j, "nosing_m", what, s.nosing_m);
  s.nosing_thickness_m = positive(j, "nosing_thickness_m", what, s.nosing_thickness_m);
  s.wall_height_m = positive(j, "wall_height_m", what, s.wall_height_m);
  s.floor_length_m = positive(j, "floor_length_m", what, s.floor_length_m);
  s.room_width_m = positive(j, "room_width_m", what, s.room_width_m);
  s.flat_length_m = positive(j, "flat_length_m", what, s.flat_length_m);
  s.ramp_length_m = positive(j, "ramp_length_m", what, s.ramp_length_m);
  s.ramp_height_m = positive(j, "ramp_height_m", what, s.ramp_height_m);
  s.ramp_landing_m = positive(j, "ramp_landing_m", what, s.ramp_landing_m);
  s.walk_end_m = num(j, "walk_end_m", what, s.walk_end_m);
  if (j.contains("dark_treads")) {
    if (!j["dark_treads"].is_boolean()) fail(what, "'dark_treads' is not true/false");
    s.dark_treads = j["dark_treads"].get<bool>();
  }
  if (j.contains("open_risers")) {
    if (!j["open_risers"].is_boolean()) fail(what, "'open_risers' is not true/false");
    s.open_risers = j["open_risers"].get<bool>();
  }
  if (s.nosing_m < 0.0 || s.nosing_m > 0.1) fail(what, "'nosing_m' must be within 0..0.1");
  if (j.contains("back_wall")) {
    if (!j["back_wall"].is_boolean()) fail(what, "'back_wall' is not true/false");
    s.back_wall = j["back_wall"].get<bool>();
  }
  flights_from_json(j, what, s);
  obstacles_from_json(j, what, s);
  if (s.kind == SceneKind::Stairs && s.flights.empty()) fail(what, "a stairs scene needs 'flights'");
  return s;
}

json scene_to_json(const Scene& s) {
  json flights = json::array();
  for (const FlightSpec& f : s.flights) flights.push_back({{"risers_m", f.riser_m}, {"treads_m", f.tread_m}});
  json boxes = json::array(), cyls = json::array();
  auto arr = [](const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); };
  for (const Box& b : s.boxes) boxes.push_back({{"min_m", arr(b.min_m)}, {"max_m", arr(b.max_m)}});
  for (const Cylinder& c : s.cylinders)
    cyls.push_back({{"base_m", arr(c.base_m)}, {"axis", arr(c.axis)}, {"length_m", c.length_m},
                    {"radius_m", c.radius_m}});
  return {{"name", s.name},
          {"kind", name_of(kind_names(), s.kind)},
          {"flights", flights},
          {"width_m", s.width_m},
          {"nosing_m", s.nosing_m},
          {"nosing_thickness_m", s.nosing_thickness_m},
          {"walls", name_of(wall_names(), s.walls)},
          {"wall_height_m", s.wall_height_m},
          {"floor_length_m", s.floor_length_m},
          {"room_width_m", s.room_width_m},
          {"flat_length_m", s.flat_length_m},
          {"back_wall", s.back_wall},
          {"ramp_length_m", s.ramp_length_m},
          {"ramp_height_m", s.ramp_height_m},
          {"ramp_landing_m", s.ramp_landing_m},
          {"walk_end_m", s.walk_end_m},
          {"dark_treads", s.dark_treads},
          {"open_risers", s.open_risers},
          {"boxes", boxes},
          {"cylinders", cyls}};
}

}  // namespace stairs::sim
