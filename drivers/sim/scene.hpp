// Parametric scenes of the simulator: straight staircases in the stair frame of
// DESIGN.md (x along the ascending direction, y left, z up, origin on the floor
// at the bottom edge of the first riser, on the flight's centre line), plus a
// few non-stair scenes. A Scene holds parameters only; geometry.hpp turns it
// into faces.
#pragma once

#include "common/types.hpp"

#include <nlohmann/json.hpp>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace stairs::sim {

// One straight flight. Step i is riser i plus the tread above it; the last
// step's tread is the landing above the flight (mid landing or top landing).
struct FlightSpec {
  std::vector<double> riser_m;  // per step, bottom first
  std::vector<double> tread_m;  // per step: going (nosing to nosing); last = landing depth
};

// Uniform flight: `steps` risers, the last tread being a landing of landing_m.
FlightSpec uniform_flight(int steps, double riser_m, double tread_m, double landing_m);

enum class SceneKind { Stairs, FlatRoom, Ramp };
enum class Walls { None, Left, Right, Both };
Walls walls_from_name(const std::string& name);  // none, left, right, both; throws std::invalid_argument

struct Box {  // axis-aligned clutter, stair frame
  Eigen::Vector3d min_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d max_m = Eigen::Vector3d::Zero();
};

struct Cylinder {  // finite capped cylinder, stair frame
  Eigen::Vector3d base_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit
  double length_m = 1.0;
  double radius_m = 0.05;
};

struct Scene {
  std::string name = "custom";
  SceneKind kind = SceneKind::Stairs;
  // Stairs: flights follow each other along x (a mid landing is the
  // last step of its flight). Ramp and FlatRoom ignore them.
  std::vector<FlightSpec> flights;
  double width_m = 1.2;          // flight width (between the side walls)
  double nosing_m = 0.0;         // overhang of each tread over the riser below
  double nosing_thickness_m = 0.04;  // tread slab thickness at the overhang
  Walls walls = Walls::Both;
  double wall_height_m = 2.6;    // above the highest tread
  double floor_length_m = 5.0;   // floor in front of the first riser (x < 0)
  double room_width_m = 4.0;     // floor and room width where a side is open
  bool back_wall = true;         // wall at the far end of the top landing
  double flat_length_m = 4.0;    // FlatRoom: floor beyond x = 0 up to the far wall
  // Ramp: an incline from x = 0 rising to ramp_height_m over ramp_length_m,
  // then a top landing of ramp_landing_m.
  double ramp_length_m = 3.0;
  double ramp_height_m = 0.3;
  double ramp_landing_m = 2.0;
  bool dark_treads = false;        // treads absorb the IR: SensorModel::dark_dropout of their pixels read nothing
  bool open_risers = false;        // each step but a landing is a tread slab (nosing_thickness_m) on nothing: no
                                   // riser below it, the floor under the flight seen between the slabs
  double walk_end_m = 0.0;         // FlatRoom: > 0 = the walk along x stops here (furniture beyond)
  std::vector<Box> boxes;          // clutter
  std::vector<Cylinder> cylinders; // clutter, handrails
};

// Presets by name: straight_up, straight_down, irregular, nosing, open_sides,
// wall_left, two_flights, cluttered, flat_room, ramp, curb, and the furniture
// families of furniture.hpp at their nominal sizes (see preset_names()).
Scene make_preset(const std::string& name);  // throws std::invalid_argument naming the preset
std::vector<std::string> preset_names();
std::string preset_summary(const std::string& name);

// Handrail along a flight's nosing line, height_m above it, on the given side (+1 left, -1 right).
Cylinder handrail(const Scene& s, int flight, int side, double height_m = 0.9);
// The balusters under such a handrail: two posts per tread (at a quarter and three quarters of its
// depth), 2.4 cm thick, from the tread up to the rail.
std::vector<Cylinder> balusters(const Scene& s, int flight, int side, double height_m = 0.9);

// Scenario files (JSON). Keys: see drivers/sim/README.md. Throws
// std::runtime_error "WHAT: reason" naming the key.
Scene scene_from_json(const nlohmann::json& j, const std::string& what);
nlohmann::json scene_to_json(const Scene& s);

// Derived geometry of the stair (stair frame).
struct StepGeometry {
  int flight = 0;
  double riser_x_m = 0.0;  // x of the riser face
  double bottom_z_m = 0.0; // z of the tread below
  double top_z_m = 0.0;    // z of this step's tread
  double end_x_m = 0.0;    // x where the next riser (or the landing's end) is
  double riser_m = 0.0;    // as specified (top_z_m - bottom_z_m up to rounding)
  double tread_m = 0.0;    // as specified (end_x_m - riser_x_m up to rounding)
  bool landing = false;
};
std::vector<StepGeometry> step_geometry(const Scene& s);

// Ground truth of the whole stair (flights with riser, tread, landing, nosing).
GroundTruth scene_truth(const Scene& s);

// Height (z) of the walkable surface at (x, y): floor, tread, landing or ramp;
// clutter ignored.
double surface_height_m(const Scene& s, double x_m, double y_m);

// Extent of the walkable area along x: [floor start, far end of the top landing].
double scene_start_x_m(const Scene& s);
double scene_end_x_m(const Scene& s);

}  // namespace stairs::sim
