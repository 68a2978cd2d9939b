// The Kinect v1 effects of SensorModel, each on a depth buffer in metres
// (0 = no measurement), row-major at the renderer's intrinsics.
#pragma once

#include "drivers/sim/raster.hpp"
#include "drivers/sim/rng.hpp"

#include <string>
#include <vector>

namespace stairs::sim {

// Which sensor the effects imitate (sensor_preset): Kinect v1 structured
// light (disparity noise, projector shadow), Kinect v2 time of flight (flying
// pixels at depth edges, multipath in concave corners, metric noise), or a
// RealSense D4xx active stereo pair (noise growing with z^2, holes at edges).
enum class SensorKind { KinectV1, KinectV2, StereoD4xx };

// Depth sensor effects. Defaults are Kinect v1's (the figures).
struct SensorModel {
  SensorKind kind = SensorKind::KinectV1;
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

  bool lateral_noise = true;         // edge effects: v1 edges wander across pixels, v2 flying pixels, D4xx holes
  double lateral_sigma_px = 0.6;     // at 640x480; scaled with the resolution
  double edge_jump_ratio = 0.03;     // a neighbour differing by more than this fraction of z is an edge

  bool grazing_dropout = true;  // no return at grazing incidence
  double grazing_start_deg = 70.0;  // dropout probability rises linearly from 0 here
  double grazing_full_deg = 88.0;   // ... to 1 here

  // Kinect v2 (time of flight)
  double tof_sigma_a_m = 0.0015;      // sigma(z) = a + b z, metric (no disparity)
  double tof_sigma_b = 0.0012;        // per m
  double flying_fraction = 0.5;       // of the edge pixels, read between the two surfaces (lateral_noise)
  bool multipath = true;              // light bounced in a concave corner lengthens the path
  double multipath_bias_m = 0.015;    // added range at the corner itself
  double multipath_range_m = 0.08;    // falling linearly to 0 this far from the corner

  // RealSense D4xx (active stereo): disparity noise of stereo_sigma_px, shadow of the second imager
  double stereo_baseline_m = 0.05;    // second imager to the right
  double stereo_focal_px = 383.0;     // at 640 px wide
  double stereo_sigma_px = 0.08;      // subpixel matching noise: sigma(z) = z^2 sigma / (f B)
  double edge_hole_fraction = 0.5;    // of the pixels at a depth edge, no match

  // Any sensor: surfaces that absorb the IR (Scene::dark_treads)
  double dark_dropout = 0.5;          // probability a pixel on a dark surface reads nothing

  // Any sensor: a smooth depth warp, as calibrations of real cameras show (Kinect v1/v2 depth distortion,
  // a RealSense's "bowl"): depth times 1 + warp (rho^2 - 1/2), rho = distance from the principal point
  // over the half-diagonal. Real planes are not flat in a real camera's depth (a real Kinect v2 floor
  // 0.7 cm rms at 0.9 m, a RealSense floor 0.3-0.4 cm at 0.7-0.9 m; the simulator's 0.1 cm) and their
  // cells' median normal turns 2-4 deg from their fitted one. Off (0) unless asked for.
  double depth_warp = 0.0;           // fraction of the depth (e.g. 0.01)

  bool holes = true;                 // small random holes
  double holes_per_megapixel = 400.0;  // hole centres per 10^6 pixels per frame
  double hole_radius_px = 1.5;         // at 640x480; scaled with the resolution
};

// Everything off but the range limits.
SensorModel perfect_sensor();

// kinect1 (the default), kinect2 (512x424 ToF), d435 (640x480 stereo); throws
// std::invalid_argument naming the sensor.
SensorModel sensor_preset(const std::string& name);
std::string sensor_name(SensorKind kind);
// The sensor's native depth intrinsics scaled to width x height (0 x 0 = native).
Intrinsics sensor_intrinsics(SensorKind kind, int width = 0, int height = 0);

// Kinect v2: edge pixels (depth differs by more than edge_jump_ratio from a
// neighbour) take, with flying_fraction, a depth between their neighbourhood's
// nearest and farthest.
void apply_flying_pixels(const SensorModel& m, Rng& rng, int width, int height, std::vector<float>& depth_m,
                         std::vector<float>& scratch_m);

// Kinect v2: a pixel within multipath_range_m of a face that stands in front
// of its own (a concave corner) reads farther, by up to multipath_bias_m.
void apply_multipath(const SensorModel& m, const Intrinsics& K, const Geometry& g, const Eigen::Isometry3d& camera_in_stair,
                     const ZBuffer& zb, std::vector<float>& depth_m);

// Kinect v2: metric noise sigma(z) = tof_sigma_a_m + tof_sigma_b z.
void apply_tof_noise(const SensorModel& m, Rng& rng, std::vector<float>& depth_m);

// D4xx: disparity noise of stereo_sigma_px (scaled with the width), and no
// match at edge_hole_fraction of the edge pixels.
void apply_stereo_noise(const SensorModel& m, double focal_px, Rng& rng, std::vector<float>& depth_m);
void apply_edge_holes(const SensorModel& m, Rng& rng, int width, int height, std::vector<float>& depth_m);

// Pixels on dark faces (`dark[id]`) read nothing with probability dark_dropout.
void apply_dark_dropout(const SensorModel& m, const std::vector<uint8_t>& dark, const ZBuffer& zb, Rng& rng,
                        std::vector<float>& depth_m);


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

// The smooth depth warp (depth_warp), every sensor.
void apply_depth_warp(const SensorModel& m, const Intrinsics& K, std::vector<float>& depth_m);

// Random small round holes.
void apply_holes(const SensorModel& m, double radius_scale, Rng& rng, int width, int height,
                 std::vector<float>& depth_m);

}  // namespace stairs::sim
