// The Kinect v1 effects of SensorModel, each on a depth buffer in metres
// (0 = no measurement), row-major at the renderer's intrinsics.
#pragma once

#include "drivers/sim/raster.hpp"
#include "drivers/sim/rng.hpp"

#include <vector>

namespace stairs::sim {

// Kinect v1 structured-light depth. Defaults are the figures.
struct SensorModel {
  bool perfect = false;  // noiseless depth: every effect below off except the range limits

  double min_range_m = 0.5;  // z outside [min, max] reads 0
  double max_range_m = 4.5;

  bool shadow = true;                 // IR projector shadow beside depth edges
  double projector_offset_m = 0.075;  // projector along the camera's +x (right in the image)
  double shadow_tolerance_m = 0.02;   // + 1% of the depth: occluder must be this much closer

  bool axial_noise = true;  // sigma(z) = a + b (z - c)^2 (Nguyen et al. 2012), applied in disparity
  double sigma_a_m = 0.0012;
  double sigma_b_per_m = 0.0019;
  double sigma_c_m = 0.4;

  bool quantisation = true;      // disparity quantised to 1/8 px
  double baseline_m = 0.075;     // disparity = focal_px * baseline / z
  double focal_px = 580.0;       // of the IR camera, for disparity (independent of the output resolution)
  double subpixel = 8.0;         // disparity steps per pixel

  bool lateral_noise = true;         // depth edges wander across pixels
  double lateral_sigma_px = 0.6;     // at 640x480; scaled with the resolution
  double edge_jump_ratio = 0.03;     // a neighbour differing by more than this fraction of z is an edge

  bool grazing_dropout = true;  // no return at grazing incidence
  double grazing_start_deg = 70.0;  // dropout probability rises linearly from 0 here
  double grazing_full_deg = 88.0;   // ... to 1 here

  bool holes = true;                 // small random holes
  double holes_per_megapixel = 400.0;  // hole centres per 10^6 pixels per frame
  double hole_radius_px = 1.5;         // at 640x480; scaled with the resolution
};

// Everything off but the range limits.
SensorModel perfect_sensor();


// Zeroes pixels whose surface point the projector (offset along the camera's
// +x) does not see: camera_zb is the scene rendered by the camera (K),
// projector_zb from the projector (P).
void apply_projector_shadow(const SensorModel& m, const Intrinsics& K, const Intrinsics& P, const ZBuffer& camera_zb,
                            const ZBuffer& projector_zb, std::vector<float>& depth_m);

// Zeroes pixels seen at grazing incidence with a probability rising from
// grazing_start_deg to grazing_full_deg; normals from the primitives hit.
void apply_grazing_dropout(const SensorModel& m, const Intrinsics& K, const Geometry& g,
                           const Eigen::Isometry3d& camera_in_stair, const ZBuffer& zb, Rng& rng,
                           std::vector<float>& depth_m);

// Pixels at a depth edge take the depth of a pixel displaced by a rounded
// Gaussian offset, so edges wander.
void apply_lateral_noise(const SensorModel& m, double sigma_px, Rng& rng, int width, int height,
                         std::vector<float>& depth_m, std::vector<float>& scratch_m);

// Axial noise and 1/subpixel quantisation in disparity.
void apply_axial_noise(const SensorModel& m, bool noise, bool quantise, Rng& rng, std::vector<float>& depth_m);

// Random small round holes.
void apply_holes(const SensorModel& m, double radius_scale, Rng& rng, int width, int height,
                 std::vector<float>& depth_m);

}  // namespace stairs::sim
