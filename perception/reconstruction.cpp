#include "perception/reconstruction.hpp"

#include "common/median.hpp"
#include "perception/grammar.hpp"

#include <algorithm>
#include <cmath>

namespace stairs {

namespace {

// A segmented riser whose face lies between axial positions s_lo and s_hi and
// which spans upwards (above = true) or downwards from height z (within
// contact_m) by more than min_span_m, or by more than cut_min_span_m where the
// image's border cuts its far end off (a sliver of it is then as good as more),
// at least min_width_m wide.
int riser_at(const PlaneSet& ps, float s_lo, float s_hi, float z, bool above, float min_span_m, float cut_min_span_m,
             float contact_m, float min_width_m) {
  return find_riser(ps, s_lo, s_hi, 0.5f * (s_lo + s_hi), min_width_m, [&](const PlaneExtent& e) {
    return above ? std::abs(e.z_min - z) < contact_m && e.z_max > z + (e.top_in_view ? min_span_m : cut_min_span_m)
                 : std::abs(e.z_max - z) < contact_m && e.z_min < z - (e.bottom_in_view ? min_span_m : cut_min_span_m);
  });
}

// The horizontal plane at a riser's foot: level with its bottom, reaching it
// (or passing beside it: a floor wider than the flight).
int level_at_foot(const PlaneSet& ps, const PlaneExtent& riser, float contact_m) {
  for (size_t i = 0; i < ps.planes.size(); ++i) {
    const PlaneExtent& e = ps.extents[i];
    if (ps.planes[i].kind == PlaneKind::Tread && std::abs(e.z_mean - riser.z_min) < contact_m &&
        e.z_mean < riser.z_max - contact_m && e.s_min < riser.s_mean && e.s_max > riser.s_mean - 2 * contact_m)
      return static_cast<int>(i);
  }
  return -1;
}

double median_rise(const std::vector<Step>& steps) {
  std::vector<double> rises;
  for (const Step& s : steps) rises.push_back(*s.riser_height_m);
  return median(rises);
}

// Going up, the chain's first level is a step too when a riser rises to its
// front edge (its bottom is usually out of view: the rise is the chain's
// median), and a riser standing on the last level is the next step, its tread
// out of view ("treads between risers").
void complete_ascending(const PlaneSet& ps, const StairChain& chain, std::vector<Step>& steps,
                        const StairConfig& cfg) {
  if (steps.empty()) return;
  const double median = median_rise(steps);
  const Level& base = chain.levels.front();
  const float contact = cfg.riser_contact_m;
  const float sliver = static_cast<float>(cfg.min_riser_seen_fraction * median);
  if (const int r = riser_at(ps, base.s_min - 2 * contact, base.s_min + 2 * contact, base.z, false, contact, sliver,
                             contact, cfg.riser_min_width_m);
      r >= 0) {
    Step s;
    s.riser_plane = r;
    s.tread_plane = base.plane;
    // Measured from the surface at the riser's foot (too low a rise for the
    // grammar: the floor under a short first riser), else from the riser's foot
    // where it is in view up to the level on top (not to the riser's own top:
    // under a nosing overhang that is the slab's underside, a slab's thickness
    // low); otherwise the median is a prior, flagged.
    const PlaneExtent& e = ps.extents[r];
    const int floor = level_at_foot(ps, e, contact);
    s.riser_height_m = floor >= 0 ? base.z - ps.extents[floor].z_mean : e.bottom_in_view ? base.z - e.z_min : median;
    // A level that is a riser's top (its tread seen from below, or edge-on) is no measured height.
    if ((floor < 0 && !e.bottom_in_view) || base.riser_top) s.inferred |= kStepRiserInferred;
    // At the riser's face, as every other step whose riser is seen (steps_from_chain): the level's
    // trimmed front lies behind it (its edge cells are lost at the corner; 1.8 cm on a synthetic
    // stair, its tread 1.8 cm short), and on a nosing overhang, where the face stands 3 cm behind
    // the edge, this one step placed otherwise than its neighbours pulled the tracker's camera by
    // 2.5 cm (a Kinect v2 steep flight's model treads: 0.62 -> 0.37 cm error).
    s.nosing_m = ps.to_camera(e.s_mean, 0.5f * (base.t_min + base.t_max), base.z).cast<double>();
    s.width_m = base.t_max - base.t_min;
    steps.insert(steps.begin(), s);
  }
  const Level& top = chain.levels.back();
  // A flight ends at a landing: a riser beyond one starts the next flight, and
  // with its top cut by the view nothing shows a step there (a landing's back
  // wall looks the same). It is a step once its top is seen.
  const bool top_is_landing = top.plane >= 0 && top.s_max - top.s_min > cfg.landing_min_depth_m;
  // The next riser stands at the top level's far end; when that level is a
  // riser's top (a tread seen edge-on from a low camera) its far end is
  // unseen: the riser stands a plausible tread beyond.
  const float s_lo = top.plane >= 0 ? top.s_max - 2 * cfg.riser_contact_m
                                    : top.s_max + static_cast<float>(cfg.tread_min_m * (1 - cfg.din_tolerance));
  const float s_hi = top.plane >= 0 ? top.s_max + 2 * cfg.riser_contact_m
                                    : top.s_max + static_cast<float>(cfg.tread_max_m * (1 + cfg.din_tolerance));
  // Its top is usually cut off by the view: a sliver of it is as good as more
  // (one whose top is in view is measured against DIN below).
  if (const int r = riser_at(ps, s_lo, s_hi, top.z, true, sliver, sliver, cfg.riser_contact_m, cfg.riser_min_width_m);
      r >= 0) {
    const PlaneExtent& e = ps.extents[r];
    const double seen = e.z_max - top.z;
    // A riser whose top is in view is measured; one that rises beyond DIN's
    // bounds is no step's (a wall, a cabinet), and neither is one cut by the view
    // whose seen part alone is taller than any riser (a landing's back wall).
    // A cut one's height is the median, flagged.
    if (e.top_in_view ? !din_riser_ok(seen, cfg) : top_is_landing || seen > cfg.highest_rise_m())
      return;
    Step s;
    s.riser_plane = r;
    s.riser_height_m = e.top_in_view ? seen : median;
    // With no tread seen above it, a riser's top is no measured level either
    // (under a nosing overhang it is the slab's underside): the rise is flagged.
    s.inferred |= e.top_in_view ? kStepRiserInferred : kStepRiserInferred | kStepNosingInferred;
    s.nosing_m = ps.to_camera(e.s_mean, 0.5f * (e.t_min + e.t_max), top.z + static_cast<float>(*s.riser_height_m))
                     .cast<double>();
    s.width_m = e.t_max - e.t_min;
    steps.push_back(s);
  }
}

// Going down, the last level of a staircase (min_steps already) is a step too
// when a depth jump shows its nosing: a tread, or a landing with the next
// flight below its edge (a floor ends at a wall, not at a drop); the riser
// below it is out of view (the rise is the chain's median).
void complete_descending(const PlaneSet& ps, const StairChain& chain, std::vector<Step>& steps,
                         const StairConfig& cfg) {
  const Level& last = chain.levels.back();
  if (static_cast<int>(steps.size()) < cfg.min_steps || !last.far_edge) return;
  Step s;
  s.tread_plane = last.plane;
  s.riser_height_m = median_rise(steps);
  s.inferred |= kStepRiserInferred;
  s.nosing_m = ps.to_camera(last.edge_s, 0.5f * (last.t_min + last.t_max), last.z).cast<double>();
  s.width_m = last.t_max - last.t_min;
  steps.push_back(s);
}

}  // namespace

void reconstruct(PlaneSet& ps, const StairChain& chain, std::vector<Step>& steps, const StairConfig& cfg) {
  const bool up = chain.direction == Direction::Up;
  if (up) complete_ascending(ps, chain, steps, cfg);
  else if (chain.direction == Direction::Down) complete_descending(ps, chain, steps, cfg);
  // Steps are nearest first: going up the next step is farther and higher,
  // going down the next step is farther and lower; either way a tread reaches
  // from its nosing to the next nosing.
  for (size_t k = 0; k < steps.size(); ++k) {
    if (up && k + 1 == steps.size() && steps[k].tread_plane < 0) steps[k].tread_depth_m.reset();
    // The nearest tread going down and the farthest going up show only their visible part.
    if ((up ? k + 1 == steps.size() : k == 0) && steps[k].tread_depth_m) steps[k].inferred |= kStepTreadPartial;
    if (up && k + 1 < steps.size()) steps[k].tread_depth_m = ps.axial(steps[k + 1].nosing_m) - ps.axial(steps[k].nosing_m);
    if (!up && k >= 1) steps[k].tread_depth_m = ps.axial(steps[k].nosing_m) - ps.axial(steps[k - 1].nosing_m);
    steps[k].landing = steps[k].tread_depth_m && *steps[k].tread_depth_m > cfg.landing_min_depth_m;
  }
  if (up) return;
  for (size_t k = 0; k < steps.size(); ++k) {
    Step& s = steps[k];
    if (s.riser_plane >= 0 || !s.riser_height_m) continue;
    const Level& tread = chain.levels[k];
    const float sa = ps.axial(s.nosing_m), top = tread.z, bottom = tread.z - static_cast<float>(*s.riser_height_m);
    Plane p;
    p.kind = PlaneKind::Riser;
    p.source = PlaneSource::Reconstructed;
    p.normal = ps.to_camera(-1, 0, 0);
    p.corners[Plane::kTopLeft] = ps.to_camera(sa, tread.t_max, top);
    p.corners[Plane::kTopRight] = ps.to_camera(sa, tread.t_min, top);
    p.corners[Plane::kBottomLeft] = ps.to_camera(sa, tread.t_max, bottom);
    p.corners[Plane::kBottomRight] = ps.to_camera(sa, tread.t_min, bottom);
    p.centroid = ps.to_camera(sa, 0.5f * (tread.t_min + tread.t_max), 0.5f * (top + bottom));
    p.length_m = tread.t_max - tread.t_min;
    p.extent_m = top - bottom;
    PlaneExtent e{sa, sa, tread.t_min, tread.t_max, bottom, top, sa, 0.5f * (top + bottom)};
    s.riser_plane = static_cast<int>(ps.planes.size());
    ps.planes.push_back(std::move(p));
    ps.extents.push_back(e);
  }
}

}  // namespace stairs
