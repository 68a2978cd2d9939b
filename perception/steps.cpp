#include "perception/steps.hpp"

#include "common/median.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace stairs {

namespace {

// Whether the face of riser i goes on above its top: another plane facing the same way within 45
// degrees (not a wall along the flight), at the same place along the stair and side by side with
// it, starting no more than a level's tolerance (same_level_m: the cells between two segments are
// often neither's) above the riser's top and reaching beyond it (a nosing slab's front face ends at
// its tread). Its top is then no nosing: a riser's upper part merged with its nosing's slab is
// tilted, no riser's plane, and the lower part's top made a 9 cm "rise" and a false step (robots'
// Kinect v1 and v2 under 3 cm nosings).
bool face_goes_on_above(const PlaneSet& ps, size_t i, const StairConfig& cfg) {
  const PlaneExtent& e = ps.extents[i];
  const Eigen::Vector3f& n = ps.planes[i].normal;
  for (size_t j = 0; j < ps.planes.size(); ++j) {
    const PlaneExtent& f = ps.extents[j];
    if (j == i || ps.planes[j].kind == PlaneKind::Tread || ps.planes[j].normal.dot(n) < std::sqrt(0.5f)) continue;
    if (std::abs(f.s_mean - e.s_mean) > cfg.riser_at_nosing_m) continue;
    if (std::min(f.t_max, e.t_max) <= std::max(f.t_min, e.t_min)) continue;
    if (f.z_min < e.z_max + cfg.same_level_m && f.z_max > e.z_max + cfg.same_level_m) return true;
  }
  return false;
}

// Whether horizontal plane i lies inside the face of a riser facing the camera: all of it within
// riser_at_nosing_m of the face along the stair, below the riser's top by more than half a level's
// tolerance and above its foot by more than one. A tread starts at its riser's top and runs back
// from it; a band across a riser's face is the edge under a nosing overhang's slab, where the
// recessed riser meets the slab's front (a Kinect v2 robot's, 4 cm below the top: it stood for the
// tread and the model's rise came out 2.6 cm short).
bool inside_a_riser_face(const PlaneSet& ps, size_t i, const StairConfig& cfg) {
  const PlaneExtent& b = ps.extents[i];
  for (size_t j = 0; j < ps.planes.size(); ++j) {
    if (ps.planes[j].kind != PlaneKind::Riser) continue;
    const PlaneExtent& r = ps.extents[j];
    if (std::min(b.t_max, r.t_max) <= std::max(b.t_min, r.t_min)) continue;
    if (std::abs(b.s_min - r.s_mean) > cfg.riser_at_nosing_m || std::abs(b.s_max - r.s_mean) > cfg.riser_at_nosing_m)
      continue;
    if (b.z_mean < r.z_max - 0.5f * cfg.same_level_m && b.z_mean > r.z_min + cfg.same_level_m) return true;
  }
  return false;
}

}  // namespace

float end_under(const Level& a, const Level& b, float run_on_m) {
  if (a.s_max <= b.s_min + run_on_m) return a.s_max;
  const auto under = a.strips.across(b.t_min, b.t_max);
  return under ? under->second : a.s_max;
}

float start_beyond(const Level& b, const Level& a, float run_on_m) {
  if (b.s_min >= a.s_max - run_on_m) return b.s_min;
  const auto beyond = b.strips.across(a.t_min, a.t_max);
  return beyond ? beyond->first : b.s_min;
}

