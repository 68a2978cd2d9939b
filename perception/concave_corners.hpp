// Stage 2b: plane fits away from concave corners. A time-of-flight sensor
// (Kinect v2) adds to the path of a pixel near a concave corner the light that
// the corner's other face bounced onto it (multipath): a band of each plane
// along the junction lies behind the plane and bends its least-squares fit.
// Every stair has such junctions (each riser on the tread below it, treads and
// risers against the walls), and a bent tread tilts gravity (thesis 3.5 takes
// up from the treads' normals) and every height measured along it.
#pragma once

#include "perception/config.hpp"
#include "perception/region_growing.hpp"

#include <cstdint>
#include <utility>
#include <vector>

namespace stairs {

// For each segment that meets another at a concave corner (both planes in
// front of each other, meeting within cfg.band_m of each other's plane): its
// cells within cfg.band_m of the other plane form the band. Where the band lies
// behind the plane fitted to the remaining cells by more than their scatter,
// and that plane is the flatter, it replaces the segment's plane (a
// structured-light or stereo plane keeps its fit); such a segment with too few
// cells outside its bands is marked `bent` instead, as is a segment lying mostly
// inside one partner's band where that partner's band showed the bend (the
// corner has multipath; the segment's own cells cannot tell).
// Segments keep their cells and sums. One pass over each cornered segment's
// cells; the plane without the band is the sums' difference.
struct ConcaveCornersScratch {  // reused across frames
  struct Box {
    Eigen::Vector3f lo, hi;  // m, optical frame
  };
  std::vector<Box> boxes;                      // per segment
  std::vector<Eigen::Vector4f> partners;  // planes as (normal, offset): n.p + w is the distance
  std::vector<size_t> partner_of;              // the segment of each partner
  std::vector<uint8_t> shows_bend;             // per segment: its band lay behind its plane
  std::vector<std::pair<size_t, size_t>> inside_band_of;  // (segment, partner): mostly in that band
  std::vector<std::pair<size_t, Segment>> refits;
  std::vector<float> x, y, z;    // one segment's cells, contiguous
  std::vector<uint8_t> in_band;  // per cell of that segment
};
void fit_away_from_concave_corners(const NormalGrid& grid, const ConcaveCornersConfig& cfg,
                                   std::vector<Segment>& segments, ConcaveCornersScratch& scratch);

}  // namespace stairs
