#include "perception/concave_corners.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace stairs {

namespace {

using Box = ConcaveCornersScratch::Box;

// Signed distances of the box's corners to the plane (n, c): [min, max].
std::pair<float, float> distance_range(const Box& b, const Eigen::Vector3f& n, const Eigen::Vector3f& c) {
  float lo = 0.0f, hi = 0.0f;
  for (int k = 0; k < 3; ++k) {
    const float a = n[k] * (b.lo[k] - c[k]), z = n[k] * (b.hi[k] - c[k]);
    lo += std::min(a, z);
    hi += std::max(a, z);
  }
  return {lo, hi};
}

Box box_of(const NormalGrid& g, const Segment& s) {
  Box b{g.points[s.cells[0]], g.points[s.cells[0]]};
  for (int c : s.cells) b.lo = b.lo.cwiseMin(g.points[c]), b.hi = b.hi.cwiseMax(g.points[c]);
  return b;
}

}  // namespace

void fit_away_from_concave_corners(const NormalGrid& g, const ConcaveCornersConfig& cfg, std::vector<Segment>& segments,
                                   ConcaveCornersScratch& scratch) {
  if (cfg.band_m <= 0.0f || segments.size() < 2) return;
  const float d = cfg.band_m, cos_corner = std::cos(cfg.min_corner_angle_deg * static_cast<float>(M_PI) / 180.0f);
  std::vector<Box>& boxes = scratch.boxes;
  boxes.clear();
  for (const Segment& s : segments) boxes.push_back(box_of(g, s));
  std::vector<Eigen::Vector4f>& partners = scratch.partners;
  // Decided on the planes as grown, applied after: a refit does not move another's band.
  std::vector<std::pair<size_t, Segment>>& refits = scratch.refits;
  refits.clear();
  // Whether each segment's band showed multipath; and the segments lying mostly inside one
  // partner's band, whose own cells cannot show a bend (nothing outside the band to fit).
  scratch.shows_bend.assign(segments.size(), 0);
  scratch.inside_band_of.clear();
  for (size_t a = 0; a < segments.size(); ++a) {
    Segment& sa = segments[a];
    partners.clear();
    scratch.partner_of.clear();
    for (size_t b = 0; b < segments.size(); ++b) {
      const Segment& sb = segments[b];
      if (a == b || std::abs(sa.normal.dot(sb.normal)) > cos_corner) continue;
      // Concave: each plane's centroid on the other's camera side.
      if (sb.normal.dot(sa.centroid - sb.centroid) <= 0.0f || sa.normal.dot(sb.centroid - sa.centroid) <= 0.0f)
        continue;
      // They meet: each reaches into the band along the other's plane (a riser
      // five steps up is in front of this tread too, but far from it).
      const auto [alo, ahi] = distance_range(boxes[a], sb.normal, sb.centroid);
      const auto [blo, bhi] = distance_range(boxes[b], sa.normal, sa.centroid);
      if (alo > d || ahi < -d || blo > d || bhi < -d) continue;
      partners.emplace_back(sb.normal.x(), sb.normal.y(), sb.normal.z(), -sb.normal.dot(sb.centroid));
      scratch.partner_of.push_back(b);
    }
    if (partners.empty()) continue;
    // The band: the cells within d of a partner's plane (the corner's line
    // lies in it). Contiguous coordinates, one branch-free pass per partner.
    const size_t n = sa.cells.size();
    scratch.x.resize(n), scratch.y.resize(n), scratch.z.resize(n);
    scratch.in_band.assign(n, 0);
    float* x = scratch.x.data();
    float* y = scratch.y.data();
    float* z = scratch.z.data();
    uint8_t* in = scratch.in_band.data();
    for (size_t k = 0; k < n; ++k) {
      const Eigen::Vector3f& p = g.points[sa.cells[k]];
      x[k] = p.x(), y[k] = p.y(), z[k] = p.z();
    }
    for (size_t i = 0; i < partners.size(); ++i) {
      const Eigen::Vector4f& q = partners[i];
      const float qx = q.x(), qy = q.y(), qz = q.z(), qw = q.w();
      size_t near = 0;
      for (size_t k = 0; k < n; ++k) {
        const bool b = std::abs(qx * x[k] + qy * y[k] + qz * z[k] + qw) < d;
        in[k] |= static_cast<uint8_t>(b);
        near += b;
      }
      if (near > (1.0f - cfg.min_core_fraction) * n) scratch.inside_band_of.emplace_back(a, scratch.partner_of[i]);
    }
    PlaneSums band;
    for (size_t k = 0; k < n; ++k)
      if (in[k]) band.add(Eigen::Vector3f(x[k], y[k], z[k]));
    if (band.n == 0) continue;
    const double left = sa.sums.n - band.n;
    if (left < 3) continue;  // nothing to tell a bend by
    // Multipath only lengthens paths: the band bends the plane where it lies
    // behind the plane of the other cells by more than their scatter (not its
    // standard error: neighbouring cells share their errors, structured
    // light's quantisation steps and smoothing), and the plane without it is
    // the flatter (cells straddling a clean corner or nosing can tilt a small
    // core's fit past the band instead).
    Segment core;
    fit_plane(sa.sums - band, core);
    const Eigen::Vector3d band_mean = band.sum / band.n;
    const double behind = -core.normal.cast<double>().dot(band_mean - core.centroid.cast<double>());
    const double noise = cfg.behind_rms * core.rms_m;
    // min_behind_m is a depth, and depth errors lie along the ray (multipath lengthens the path):
    // a tread seen 13 deg edge-on shows a band 6 mm behind along the ray as 1.3 mm along its normal.
    constexpr double kMinCosIncidence = 0.05;  // 87 deg: no surface is seen flatter
    const double cos_incidence =
        std::max(kMinCosIncidence, std::abs(core.normal.cast<double>().dot(band_mean.normalized())));
    if (core.rms_m >= sa.rms_m || behind < noise || behind / cos_incidence < cfg.min_behind_m) continue;
    // Bent, and too little of it outside the bands to stand for its plane.
    scratch.shows_bend[a] = 1;
    if (left < cfg.min_core_fraction * sa.sums.n) {
      sa.bent = true;
      continue;
    }
    refits.emplace_back(a, core);
  }
  // A plane lying along one corner, inside its band (a robot looking up a flight sees the last
  // centimetres of the tread ahead, edge-on, before the next riser), is bent where the corner shows
  // multipath on its other face: its tilt across the corner is the bias's (2 deg), not the tread's.
  // A corner without multipath (structured light, stereo) leaves it its fit.
  for (const auto& [a, b] : scratch.inside_band_of)
    if (scratch.shows_bend[b]) segments[a].bent = true;
  for (const auto& [a, core] : refits) {
    Segment& sa = segments[a];
    sa.centroid = core.centroid;
    sa.normal = core.normal;
    sa.rms_m = core.rms_m;
    for (int k = 0; k < 2; ++k) sa.axis[k] = core.axis[k], sa.spread_m2[k] = core.spread_m2[k];
  }
}

}  // namespace stairs
