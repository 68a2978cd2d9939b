// Every parameter of the perception pipeline, with its unit and default.
// Pixel counts are given for 640x480 and scaled with the frame's resolution.
#pragma once

#include <string>

namespace stairs {

// --- verification (perception/verification.hpp): the evidence a real flight leaves
struct VerificationConfig {
  // Each check can be switched off (the ablation in BENCHMARKS.md).
  bool riser_support = true;  // a solid riser under each nosing, no view through beneath it
  bool foot_support = true;   // the level below reaches the riser's foot (the step stands on it)
  bool widths = true;         // each tread spans its width; treads share one width and overlap laterally
  bool alignment = true;      // the segmented risers (nosings) are parallel in plan view
  bool regularity = true;     // measured rises and runs agree within a tolerance

  int lateral_samples = 8;            // samples across a step's width per probed surface
  int vertical_samples = 4;           // samples up a riser
  float lateral_margin = 0.15f;       // of the width left out at each side (walls, stringers)
  float vertical_margin = 0.25f;      // of the rise left out at top and bottom (nosing overhang, flying pixels)
  float max_nosing_overhang_m = 0.05f;  // m; a riser may stand this far behind its nosing (DIN: 2-5 cm)
  float min_probe_elevation_deg = 10.0f;  // deg; a level seen flatter than this decides no probe on it
  float probe_offset_m = 0.06f;       // m; probes of a level lie this far from the edge they test
  float probe_depth_m = 0.2f;         // m; probes reach this far into a tread (at most its measured depth)
  float solid_tolerance_m = 0.03f;    // m; depth within this (+ the next term) of the probe = a surface there
  float solid_tolerance_per_m2 = 0.005f;  // m per m^2 of depth: sensor noise grows with z^2 (3 sigma of a
                                          // Kinect v1 cell mean at 4 m)
  float max_see_through = 0.3f;       // of the decided probes: more seen beyond the surface refutes it
  int min_decided_probes = 6;         // fewer decided probes (occluded, no depth, off image) = no verdict
  float border_margin_px = 8.0f;      // px at 640x480; a tread end this close to the image border is cut
  float end_offset_m = 0.05f;         // m; a tread's end is open when the view passes on this far beyond it
  float min_width_ratio = 0.6f;       // narrower / wider tread width when the narrower one is uncut
  float min_lateral_overlap = 0.5f;   // of the narrower tread's width, consecutive treads overlap
  float max_riser_yaw_spread_deg = 8.0f;  // deg; segmented risers of one flight are this parallel
  float rise_tolerance_m = 0.05f;     // m; a measured rise this far from the median is irregular (old
                                      // flights' construction tolerance plus noise at range)
  float run_tolerance_m = 0.07f;      // m; a measured run this far from the median is irregular
  float rise_outlier_m = 0.08f;       // m; one rise may deviate this much when enough others agree
  float run_outlier_m = 0.12f;        // m; likewise one run
  int regular_steps_for_an_outlier = 3;  // measured rises (runs) within tolerance that allow one outlier
  float min_run_m = 0.138f;           // m; a shorter measured run is no tread (DIN's 0.23 m less its tolerance)
};

// --- imu (perception/imu_gravity.hpp): gravity from an optional IMU (issue 15)
struct ImuConfig {
  // IMU frame -> camera optical frame, applied to the live channel and logged
  // STAIRS_IMU (a sequence's imu.txt is already in the camera frame):
  // R = Rz(yaw) Ry(pitch) Rx(roll).
  float to_camera_roll_deg = 0.0f;
  float to_camera_pitch_deg = 0.0f;
  float to_camera_yaw_deg = 0.0f;
  float time_constant_s = 1.0f;      // s; accelerometer correction of the gyro-propagated up: walking
                                     // accelerations (~2 Hz) average out, gyro bias cannot build up
  float max_force_deviation = 0.2f;  // of g; no start from a force this far off 1 g, and no correction from
                                     // one twice this far from the filtered gravity (a jolt, a bump)
  float max_age_s = 0.1f;            // s; IMU data this much older than a frame is stale: planes only
  float warmup_s = 0.5f;             // s; of samples before the filter's up is used (it starts on one sample)
  float plane_agreement_deg = 2.0f;  // deg; planes' up within this of the IMU's is kept: level floors and
                                     // treads measure it better than a walking IMU
  float max_disagreement_deg = 10.0f;  // deg; an IMU farther than this from the planes is rejected (a
                                       // wrong mount rotation, a broken IMU): no ramp people walk is steeper
};

struct PerceptionConfig {
  // --- normals: organized grid of cell means, normals by neighbour cross products
  int grid_cell_px = 4;            // px at 640 wide; cell side (scaled, >= 1)
  int normal_radius_cells = 2;     // cells; half baseline of the cross product
  float max_depth_m = 5.0f;        // m; farther measurements are ignored
  float min_depth_m = 0.3f;        // m
  float jump_ratio = 0.05f;        // |dz| / z above which two cells are not neighbours (and
                                   // pixels of one cell not on its nearest surface)
  float cell_min_valid_fraction = 0.5f;  // of a cell's pixels on its nearest surface, else no point
  float cell_valid_fraction_range_m = 1.5f;  // m; beyond, that fraction falls as 1/depth (dropout)
  float inverse_depth_kink_per_m = 0.008f;  // 1/m; |1/z_l + 1/z_r - 2/z_c| above this = a corner or
                                             // jump between (1/z is affine in the image on a plane)
  bool smooth_normals = true;      // 3x3 mean of the normals

