#include "perception/bridged_surfaces.hpp"

#include "common/median.hpp"

#include <algorithm>
#include <cmath>

namespace stairs {

void fit_away_from_bridged_surfaces(const NormalGrid& g, const BridgedSurfacesConfig& cfg,
                                    std::vector<Segment>& segments, BridgedSurfacesScratch& scratch) {
  const float cos_min = std::cos(cfg.min_angle_deg * static_cast<float>(M_PI) / 180.0f);
  // 1.4826 * median absolute deviation: the standard deviation of normal scatter.
  constexpr float kMadToSigma = 1.4826f;
  constexpr size_t kMedianSamples = 255;
  std::vector<float>& v = scratch.values;
  std::vector<float>& r = scratch.offsets;
  for (Segment& s : segments) {
    if (s.cells.size() < 3) continue;
    // The median normal, component by component: the bridging cells are the few. Of at most
    // kMedianSamples cells spread over the segment (a median of 3 x 19200 cells per frame cost 0.55 ms,
    // a third of the pipeline; a sample's median is within a fraction of a degree of it).
    const size_t stride = (s.cells.size() + kMedianSamples - 1) / kMedianSamples;
    Eigen::Vector3f m;
    for (int k = 0; k < 3; ++k) {
      v.clear();
      for (size_t i = 0; i < s.cells.size(); i += stride) v.push_back(g.normals[s.cells[i]][k]);
      m[k] = median_in_place(v);
    }
    if (m.squaredNorm() < 0.25f) continue;  // the cells' normals disagree: no surface stands out
    m.normalize();
    if (std::abs(m.dot(s.normal)) >= cos_min) continue;
    r.clear();
    for (int c : s.cells) r.push_back(m.dot(g.points[c]));
    v = r;
    const float offset = median_in_place(v);
    for (float& x : v) x = std::abs(x - offset);
    const float cut = std::max(cfg.cut_sigmas * kMadToSigma * median_in_place(v), cfg.min_cut_m);
    // A strip no wider across than a few times its scatter is a line: any plane through it fits,
    // the least-squares one and a refit alike (a tread's edge seen edge-on, turned 40 deg by a refit,
    // became a level with no depth and cost the frame its staircase).
    if (std::sqrt(std::min(s.spread_m2[0], s.spread_m2[1])) < cfg.min_across_cuts * cut) continue;
    PlaneSums on;
    size_t in_front = 0, behind = 0;  // off the median plane, towards the camera or away
    for (size_t i = 0; i < s.cells.size(); ++i) {
      const float d = r[i] - offset;
      if (std::abs(d) <= cut) on.add(g.points[s.cells[i]]);
      else ++(d > 0 ? in_front : behind);
    }
    if (on.n == s.sums.n || 2 * on.n <= s.sums.n) continue;  // the median's surface is most of the segment
    // A bridged surface stands in front of the plane (a nosing slab's front before its riser). Cells
    // mostly behind it may be its own depth lengthened (a time-of-flight camera's multipath, a polished
    // floor's reflections: a real Kinect v2's floor had 949 cells 3-10 cm "below" it, and the rest
    // turned 1.7 deg from the treads beside it); they do not show another surface.
    if (in_front <= behind) continue;
    // A surface's own scatter trimmed at a few sigmas leaves its rms as it was (noisy far planes:
    // 1.0-1.4 times flatter); a bridged surface off the plane leaves the rest flatter by its offset
    // (risers merged with their nosing slab: 3-13 times).
    Segment surface;
    fit_plane(on, surface);
    if (surface.rms_m * cfg.min_flatter > s.rms_m) continue;
    s.centroid = surface.centroid;
    s.normal = surface.normal;
    s.rms_m = surface.rms_m;
    for (int k = 0; k < 2; ++k) s.axis[k] = surface.axis[k], s.spread_m2[k] = surface.spread_m2[k];
    // Cells within same_face_m of the plane stay: a nosing slab's front is part of the step's face,
    // and its top is the tread's. Farther ones are another surface (another step's face), and would
    // stretch the plane's extent over it.
    size_t kept = 0;
    PlaneSums away;
    for (size_t i = 0; i < s.cells.size(); ++i) {
      if (std::abs(r[i] - offset) <= cfg.same_face_m)
        s.cells[kept++] = s.cells[i];
      else
        away.add(g.points[s.cells[i]]);
    }
    s.cells.resize(kept);
    s.sums = s.sums - away;
  }
}

}  // namespace stairs
