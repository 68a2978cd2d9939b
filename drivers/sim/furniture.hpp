// Negative scenes: rooms with furniture and no stair, as families whose sizes
// are drawn from a seed (seed 0 = the nominal sizes). The camera walks towards
// the furniture from 3.5 m to 0.8 m away (Scene::walk_end_m). Chair seats,
// table tops, sofas and shelves give level surfaces at stair-like heights:
// perception must report no staircase on any frame.
#pragma once

#include "drivers/sim/scene.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace stairs::sim {

// kitchen_table, sofa, armchair, bed, desk, bookshelf, boxes, counter_stools,
// bench, planter, tv_stand.
std::vector<std::string> furniture_families();
bool is_furniture(const std::string& name);

// Throws std::invalid_argument naming the family when it is unknown.
Scene furniture_scene(const std::string& family, uint64_t seed);

// A family's pieces (sizes from `seed`) set beside a stair's foot: on the flight's left, clear of it
// by kBesideGap_m, their far end kBesideGap_m before the first riser, facing the approach; the room
// is widened to hold them. A kitchen or a hall next to a real flight: its seats and tops at stair-like
// heights beside true steps. Throws std::invalid_argument for an unknown family, a scene that is no
// stair, or a wall on the flight's left.
void furnish_beside_flight(Scene& stair, const std::string& family, uint64_t seed);

}  // namespace stairs::sim