std::vector<Level> tread_levels(const PlaneSet& ps, const std::vector<JumpEdge>& edges, const StairConfig& cfg) {
  std::vector<Level> levels;
  for (size_t i = 0; i < ps.planes.size(); ++i) {
    const PlaneExtent& e = ps.extents[i];
    if (ps.planes[i].kind != PlaneKind::Tread || e.t_max - e.t_min < cfg.min_step_width_m) continue;
    if (inside_a_riser_face(ps, i, cfg)) continue;
    levels.push_back({static_cast<int>(i), e.z_mean, e.s_min, e.s_max, e.t_min, e.t_max});
    levels.back().strips = e.strips;
  }
  // Treads seen edge-on (a camera below or level with them) are too thin to
  // segment, but the riser below each one is in view: its top edge is the
  // tread's front ("treads between risers", thesis 4.5).
  const size_t n_treads = levels.size();
  const float same_level = cfg.same_level_m, behind = cfg.riser_own_behind_m, ahead = cfg.riser_own_ahead_m;
  // A tread less than the lowest plausible rise above a riser's top is that
  // riser's own: a nosing overhang hides the riser's top under its slab.
  const float min_rise_m = cfg.lowest_rise_m();
  // A riser at range splits across its width into fragments with one top:
  // they are one level, as wide as all of them together.
  std::vector<Level> tops;
  const float near = cfg.riser_at_nosing_m;
  const float max_rise_m = cfg.highest_rise_m();
  for (size_t i = 0; i < ps.planes.size(); ++i) {
    const PlaneExtent& e = ps.extents[i];
    if (ps.planes[i].kind != PlaneKind::Riser || !e.top_in_view || face_goes_on_above(ps, i, cfg)) continue;
    // A riser spans one rise: a face taller than the highest is a wall or a cabinet's front, and its
    // top no tread's front (a D435 robot's room: the back wall at 5 m in two fragments, 1.05 and 1.15 m
    // tall where its depth gave out, made a two-step flight of their tops).
    if (e.z_max - e.z_min > max_rise_m + same_level) continue;
    auto same = std::find_if(tops.begin(), tops.end(), [&](const Level& l) {
      return std::abs(l.z - e.z_max) < same_level && std::abs(l.s_min - e.s_mean) < near &&
             std::max(l.t_min, e.t_min) - std::min(l.t_max, e.t_max) < near;
    });
    if (same == tops.end()) {
      tops.push_back({-1, e.z_max, e.s_mean, e.s_mean, e.t_min, e.t_max, false, 0.0f, true});
    } else {
      same->t_min = std::min(same->t_min, e.t_min);
      same->t_max = std::max(same->t_max, e.t_max);
    }
  }
  // A tread whose front edge stands at the riser's face is that riser's own at any height up to the
  // highest rise: the riser's top lies hidden under its nosing, and seen from above at a steep angle
  // the slab and the shadow of its edge hide more than the lowest rise (a D435 at 0.6 m saw a riser
  // end 8.5 cm below its tread, and that "level" made an 8.5 cm and a 25.5 cm step of two 17 cm ones).
  for (const Level& top : tops) {
    if (top.t_max - top.t_min < cfg.min_step_width_m) continue;
    bool seen = false;
    for (size_t k = 0; k < n_treads && !seen; ++k) {
      const Level& l = levels[k];
      if (!(l.z > top.z - same_level)) continue;
      seen = (l.z < top.z + min_rise_m && l.s_max > top.s_min - behind && l.s_min < top.s_min + ahead) ||
             (l.z < top.z + max_rise_m && std::abs(l.s_min - top.s_min) < near);
    }
    if (!seen) levels.push_back(top);
  }
  // Likewise far treads seen from above are strips too thin for planes, but
  // their nosings show as depth jumps: the tread ends there. A jump at a
  // riser's top level belongs to it too (its nosing seen from below, or the
  // rim of a hole in a dark tread): one surface is one level.
  const size_t n_surfaces = levels.size();
  for (const JumpEdge& j : edges) {
    bool seen = false;
    for (size_t k = 0; k < n_surfaces && !seen; ++k) {
      seen = std::abs(levels[k].z - j.z) < same_level && levels[k].s_max > j.s - ahead &&
             levels[k].s_min < j.s + behind;
      // The farthest edge that ends it (a tread holds one nosing).
      if (seen && (!levels[k].far_edge || j.nosing_s > levels[k].edge_s)) levels[k].edge_s = j.nosing_s;
      levels[k].far_edge = levels[k].far_edge || seen;
      // A riser's top shows its step's width only as far as the riser was
      // segmented; the nosing's jump shows the rest.
      if (seen && levels[k].plane < 0) {
        levels[k].t_min = std::min(levels[k].t_min, j.t_min);
        levels[k].t_max = std::max(levels[k].t_max, j.t_max);
      }
    }
    if (!seen) levels.push_back({-1, j.z, j.s, j.s, j.t_min, j.t_max, true, j.nosing_s});
  }
  for (Level& l : levels) {
    if (l.plane < 0) continue;
    const PlaneExtent& e = ps.extents[static_cast<size_t>(l.plane)];
    l.reach_below_m = std::max(0.0f, l.z - e.z_min);
    l.reach_above_m = std::max(0.0f, e.z_max - l.z);
  }
  std::sort(levels.begin(), levels.end(), [](const Level& a, const Level& b) { return a.z < b.z; });
  return levels;
}