  // --- region_growing: "last normal" model (over-segments, never under-segments)
  float grow_angle_deg = 15.0f;      // max angle between neighbouring normals
  float grow_region_angle_deg = 20.0f;  // max angle to the region's mean normal (no leak round corners)
  float grow_distance_m = 0.01f;     // max point-to-plane distance to the last cell at 1 m (x z^2)
  float grow_max_distance_m = 0.03f;  // cap of that distance: a riser seen from above never joins
  int min_plane_px_320 = 100;        // px at 320x240; smaller planes are dropped (scaled)

  // --- gravity (Algorithm 4, weighted horizontal normals)
  float max_tilt_from_image_up_deg = 80.0f;  // horizontal-plane candidates vs. image up
  float parallel_deg = 4.0f;                 // normals this close count as parallel
  float gravity_prior_max_deg = 20.0f;        // up may turn this much from the previous frame's
  double gravity_prior_max_gap_s = 1.0;       // s; after a longer gap the previous up is forgotten
  float gravity_min_support_fraction = 0.1f;  // with a prior: treads with less support than this
                                              // fraction of the largest vertical family yield to it
  float beneath_view_edge_margin_m = 0.1f;   // m; a surface whose near edge is this close to where
  float beneath_view_edge_tolerance = 0.15f;  // (+ this fraction) the image's bottom row meets its
                                              // height runs on beneath the camera
  float beneath_same_level_m = 0.04f;         // m; a surface this close to the flight's first level is that level

  // --- edges_depth_jumps
  float edge_jump_min_m = 0.05f;        // m; depth step between vertical neighbours that is a jump
  float edge_jump_ratio = 0.03f;        // of the depth; the jump must exceed this too (noise grows)
  int edge_gap_cells = 2;               // cells without a measurement a jump may span (shadow)
  float edge_height_gap_m = 0.02f;      // m; jump points chain into one height group below this
  float edge_ransac_threshold_m = 0.02f;  // m; RANSAC line inlier distance
  int edge_ransac_iterations = 100;
  int edge_min_points = 8;              // jump points of a line
  int edge_max_lines_per_group = 3;     // lines fitted per height group
  float edge_max_tilt_deg = 10.0f;      // a step edge is horizontal within this
  float edge_max_axis_deg = 20.0f;      // and across the stair axis within this

