// Stage 2c: plane fits away from surfaces the region growing bridged. Under a
// nosing overhang the slab's front face stands a few centimetres in front of the
// riser, parallel to it, and the cells across the slab's underside carry normals
// close enough to both that one segment grows over riser and slab front: its
// least-squares plane tilts (a Kinect v1 robot looking up a flight saw risers
// tilted 5-10 deg, and up, their cross product with a wall, 6-10 deg off).
// Each cell's own normal still points the surface's way, so their median gives
// the plane most of the segment lies on.
#pragma once

#include "perception/config.hpp"
#include "perception/region_growing.hpp"

#include <vector>

namespace stairs {

struct BridgedSurfacesScratch {  // reused across frames
  std::vector<float> values, offsets;
};

// For each segment whose cells' median normal turns more than cfg.min_angle_deg
// from its least-squares normal (and that is wider across than cfg.min_across_cuts
// cuts: a line has no plane): the cells within cfg.cut_sigmas robust sigmas (at
// least cfg.min_cut_m) of the median plane are its surface; where most cells off
// it lie in front of it (towards the camera: cells behind may be the plane's own
// depth lengthened by multipath) and the plane
// fitted to them is at least cfg.min_flatter times flatter (rms) than the whole,
// it replaces the segment's plane (centroid, normal, rms, axes, spread), and the
// cells farther than cfg.same_face_m from it leave the segment (cells and sums).
// Those nearer stay: a nosing slab's front is part of the step's face, and its top
// is the tread's. One pass over the cells of each segment that turns.
void fit_away_from_bridged_surfaces(const NormalGrid& grid, const BridgedSurfacesConfig& cfg,
                                    std::vector<Segment>& segments, BridgedSurfacesScratch& scratch);

}  // namespace stairs