std::vector<Step> steps_from_chain(const PlaneSet& ps, const StairChain& chain, const StairConfig& cfg) {
  std::vector<Step> steps;
  const auto& L = chain.levels;
  const bool up = chain.direction == Direction::Up;
  // Up: step k is the riser below level k and level k's tread (k >= 1).
  // Down: step k is level k's tread and the riser below it (k < n - 1).
  const size_t first = up ? 1 : 0, last = up ? L.size() : L.size() - 1;
  std::vector<float> nosing_s;                  // along the stair, per step
  std::vector<std::optional<float>> band_mid;  // going up: the middle of the band the face lies in
  for (size_t k = first; k < last && L.size() >= 2; ++k) {
    const Level& tread = L[k];
    const Level& below = up ? L[k - 1] : L[k + 1];
    Step s;
    s.tread_plane = tread.plane;
    s.riser_height_m = tread.z - below.z;
    // A riser's top is no measured level: under a nosing overhang it is the
    // slab's underside, a slab's thickness below the tread (an independent
    // simulator's steep flight with 3 cm nosings lost 1.7 cm of rise this way).
    // The rise is then a prior, flagged: the tracker takes it from the fused
    // nosing heights, and verification's regularity does not judge it.
    if (tread.riser_top || below.riser_top) s.inferred |= kStepRiserInferred;
    // Going down the nosing is the depth jump at the tread's far end where one
    // shows it: the plane's trimmed extent stops short of the edge's cells.
    float at = up ? tread.s_min : tread.far_edge ? tread.edge_s : tread.s_max;
    // Going up, the riser's face lies by where the level below stops and this
    // tread starts: neither level reaches into the step (within riser_contact_m
    // of noise), and each loses its cells at the corner (to noise, or to a riser
    // fitted tilted that takes them). The face is searched for there too. Both
    // are seen planes: a level seen only as its front edge (a nosing's depth
    // jump) starts at the nosing itself, and its "band" put the face half a band
    // off (that offset, carried to an unseen face, made a Kinect v2's first tread 18 cm for 24).
    const float below_end = end_under(below, tread, cfg.max_level_gap_m);
    const bool band = up && below.plane >= 0 && tread.plane >= 0 && !below.riser_top && !tread.riser_top &&
                      below_end < tread.s_min + cfg.riser_contact_m;
    // The riser whose face lies at the nosing line, spanning the rise; of
    // several, the one reaching lowest: a riser stands on the level below, and
    // under a nosing overhang the slab's front face, a few cm tall at the
    // tread's level and 2-4 cm nearer, is a plane of its own (taking it put
    // that step's nosing at the slab and the next one's at a riser's face: a
    // hand-held Kinect v1 ascent's treads 0.20-0.25 m for 0.222).
    s.riser_plane = find_riser(
        ps, std::min(at - cfg.riser_at_nosing_m, band ? below_end : at), at + cfg.riser_at_nosing_m,
        cfg.riser_min_width_m, [&](const PlaneExtent& e) { return e.z_max >= below.z && e.z_min <= tread.z; },
        [](const PlaneExtent& a, const PlaneExtent& b) { return a.z_min < b.z_min; });
    // The riser's face is the better estimate: the tread's edge cells are lost at the corner.
    if (s.riser_plane >= 0) at = ps.extents[s.riser_plane].s_mean;
    nosing_s.push_back(at);
    band_mid.push_back(band ? std::optional<float>(0.5f * (below_end + tread.s_min)) : std::nullopt);
    s.tread_depth_m = tread.s_max - tread.s_min;
    s.width_m = tread.t_max - tread.t_min;
    steps.push_back(s);
  }
  // A step whose face no riser shows has it where the faces that are shown stand from their bands'
  // middles: about there where no overhang hides the level below (the tread's front alone lay 5-10 cm
  // behind the face at 2.5-3.6 m: a D435's and a Kinect v2's far treads measured 30-39 cm for 25-29),
  // an overhang's depth behind it where the slab hides the level below to its front (the slab's front
  // on some steps and the faces on others made a Kinect v2's treads 26-30 cm for 28).
  std::vector<float> offsets;
  for (size_t i = 0; i < steps.size(); ++i)
    if (steps[i].riser_plane >= 0 && band_mid[i]) offsets.push_back(nosing_s[i] - *band_mid[i]);
  const float offset = offsets.empty() ? 0.0f : median(offsets);
  for (size_t i = 0; i < steps.size(); ++i) {
    if (steps[i].riser_plane < 0 && band_mid[i]) nosing_s[i] = *band_mid[i] + offset;
    const Level& tread = L[first + i];
    steps[i].nosing_m = ps.to_camera(nosing_s[i], 0.5f * (tread.t_min + tread.t_max), tread.z).cast<double>();
  }
  return steps;
}

}  // namespace stairs