  // --- edges_normal_image (thesis 3.4.1): gravity-aligned normals as colours, Canny, contours, Hough
  int normal_edge_blur_cells = 1;         // cells; Gaussian blur radius before Canny: the two edges of a
                                          // rounded nosing's band of in-between normals become one
  float normal_edge_canny_low = 100.0f;   // Canny hysteresis thresholds on the 3x3 Sobel L1 gradient
  float normal_edge_canny_high = 200.0f;  // of the 8-bit normal image (a sharp 90 deg bend gives ~500)
  float normal_edge_min_contour_px = 32.0f;  // px at 640x480; shorter edge curves (their span) are noise
  float normal_edge_hough_theta_deg = 1.0f;  // deg; Hough angle resolution (rho: one grid cell)
  float normal_edge_hough_votes_px = 32.0f;  // px at 640x480; edge pixels on a line for a Hough line
  float normal_edge_hough_min_length_px = 48.0f;  // px at 640x480; shorter Hough segments are dropped
  float normal_edge_hough_max_gap_px = 12.0f;     // px at 640x480; gaps bridged along a Hough segment
  int normal_edge_side_cells = 2;           // cells; strip on each side of a line giving its two surfaces
  float normal_edge_min_bend_deg = 30.0f;   // deg; the surfaces on the two sides turn by at least this
  float normal_edge_max_tilt_deg = 10.0f;   // deg; a step edge is horizontal within this
  float normal_edge_max_axis_deg = 20.0f;   // deg; and across the stair axis within this
  float normal_edge_max_range_m = 4.0f;     // m; farther edges are dropped (far normals are noisy)
  float normal_edge_merge_bin_m = 0.05f;    // m; merge histogram bin of horizontal distance and height
  float normal_edge_merge_bin_deg = 10.0f;  // deg; merge histogram bin of direction (step edges are all
                                            // parallel: position tells them apart, short pieces vary)

  // --- plane_geometry
  float horizontal_tol_deg = 12.0f;   // tread/landing: normal within this of up
  float vertical_tol_deg = 15.0f;     // riser: normal within this of horizontal
  float merge_bin_m = 0.05f;          // height/depth histogram bin
  float merge_gap_m = 0.15f;          // m; same-bin planes merge when this close in the plane
  float extent_percentile = 0.02f;    // fraction trimmed at each end of an extent

  // --- steps and grammar (DIN 18065 with tolerance)
  float riser_min_m = 0.14f;
  float riser_max_m = 0.20f;
  float tread_min_m = 0.23f;
  float tread_max_m = 0.37f;
  float step_rule_min_m = 0.59f;      // 2R + T lower bound
  float step_rule_max_m = 0.65f;      // 2R + T upper bound
  float din_tolerance = 0.4f;         // relative tolerance on every DIN bound
  float level_max_spread_of_rise = 0.5f;  // of the rise: a level's heights reach at most this far towards
                                          // the next (a tread is level within noise; a ramp is not)
  float landing_min_depth_m = 0.50f;  // a tread deeper than this is a landing
  float min_step_width_m = 0.3f;      // m; narrower horizontal planes (chair seats) are no treads
  float max_lateral_gap_m = 0.5f;     // m; consecutive treads must overlap laterally up to this gap
  float min_riser_seen_fraction = 0.1f;   // of the median rise: a riser standing on the last
                                          // tread, its top cut off by the view, still gives a step
  int min_steps = 2;                  // fewer detected steps = no staircase

  // --- verification: JSON object "verification" with the keys of VerificationConfig
  VerificationConfig verification;
  // --- imu: JSON object "imu" with the keys of ImuConfig
  ImuConfig imu;

  // --- observation
  int max_sample_points = 1024;  // per tread/riser, spatially even grid subsample
  int max_other_points = 64;     // per other plane
  int max_planes = 64;           // segmented planes reported (<= 192), treads/risers first
  int max_edges = 256;           // edges reported (<= 256), depth-jump edges first
};

// Reads a JSON object of parameters (any subset). Throws std::runtime_error
// naming the file and key on an unknown key, a wrong type or an unreadable file.
PerceptionConfig load_perception_config(const std::string& json_path);

}  // namespace stairs
