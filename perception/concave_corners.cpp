#include "perception/concave_corners.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace stairs {

namespace {

struct Box {
  Eigen::Vector3f lo, hi;
};

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

void fit_away_from_concave_corners(const NormalGrid& g, const ConcaveCornersConfig& cfg,
                                   std::vector<Segment>& segments, std::vector<uint8_t>& in_band) {
  if (cfg.band_m <= 0.0f || segments.size() < 2) return;
  in_band.assign(static_cast<size_t>(g.width) * g.height, 0);
  const float d = cfg.band_m, cos_corner = std::cos(cfg.min_corner_angle_deg * static_cast<float>(M_PI) / 180.0f);
  std::vector<Box> boxes;
  boxes.reserve(segments.size());
  for (const Segment& s : segments) boxes.push_back(box_of(g, s));
  Segment core;
  for (size_t a = 0; a < segments.size(); ++a) {
    Segment& sa = segments[a];
    int banded = 0;
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
      for (int c : sa.cells)
        if (!in_band[c] && std::abs(sb.normal.dot(g.points[c] - sb.centroid)) < d) in_band[c] = 1, ++banded;
    }
    if (banded == 0) continue;
    const size_t left = sa.cells.size() - static_cast<size_t>(banded);
    if (left < 3 || static_cast<float>(left) < cfg.min_core_fraction * static_cast<float>(sa.cells.size())) {
      sa.bent = true;
      continue;
    }
    // Multipath only lengthens paths: the band bends the plane where it lies
    // behind the plane of the other cells by more than the noise of its mean,
    // and the plane without it is the flatter (cells straddling a clean
    // corner or nosing can tilt a small core's fit past the band instead).
    core.cells.clear();
    for (int c : sa.cells)
      if (!in_band[c]) core.cells.push_back(c);
    fit_segment(g, core);
    double behind = 0.0;
    for (int c : sa.cells)
      if (in_band[c]) behind -= core.normal.dot(g.points[c] - core.centroid);
    behind /= banded;
    const double noise = cfg.behind_sigmas * core.rms_m / std::sqrt(static_cast<double>(banded));
    if (core.rms_m >= sa.rms_m || behind < std::max(static_cast<double>(cfg.min_behind_m), noise)) continue;
    std::swap(core.cells, sa.cells);
    sa = core;
    std::swap(core.cells, sa.cells);
  }
}

}  // namespace stairs
