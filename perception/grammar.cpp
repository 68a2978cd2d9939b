#include "perception/grammar.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace stairs {

bool din_riser_ok(double r, const StairConfig& c) {
  return r >= c.lowest_rise_m() && r <= c.highest_rise_m();
}
bool din_tread_ok(double t, const StairConfig& c) {
  return t >= c.tread_min_m * (1 - c.din_tolerance) && t <= c.tread_max_m * (1 + c.din_tolerance);
}
bool din_rule_ok(double r, double t, const StairConfig& c) {
  const double v = 2 * r + t;
  return v >= c.step_rule_min_m * (1 - c.din_tolerance) && v <= c.step_rule_max_m * (1 + c.din_tolerance);
}

namespace {

// Relative distance of a value from the un-widened DIN interval.
double deviation(double v, double lo, double hi) { return v < lo ? (lo - v) / lo : v > hi ? (v - hi) / hi : 0.0; }

bool laterally_overlapping(const Level& a, const Level& b, const StairConfig& c) {
  return std::max(a.t_min, b.t_min) - std::min(a.t_max, b.t_max) <= c.max_lateral_gap_m;
}

// Deviation of the successor `b` of `a` (nullopt = not a successor). `prev_nosing`
// is a's nosing when a is itself a step (its tread depth is then known).
std::optional<double> successor(const Level& a, const Level& b, Direction dir, std::optional<float> a_nosing,
                                const StairConfig& c) {
  // A riser facing the camera stands in front of the level on its top: going
  // down, risers face away, so such a level is in no descending flight (a
  // table's legs seen under its top are).
  if (dir == Direction::Down && (a.riser_top || b.riser_top)) return std::nullopt;
  // A descending flight is seen from above: its levels lie below the eye (seen from below, a flight
  // rises away from the camera). A robot's camera under a chair's back, a table's edge and the
  // seat's (their depth jumps, seen from below) had them as a flight going down.
  if (dir == Direction::Down && (a.z >= 0 || b.z >= 0)) return std::nullopt;
  const float rise = dir == Direction::Up ? b.z - a.z : a.z - b.z;
  if (!din_riser_ok(rise, c) || !laterally_overlapping(a, b, c)) return std::nullopt;
  // A step rises above the whole of the level below it: a tread is level
  // within noise, a slope (a ramp cut into patches) rises through the height
  // of the next "step" by itself.
  const Level& lower = dir == Direction::Up ? a : b;
  const Level& upper = dir == Direction::Up ? b : a;
  const float spread = c.level_max_spread_of_rise * rise;
  if (lower.reach_above_m > spread || upper.reach_below_m > spread) return std::nullopt;
  double dev = deviation(rise, c.riser_min_m, c.riser_max_m);
  if (dir == Direction::Up) {
    if (b.s_min <= a.s_min) return std::nullopt;
    // A level seen only as its front edge (a riser's top, a nosing's depth
    // jump: a tread above the camera or edge-on) has an unseen tread reaching
    // to the next riser, a tread's depth away. Only a seen tread can be a
    // landing, so the gap is a plausible tread.
    const float gap = b.s_min - end_under(a, b, c.max_level_gap_m);
    if (a.s_max <= a.s_min ? !din_tread_ok(gap, c) : std::abs(gap) > c.max_level_gap_m) return std::nullopt;
    if (a_nosing) {
      const float tread = b.s_min - *a_nosing;
      if (tread < c.landing_min_depth_m) {
        if (!din_tread_ok(tread, c) || !din_rule_ok(rise, tread, c)) return std::nullopt;
        dev += deviation(tread, c.tread_min_m, c.tread_max_m);
      }
    }
  } else {
    // Going down the lower tread shows beyond the upper nosing (its near part is hidden).
    if (b.s_max <= a.s_max || start_beyond(b, a, c.max_level_gap_m) < a.s_max - c.max_level_gap_m) return std::nullopt;
    const float tread = b.s_max - a.s_max;
    // A level seen only as its nosing's jump (a far tread, a strip too thin for
    // a plane) is a tread between two nosings: only a seen tread can be a landing.
    if (b.s_max <= b.s_min && !din_tread_ok(tread, c)) return std::nullopt;
    if (tread < c.landing_min_depth_m) {
      if (!din_tread_ok(tread, c) || !din_rule_ok(rise, tread, c)) return std::nullopt;
      dev += deviation(tread, c.tread_min_m, c.tread_max_m);
    }
  }
  return dev;
}

// Whether a tread plane other than `a` and `b` lies between them, in height and along the stair
// (between where a ends and b starts), across b's width: b rises (drops) over a step, not from a. A
// flight has no level between two consecutive treads; the step between is one the grammar did not
// take (a real Kinect v2's 8 cm first riser, under DIN's lowest rise, had the floor chained to the
// second tread, a 17.8 cm "rise" over a 30 cm "gap" the first tread filled). A plane, not a level
// of an edge's or a riser's top: a nosing's depth jump is seen a few centimetres off its tread's
// height, and going down such a level "between" cut descents.
bool level_between(const std::vector<Level>& levels, size_t a_index, size_t b_index, Direction dir,
                   const StairConfig& c) {
  const Level& a = levels[a_index];
  const Level& b = levels[b_index];
  const bool up = dir == Direction::Up;
  const float z_lo = std::min(a.z, b.z) + c.same_level_m, z_hi = std::max(a.z, b.z) - c.same_level_m;
  const float s_lo = up ? end_under(a, b, c.max_level_gap_m) : a.s_max;
  const float s_hi = up ? b.s_min : start_beyond(b, a, c.max_level_gap_m);
  for (size_t k = 0; k < levels.size(); ++k) {
    const Level& m = levels[k];
    if (k == a_index || k == b_index || m.plane < 0 || m.z <= z_lo || m.z >= z_hi || !laterally_overlapping(m, b, c))
      continue;
    const float mid = 0.5f * (m.s_min + m.s_max);
    if (mid > s_lo && mid < s_hi) return true;
  }
  return false;
}

// The tread that `b` adds after `a` is a landing (its depth is known).
bool is_landing(const Level& a, const Level& b, Direction dir, std::optional<float> a_nosing, const StairConfig& c) {
  if (dir == Direction::Up) return a_nosing && b.s_min - *a_nosing >= c.landing_min_depth_m;
  return b.s_max - a.s_max >= c.landing_min_depth_m;
}

StairChain grow_chain(const std::vector<Level>& levels, size_t start, Direction dir, const StairConfig& c) {
  StairChain chain;
  chain.direction = dir;
  chain.levels.push_back(levels[start]);
  std::vector<uint8_t> used(levels.size(), 0);
  used[start] = 1;
  size_t last = start;
  bool last_landing = false;
  for (;;) {
    const Level& a = chain.levels.back();
    std::optional<float> a_nosing;
    if (dir == Direction::Up && chain.levels.size() >= 2) a_nosing = a.s_min;
    int best = -1;
    double best_dev = 0;
    float best_rise = 0;
    bool best_landing = false;
    for (size_t j = 0; j < levels.size(); ++j) {
      if (used[j]) continue;
      const auto dev = successor(a, levels[j], dir, a_nosing, c);
      if (!dev || level_between(levels, last, j, dir, c)) continue;
      const float rise = std::abs(levels[j].z - a.z);
      // The successor is a step a tread's depth on where there is one (a level seen farther, the
      // top of a head or a box beyond the flight a few centimetres below a nosing, is no landing
      // before it: it cut a descent's chain at the top landing's edge), then the nearest in height.
      const bool landing = is_landing(a, levels[j], dir, a_nosing, c);
      if (best < 0 || (landing != best_landing ? !landing : rise < best_rise)) {
        best = static_cast<int>(j);
        best_dev = *dev;
        best_rise = rise;
        best_landing = landing;
      }
    }
    if (best < 0) break;
    // A landing counts once the chain goes on beyond it (the floor a flight
    // ends on is no landing).
    if (last_landing) ++chain.landings;
    last_landing = is_landing(a, levels[best], dir, a_nosing, c);
    used[best] = 1;
    last = static_cast<size_t>(best);
    chain.levels.push_back(levels[best]);
    chain.deviation += best_dev;
  }
  return chain;
}

}  // namespace

StairChain best_chain(const std::vector<Level>& levels, const StairConfig& c) {
  StairChain best;
  for (Direction dir : {Direction::Up, Direction::Down})
    for (size_t i = 0; i < levels.size(); ++i) {
      StairChain ch = grow_chain(levels, i, dir, c);
      // Landings need regular steps around them: a step, a deep "tread" and
      // another step are furniture, not a staircase.
      if (ch.landings > 0 && ch.steps() - ch.landings < c.min_steps) continue;
      if (ch.steps() > best.steps() || (ch.steps() == best.steps() && ch.deviation < best.deviation))
        best = std::move(ch);
    }
  if (best.steps() < 1) return StairChain{};
  return best;
}

}  // namespace stairs
