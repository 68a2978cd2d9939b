#include "drivers/sim/sim_setup.hpp"

#include "common/cloud.hpp"
#include "common/json_io.hpp"
#include "drivers/sim/furniture.hpp"

#include <cmath>
#include <stdexcept>

namespace stairs::sim {
namespace {

const char* const kSensorSwitches[][2] = {
    {"no-shadow", "projector (d435: second imager) shadow"},     {"no-axial-noise", "axial noise"},
    {"no-quantisation", "disparity quantisation"},
    {"no-lateral-noise", "edge effects (kinect1: edges wander, kinect2: flying pixels, d435: holes)"},
    {"no-multipath", "kinect2 multipath in concave corners"},
    {"no-grazing", "grazing-incidence dropout"},   {"no-holes", "random holes"}};

// The sensor's native intrinsics, scaled to --resolution when given.
Intrinsics parse_resolution(const std::string& r, SensorKind sensor) {
  if (r.empty()) return sensor_intrinsics(sensor);
  int w = 0, h = 0;
  char x = 0;
  if (std::sscanf(r.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' || w < 16 || h < 16 || w > 2048 || h > 2048)
    throw std::runtime_error("--resolution: expected WIDTHxHEIGHT (e.g. 640x480, 320x240), got '" + r + "'");
  return sensor_intrinsics(sensor, w, h);
}

double positive(const Options& o, const std::string& name) {
  const double v = o.get_double(name);
  if (!(v > 0.0)) throw std::runtime_error("--" + name + " must be positive");
  return v;
}

}  // namespace

void add_setup_options(Options& o) {
  o.add("list", "", "list the scene presets and exit")
      .add("preset", "NAME", "scene preset (see --list)", "straight_up")
      .add("scenario", "FILE", "scene from a JSON scenario file (drivers/sim/README.md); may name a preset")
      .add("steps", "N", "override: steps per flight (uniform risers/treads)")
      .add("riser", "M", "override: riser height of every step")
      .add("tread", "M", "override: tread depth (going) of every step but the landings")
      .add("landing", "M", "override: depth of every flight's landing")
      .add("width", "M", "override: flight width")
      .add("nosing", "M", "override: nosing overhang")
      .add("walls", "SIDES", "override: side walls none|left|right|both")
      .add("open-risers", "", "override: open risers (every step but a landing a tread slab on nothing)")
      .add("furniture", "FAMILY",
           "a furniture family (--list; sizes from --seed) beside the flight's foot, on its left (needs no left wall)")
      .add("direction", "DIR", "up or down; auto = down for presets named *_down", "auto")
      .add("situation", "S",
           "approach|first_step|flight|landing|full, or round_trip: the whole stair, a half turn on the spot on "
           "the far landing (4 s) and back",
           "full")
      .add("carrier", "C", "handheld (1 m high, pitch -35 deg, gait wobble) or robot (0.45 m, pitching with the slope)",
           "handheld")
      .add("speed", "M/S", "walking speed along the path (carrier default: handheld 0.6, robot 0.3)")
      .add("fps", "HZ", "frame rate", "30")
      .add("height", "M", "camera height above the surface beneath (carrier default)")
      .add("pitch", "DEG", "camera pitch, negative = down (carrier default: handheld -35, robot mount -20)")
      .add("lateral", "M", "offset from the flight's centre line, + = left", "0")
      .add("yaw", "DEG", "heading offset from straight up/down the stair", "0")
      .add("roll", "DEG", "hand-held: camera roll about its optical axis, + = right side down (a robot's rolls with its body)", "0")
      .add("wobble", "X", "scale of the hand-held wobble / robot vibration, 0 = steady", "1")
      .add("approach", "M", "distance before the first edge where approach/full start", "3")
      .add("sensor", "NAME", "kinect1 (structured light, 640x480), kinect2 (time of flight, 512x424) or d435 (stereo, 640x480)",
           "kinect1")
      .add("resolution", "WxH", "depth resolution; the sensor's native intrinsics scaled (default: native)")
      .add("perfect", "", "noiseless depth: no sensor effects except the 0.5-4.5 m range");
  for (const auto& s : kSensorSwitches) o.add(s[0], "", std::string("switch off the ") + s[1]);
  o.add("depth-warp", "FRACTION",
        "smooth depth warp as real cameras show: depth x (1 + FRACTION (rho^2 - 1/2)), rho = radius over the "
        "half-diagonal (e.g. 0.01; 0 = off)",
        "0");
  o.add("seed", "N", "random seed: the same seed gives the same bytes (and a furniture preset's sizes)", "1");
}

SimSetup setup_from_options(const Options& o) {
  SimSetup s;
  if (o.has("scenario")) {
    const std::string path = o.get("scenario");
    s.scene = scene_from_json(read_json_file(path), path);
  } else {
    try {
      s.scene = make_preset(o.get("preset"));
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(std::string("--preset: ") + e.what());
    }
  }
  Scene& sc = s.scene;
  if (o.has("steps") || o.has("riser") || o.has("tread") || o.has("landing")) {
    if (sc.kind != SceneKind::Stairs) throw std::runtime_error("--steps/--riser/--tread/--landing need a stairs scene");
    for (FlightSpec& f : sc.flights) {
      const int steps = o.has("steps") ? o.get_int("steps") : static_cast<int>(f.riser_m.size());
      if (steps < 1 || steps > 100) throw std::runtime_error("--steps must be within 1..100");
      const double riser = o.has("riser") ? positive(o, "riser") : f.riser_m.front();
      const double tread = o.has("tread") ? positive(o, "tread") : (f.tread_m.size() > 1 ? f.tread_m.front() : 0.25);
      const double landing = o.has("landing") ? positive(o, "landing") : f.tread_m.back();
      f = uniform_flight(steps, riser, tread, landing);
    }
  }
  if (o.has("width")) sc.width_m = positive(o, "width");
  if (o.has("nosing")) {
    sc.nosing_m = o.get_double("nosing");
    if (sc.nosing_m < 0.0 || sc.nosing_m > 0.1) throw std::runtime_error("--nosing must be within 0..0.1 m");
  }
  if (o.has("walls")) {
    try {
      sc.walls = walls_from_name(o.get("walls"));
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(std::string("--walls: ") + e.what());
    }
  }

  if (o.flag("open-risers")) {
    if (sc.kind != SceneKind::Stairs) throw std::runtime_error("--open-risers needs a stairs scene");
    sc.open_risers = true;
  }

  try {
    s.sensor = sensor_preset(o.get("sensor"));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("--sensor: ") + e.what());
  }
  s.K = parse_resolution(o.has("resolution") ? o.get("resolution") : "", s.sensor.kind);

  s.sensor.perfect = o.flag("perfect");
  s.sensor.multipath = s.sensor.multipath && !o.flag("no-multipath");
  s.sensor.shadow = s.sensor.shadow && !o.flag("no-shadow");
  s.sensor.axial_noise = s.sensor.axial_noise && !o.flag("no-axial-noise");
  s.sensor.quantisation = s.sensor.quantisation && !o.flag("no-quantisation");
  s.sensor.lateral_noise = s.sensor.lateral_noise && !o.flag("no-lateral-noise");
  s.sensor.grazing_dropout = s.sensor.grazing_dropout && !o.flag("no-grazing");
  s.sensor.holes = s.sensor.holes && !o.flag("no-holes");
  s.sensor.depth_warp = o.get_double("depth-warp");
  if (!(std::abs(s.sensor.depth_warp) <= 0.1)) throw std::runtime_error("--depth-warp must be within -0.1..0.1");

  TrajectoryConfig& t = s.trajectory;
  try {
    t = trajectory_defaults(carrier_from_name(o.get("carrier")));
    t.situation = situation_from_name(o.get("situation"));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  const std::string dir = o.get("direction");
  if (dir == "auto") t.descending = sc.name.size() > 5 && sc.name.substr(sc.name.size() - 5) == "_down";
  else if (dir == "up" || dir == "down") t.descending = dir == "down";
  else throw std::runtime_error("--direction must be up, down or auto");
  if (o.has("speed")) t.speed_mps = positive(o, "speed");
  t.fps = positive(o, "fps");
  if (o.has("height")) t.height_m = positive(o, "height");
  if (o.has("pitch")) t.pitch_deg = o.get_double("pitch");
  t.lateral_m = o.get_double("lateral");
  t.yaw_deg = o.get_double("yaw");
  t.roll_deg = o.get_double("roll");
  if (t.roll_deg != 0.0 && t.carrier != Carrier::HandHeld)
    throw std::runtime_error("--roll is for a hand-held camera: a robot's camera rolls with its body (mount)");
  if (std::abs(t.roll_deg) > 45.0) throw std::runtime_error("--roll must be within +-45 deg");
  t.wobble = o.get_double("wobble");
  t.approach_m = positive(o, "approach");
  const double seed = o.get_double("seed");
  if (seed < 0 || seed != std::floor(seed)) throw std::runtime_error("--seed must be a non-negative integer");
  s.seed = static_cast<uint64_t>(seed);
  // A furniture family's sizes are drawn from the seed too (one seed, one room).
  if (!o.has("scenario") && is_furniture(o.get("preset"))) s.scene = furniture_scene(o.get("preset"), s.seed);
  if (o.has("furniture")) {
    try {
      furnish_beside_flight(s.scene, o.get("furniture"), s.seed);
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(std::string("--furniture: ") + e.what());
    }
  }
  return s;
}

nlohmann::json setup_to_json(const SimSetup& s) {
  const SensorModel& m = s.sensor;
  const TrajectoryConfig& t = s.trajectory;
  return {{"seed", s.seed},
          {"camera", to_json(s.K, 0.001)},
          {"sensor",
           {{"model", sensor_name(m.kind)},
            {"perfect", m.perfect},
            {"shadow", m.shadow},
            {"axial_noise", m.axial_noise},
            {"quantisation", m.quantisation},
            {"lateral_noise", m.lateral_noise},
            {"grazing_dropout", m.grazing_dropout},
            {"multipath", m.multipath},
            {"holes", m.holes},
            {"depth_warp", m.depth_warp},
            {"range_m", {m.min_range_m, m.max_range_m}}}},
          {"trajectory",
           {{"carrier", carrier_name(t.carrier)},
            {"situation", situation_name(t.situation)},
            {"direction", t.descending ? "down" : "up"},
            {"speed_mps", t.speed_mps},
            {"fps", t.fps},
            {"height_m", t.height_m},
            {"pitch_deg", t.pitch_deg},
            {"lateral_m", t.lateral_m},
            {"yaw_deg", t.yaw_deg},
            {"roll_deg", t.roll_deg},
            {"wobble", t.wobble}}},
          {"scenario", scene_to_json(s.scene)}};
}

}  // namespace stairs::sim
