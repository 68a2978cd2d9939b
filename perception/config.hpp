// Every parameter of the perception pipeline, with its unit and default.
// Pixel counts are given for 640x480 and scaled with the frame's resolution.
#pragma once

#include "common/config_file.hpp"
#include "common/limits.hpp"
#include "common/mount.hpp"
#include "common/stair_definition.hpp"

#include <nlohmann/json.hpp>

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
  int end_probes = 3;                 // probes beyond each end, evenly along the tread's run
  int end_probes_through = 2;         // of them that must see through: a majority, one noisy cell is no side
  float min_width_ratio = 0.6f;       // narrower / wider tread width when the narrower one is uncut
  float min_lateral_overlap = 0.5f;   // of the narrower tread's width, consecutive treads overlap
  float max_riser_yaw_spread_deg = 8.0f;  // deg; segmented risers of one flight are this parallel
  float rise_tolerance_m = 0.05f;     // m; a measured rise this far from the median (of two: from the
                                      // other) is irregular (old flights' construction tolerance plus noise
                                      // at range)
  float run_tolerance_m = 0.07f;      // m; a measured run this far from the median is irregular
  float rise_outlier_m = 0.08f;       // m; one rise may deviate this much when enough others agree
  float run_outlier_m = 0.12f;        // m; likewise one run
  int regular_steps_for_an_outlier = 3;  // measured rises (runs) within tolerance that allow one outlier
  float min_run_m = 0.138f;           // m; a shorter measured run is no tread (DIN's 0.23 m less its tolerance)

  template <class V>
  void visit(V& v) {
    v("riser_support", riser_support);
    v("foot_support", foot_support);
    v("widths", widths);
    v("alignment", alignment);
    v("regularity", regularity);
    v("lateral_samples", lateral_samples, 1, 64);
    v("vertical_samples", vertical_samples, 1, 64);
    v("lateral_margin", lateral_margin, 0.0f, 0.49f);
    v("vertical_margin", vertical_margin, 0.0f, 0.49f);
    v("max_nosing_overhang_m", max_nosing_overhang_m, 0.0f, 0.5f);
    v("min_probe_elevation_deg", min_probe_elevation_deg, 0.0f, 90.0f);
    v("probe_offset_m", probe_offset_m, 0.001f, 1.0f);
    v("probe_depth_m", probe_depth_m, 0.001f, 2.0f);
    v("solid_tolerance_m", solid_tolerance_m, 0.001f, 1.0f);
    v("solid_tolerance_per_m2", solid_tolerance_per_m2, 0.0f, 1.0f);
    v("max_see_through", max_see_through, 0.0f, 1.0f);
    v("min_decided_probes", min_decided_probes, 1, 4096);
    v("border_margin_px", border_margin_px, 0.0f, 320.0f);
    v("end_offset_m", end_offset_m, 0.0f, 1.0f);
    v("end_probes", end_probes, 1, 16);
    v("end_probes_through", end_probes_through, 1, 16);
    v("min_width_ratio", min_width_ratio, 0.0f, 1.0f);
    v("min_lateral_overlap", min_lateral_overlap, 0.0f, 1.0f);
    v("max_riser_yaw_spread_deg", max_riser_yaw_spread_deg, 0.01f, 90.0f);
    v("rise_tolerance_m", rise_tolerance_m, 0.001f, 1.0f);
    v("run_tolerance_m", run_tolerance_m, 0.001f, 1.0f);
    v("rise_outlier_m", rise_outlier_m, 0.001f, 1.0f);
    v("run_outlier_m", run_outlier_m, 0.001f, 1.0f);
    v("regular_steps_for_an_outlier", regular_steps_for_an_outlier, 2, 64);
    v("min_run_m", min_run_m, 0.0f, 2.0f);
  }
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

  template <class V>
  void visit(V& v) {
    v("to_camera_roll_deg", to_camera_roll_deg, -360.0f, 360.0f);
    v("to_camera_pitch_deg", to_camera_pitch_deg, -360.0f, 360.0f);
    v("to_camera_yaw_deg", to_camera_yaw_deg, -360.0f, 360.0f);
    v("time_constant_s", time_constant_s, 0.001f, 1000.0f);
    v("max_force_deviation", max_force_deviation, 0.001f, 0.999f);
    v("max_age_s", max_age_s, 0.001f, 10.0f);
    v("warmup_s", warmup_s, 0.0f, 100.0f);
    v("plane_agreement_deg", plane_agreement_deg, 0.0f, 90.0f);
    v("max_disagreement_deg", max_disagreement_deg, 0.01f, 90.0f);
  }
};

// --- normals (thesis 3.2): organized grid of cell means, normals by neighbour cross products
struct NormalsConfig {
  int grid_cell_px = 4;            // px at 640 wide; cell side (scaled, >= 1)
  int radius_cells = 2;            // cells; half baseline of the cross product
  float max_depth_m = 5.0f;        // m; farther measurements are ignored
  float min_depth_m = 0.3f;        // m; nearer ones too (below every sensor's minimum range)
  float jump_ratio = 0.05f;        // |dz| / z above which two cells are not neighbours (and
                                   // pixels of one cell not on its nearest surface)
  float cell_min_valid_fraction = 0.5f;  // of a cell's measured pixels on its nearest surface, else no
                                         // point (flying pixels between surfaces are a few)
  float cell_min_coverage = 0.5f;  // of a cell's pixels; it counts as measured on at least this many
                                   // (a dark surface's dropout leaves half; a few returns make no mean)
  float cell_valid_fraction_range_m = 1.5f;  // m; beyond, that fraction falls as 1/depth (dropout)
  float inverse_depth_kink_per_m = 0.008f;  // 1/m; |1/z_l + 1/z_r - 2/z_c| above this = a corner or
                                             // jump between (1/z is affine in the image on a plane)
  bool smooth = true;              // 3x3 mean of the normals
  float smooth_max_angle_deg = 25.84193f;  // deg; only neighbours this close join the mean (no blur across a
                                           // step's bend; acos 0.9)

  template <class V>
  void visit(V& v) {
    v("grid_cell_px", grid_cell_px, 1, 64);
    v("radius_cells", radius_cells, 1, 16);
    v("max_depth_m", max_depth_m, 0.1f, 100.0f);
    v("min_depth_m", min_depth_m, 0.0f, 100.0f);
    v("jump_ratio", jump_ratio, 0.0f, 1.0f);
    v("cell_min_valid_fraction", cell_min_valid_fraction, 0.01f, 1.0f);
    v("cell_min_coverage", cell_min_coverage, 0.0f, 1.0f);
    v("cell_valid_fraction_range_m", cell_valid_fraction_range_m, 0.01f, 100.0f);
    v("inverse_depth_kink_per_m", inverse_depth_kink_per_m, 0.0f, 10.0f);
    v("smooth", smooth);
    v("smooth_max_angle_deg", smooth_max_angle_deg, 0.0f, 90.0f);
  }
};

// --- region_growing (thesis 3.3): "last normal" model (over-segments, never under-segments)
struct RegionGrowingConfig {
  float angle_deg = 15.0f;         // deg; max angle between neighbouring normals
  float region_angle_deg = 20.0f;  // deg; max angle to the region's mean normal (no leak round corners)
  float distance_m = 0.01f;        // m; max point-to-plane distance to the last cell at 1 m (x z^2)
  float max_distance_m = 0.03f;    // m; cap of that distance: a riser seen from above never joins
  float distance_floor_m = 0.004f;  // m; added to that distance: depth quantisation of near cells
  int min_plane_px_320 = 100;      // px at 320x240; smaller planes are dropped (scaled)
  float fit_jump_ratio = 0.05f;    // fraction of depth; a cell this much nearer or farther than a neighbour
                                   // of another segment mixes the two: left out of its segment's plane fit
                                   // (flying pixels tilt strips between jumps; as normals.jump_ratio)

  template <class V>
  void visit(V& v) {
    v("angle_deg", angle_deg, 0.0f, 90.0f);
    v("region_angle_deg", region_angle_deg, 0.0f, 90.0f);
    v("distance_m", distance_m, 0.0f, 1.0f);
    v("max_distance_m", max_distance_m, 0.0f, 1.0f);
    v("distance_floor_m", distance_floor_m, 0.0f, 0.1f);
    v("min_plane_px_320", min_plane_px_320, 1, 76800);
    v("fit_jump_ratio", fit_jump_ratio, 0.0f, 1.0f);
  }
};

// --- bridged surfaces (bridged_surfaces.hpp): plane fits away from a nosing slab grown into its riser
struct BridgedSurfacesConfig {
  float min_angle_deg = 1.5f;  // deg; a segment's cells' median normal this far from its fitted normal
                               // may show a bridged surface (gravity.consensus_deg: a tilt that matters)
  float cut_sigmas = 3.0f;     // cells farther than this many robust sigmas from the median plane are
                               // another surface (a surface's own noise lies within)
  float min_cut_m = 0.004f;    // m; never nearer than this: depth quantisation of near cells
  float min_flatter = 2.0f;    // the rest must fit this many times flatter (rms) than the whole: trimming
                               // noise changes the rms by 1.0-1.4, a bridged slab 3-13 times
  float min_across_cuts = 2.0f;  // a segment narrower across (std) than this many cuts is a line: no plane
                                 // to recover (a tread's edge strip, 1.5-2.7 mm across)
  float same_face_m = 0.05f;     // m; cells off the plane within this stay the segment's (a nosing slab's
                                 // front, verification.max_nosing_overhang_m); farther ones leave it

  template <class V>
  void visit(V& v) {
    v("min_angle_deg", min_angle_deg, 0.0f, 90.0f);
    v("cut_sigmas", cut_sigmas, 0.5f, 100.0f);
    v("min_cut_m", min_cut_m, 0.0f, 0.1f);
    v("min_flatter", min_flatter, 1.0f, 100.0f);
    v("min_across_cuts", min_across_cuts, 0.0f, 100.0f);
    v("same_face_m", same_face_m, 0.0f, 1.0f);
  }
};

// --- concave corners (concave_corners.hpp): plane fits away from time-of-flight multipath bands
struct ConcaveCornersConfig {
  float band_m = 0.08f;                // m; a corner's band: multipath bias falls off over about this (0 = off)
  float min_corner_angle_deg = 45.0f;  // deg; planes meeting at least this steeply form a corner
  float min_behind_m = 0.002f;         // m; band mean behind the rest of the plane, along the view ray
                                       // (depth errors lie along it), that counts as bent
  float behind_rms = 1.5f;             // and more than this many times the rest's rms residual (Kinect v2
                                       // multipath: 2.6-6.4; structured light at 3 m: 0.8-1.0)
  float min_core_fraction = 0.3f;      // a bent plane with less outside its bands is marked bent: not used
                                       // for gravity (also one with less outside a corner's band that bends)

  template <class V>
  void visit(V& v) {
    v("band_m", band_m, 0.0f, 1.0f);
    v("min_corner_angle_deg", min_corner_angle_deg, 0.0f, 90.0f);
    v("min_behind_m", min_behind_m, 0.0f, 0.1f);
    v("behind_rms", behind_rms, 0.0f, 100.0f);
    v("min_core_fraction", min_core_fraction, 0.0f, 1.0f);
  }
};

// --- gravity (thesis Algorithm 4): up from weighted horizontal normals
struct GravityConfig {
  float max_tilt_from_image_up_deg = 80.0f;  // deg; horizontal-plane candidates vs. image up (with no previous
                                             // up: with one, nearness to it alone)
  float parallel_deg = 4.0f;                 // deg; normals this close count as parallel
  float prior_max_deg = 20.0f;               // deg; up may turn this much from the previous frame's (more
                                             // by sway_deg_per_s where that up is older: no plane measured it)
  double prior_max_gap_s = 1.0;              // s; after a longer gap between frames the previous up is forgotten
  double carry_max_s = 0.3;                  // s; a pitch no plane measures (walls along the view, no
                                             // tread) is the last measured one this long at most: a hand-
                                             // held camera sways ~5 deg/s, 1.5 deg (consensus_deg) in 0.3 s
  double sway_deg_per_s = 10.0;  // deg/s; how fast a carried pitch may wander from the measured one: a
                                 // walker's camera swings a few degrees at step frequency (the simulated
                                 // hand-held walks: 6.5 deg/s), the prior's uncertainty
  float min_support_fraction = 0.1f;         // with a prior: treads with less support than this
                                             // fraction of the largest vertical family yield to it
  float second_family_min_angle_deg = 30.0f;  // deg; a second vertical family (risers and a wall) must
                                              // turn this far from the first for up = their cross product
  float consensus_deg = 1.5f;  // deg; a segment agrees with an up when parallel or perpendicular to it within
                               // this: a large plane's normal is good to a fraction of it, a bent tread is not
  float refine_first_deg = 3.0f;  // deg; the least-squares up's first pass takes the treads this near the
                                  // consensus up (walls and risers may set it off by a degree or two)
  float fit_rms_floor_m = 0.001f;  // m; no plane's fit residual counts as smaller (depth resolution)
  float fit_rms_floor_per_m2 = 0.0015f;  // 1/m; nor smaller than this times its depth squared: depth noise
                                         // grows with z^2 (Kinect v1 1.5 mm at 1 m, 1.4 cm at 3 m; stereo
                                         // worse) and is correlated there (quantised disparity), which a far
                                         // sliver's small residual hides; whether a frame measures its pitch
                                         // also counts it as a resolution that no average over cells beats
  float riser_lean_deg = 3.0f;  // deg; a face no taller than a rise may lean this far from plumb unseen by its
                                // fit's noise (an inclined riser, DIN 18065's undercut; its nosing's front; a
                                // time-of-flight foot): it argues for an up's pitch no better than this
  float riser_max_height_m = 0.3f;  // m; faces taller than this are walls, plumb by construction (DIN's
                                    // highest rise with its tolerance, as plane_geometry.axis_riser_max_height_m)
  float refine_prior_fraction = 1e-5f;  // directions the treads constrain less than this fraction of their
                                        // total information keep the consensus up (a lone thin strip)

  template <class V>
  void visit(V& v) {
    v("max_tilt_from_image_up_deg", max_tilt_from_image_up_deg, 0.0f, 90.0f);
    v("parallel_deg", parallel_deg, 0.0f, 45.0f);
    v("prior_max_deg", prior_max_deg, 0.0f, 180.0f);
    v("prior_max_gap_s", prior_max_gap_s, 0.0, 3600.0);
    v("carry_max_s", carry_max_s, 0.0, 3600.0);
    v("sway_deg_per_s", sway_deg_per_s, 0.0, 1000.0);
    v("min_support_fraction", min_support_fraction, 0.0f, 1.0f);
    v("second_family_min_angle_deg", second_family_min_angle_deg, 1.0f, 90.0f);
    v("consensus_deg", consensus_deg, 0.01f, 45.0f);
    v("refine_first_deg", refine_first_deg, 0.01f, 45.0f);
    v("fit_rms_floor_m", fit_rms_floor_m, 1e-6f, 0.1f);
    v("fit_rms_floor_per_m2", fit_rms_floor_per_m2, 0.0f, 0.1f);
    v("riser_lean_deg", riser_lean_deg, 0.01f, 45.0f);
    v("riser_max_height_m", riser_max_height_m, 0.0f, 10.0f);
    v("refine_prior_fraction", refine_prior_fraction, 0.0f, 1.0f);
  }
};

// --- camera_height (perception/camera_height.hpp): only where the surface beneath is verifiable
struct CameraHeightConfig {
  float view_edge_margin_m = 0.1f;   // m; a surface whose near edge is this close to where the
  float view_edge_tolerance = 0.15f;  // (+ this fraction) the image's bottom row meets its height
                                      // runs on beneath the camera
  // With the point straight beneath in view: the grid's cells around the plumb line.
  float beneath_radius_m = 0.05f;     // m; cells this close to the plumb line must lie on all its sides
                                      // (a 4 px cell at 0.5 m is 1 cm)
  int beneath_nearest_cells = 5;      // the nearest this many give the level: a few, against noise
  float level_tolerance_m = 0.05f;    // m; nearest cells farther apart in height straddle an edge (a
                                      // rise is >= 10 cm): which level is beneath is unknown
  // With the top-level "mount" (issue 15): out of view, the level at the mount's height below a level
  // carrier is its ground. Without one (hand-held), only a surface seen beneath counts.
  float mount_tilt_tolerance_deg = 3.0f;   // deg; pitch and roll this close to the mount's: the carrier is level
  float mount_height_tolerance_m = 0.05f;  // m; suspension, sinkage, noise; a riser (>= 0.1 m) is far more

  template <class V>
  void visit(V& v) {
    v("view_edge_margin_m", view_edge_margin_m, 0.0f, 10.0f);
    v("view_edge_tolerance", view_edge_tolerance, 0.0f, 10.0f);
    v("beneath_radius_m", beneath_radius_m, 0.001f, 1.0f);
    v("beneath_nearest_cells", beneath_nearest_cells, 1, 100000);
    v("level_tolerance_m", level_tolerance_m, 0.0f, 1.0f);
    v("mount_tilt_tolerance_deg", mount_tilt_tolerance_deg, 0.0f, 45.0f);
    v("mount_height_tolerance_m", mount_height_tolerance_m, 0.0f, 1.0f);
  }
};

// --- edges_depth_jumps (thesis 3.4.2): step edges where depth jumps
struct DepthJumpEdgesConfig {
  float jump_min_m = 0.05f;        // m; depth step between vertical neighbours that is a jump
  float jump_ratio = 0.03f;        // of the depth; the jump must exceed this too (noise grows)
  int gap_cells = 2;               // cells without a measurement a jump may span (shadow)
  float height_gap_m = 0.02f;      // m; jump points chain into one height group below this
  float ransac_threshold_m = 0.02f;  // m; RANSAC line inlier distance
  int ransac_iterations = 100;     // RANSAC draws per height group
  int min_points = 8;              // jump points of a line
  int max_lines_per_group = 3;     // lines fitted per height group
  float max_tilt_deg = 10.0f;      // deg; a step edge is horizontal within this
  float max_axis_deg = 20.0f;      // deg; and across the stair axis within this
  float axis_search_deg = 60.0f;   // deg; with no axis from risers and no line within max_axis_deg of across
                                   // forward, lines this far off give it (looking down a flight 35 deg off its
                                   // axis); beyond it lines run along the view: rails, walls' tops
  float axis_cluster_deg = 10.0f;  // deg; a flight's nosings are parallel within this (the axis from the
                                   // best-supported direction's lines: a rail's top along the flight is none)
  float refine_max_m = 0.05f;      // m; a jump placed at its pixel row moves at most this far from the
                                   // cell's mean point (about a cell at 2 m; farther means a bad normal)
  float level_tol_deg = 30.0f;     // deg; a near cell whose normal is this close to up is a tread: its
                                   // row is placed on the level, the cell's own normal bends at the edge
  float row_tolerance_m = 0.01f;   // m; a pixel within this (+ the next term) of the near surface is on it
  float row_tolerance_per_m2 = 0.004f;  // per m^2 of depth: the sensors' noise grows as z^2 (thesis 2.2)

  template <class V>
  void visit(V& v) {
    v("jump_min_m", jump_min_m, 0.0f, 10.0f);
    v("jump_ratio", jump_ratio, 0.0f, 1.0f);
    v("gap_cells", gap_cells, 0, 64);
    v("height_gap_m", height_gap_m, 0.0f, 1.0f);
    v("ransac_threshold_m", ransac_threshold_m, 0.0f, 1.0f);
    v("ransac_iterations", ransac_iterations, 1, 100000);
    v("min_points", min_points, 2, 100000);
    v("max_lines_per_group", max_lines_per_group, 1, 100);
    v("max_tilt_deg", max_tilt_deg, 0.0f, 90.0f);
    v("max_axis_deg", max_axis_deg, 0.0f, 90.0f);
    v("axis_search_deg", axis_search_deg, 0.0f, 90.0f);
    v("axis_cluster_deg", axis_cluster_deg, 0.0f, 90.0f);
    v("refine_max_m", refine_max_m, 0.0f, 1.0f);
    v("level_tol_deg", level_tol_deg, 0.0f, 90.0f);
    v("row_tolerance_m", row_tolerance_m, 0.0f, 1.0f);
    v("row_tolerance_per_m2", row_tolerance_per_m2, 0.0f, 1.0f);
  }
};

// --- edges_normal_image (thesis 3.4.1): gravity-aligned normals as colours, Canny, contours, Hough
struct NormalImageEdgesConfig {
  bool enabled = false;            // off by default: no later stage reads these edges, and with the
                                   // depth-jump edges and planes they changed no figure (BENCHMARKS.md
                                   // ablation); on, they go into the observation (viewer, diagnosis)
  int blur_cells = 1;              // cells; Gaussian blur radius before Canny: the two edges of a
                                   // rounded nosing's band of in-between normals become one
  float canny_low = 100.0f;        // Canny hysteresis thresholds on the 3x3 Sobel L1 gradient
  float canny_high = 200.0f;       // of the 8-bit normal image (a sharp 90 deg bend gives ~500)
  float min_contour_px = 32.0f;    // px at 640x480; shorter edge curves (their span) are noise
  float hough_theta_deg = 1.0f;    // deg; Hough angle resolution (rho: one grid cell)
  float hough_votes_px = 32.0f;    // px at 640x480; edge pixels on a line for a Hough line
  float hough_min_length_px = 48.0f;  // px at 640x480; shorter Hough segments are dropped
  float hough_max_gap_px = 12.0f;     // px at 640x480; gaps bridged along a Hough segment
  int side_cells = 2;              // cells; strip on each side of a line giving its two surfaces
  float min_bend_deg = 30.0f;      // deg; the surfaces on the two sides turn by at least this
  float max_tilt_deg = 10.0f;      // deg; a step edge is horizontal within this
  float max_axis_deg = 20.0f;      // deg; and across the stair axis within this
  float axis_search_deg = 60.0f;   // deg; with no axis from risers and no line within max_axis_deg of across
                                   // forward, lines this far off give it (looking down a flight 35 deg off its
                                   // axis); beyond it lines run along the view: rails, walls' tops
  float axis_cluster_deg = 10.0f;  // deg; a flight's nosings are parallel within this (the axis from the
                                   // best-supported direction's lines: a rail's top along the flight is none)
  float max_range_m = 4.0f;        // m; farther edges are dropped (far normals are noisy)
  float merge_bin_m = 0.05f;       // m; merge histogram bin of horizontal distance and height
  float merge_bin_deg = 10.0f;     // deg; merge histogram bin of direction (step edges are all
                                   // parallel: position tells them apart, short pieces vary)

  template <class V>
  void visit(V& v) {
    v("enabled", enabled);
    v("blur_cells", blur_cells, 0, 16);
    v("canny_low", canny_low, 0.0f, 2000.0f);
    v("canny_high", canny_high, 0.0f, 2000.0f);
    v("min_contour_px", min_contour_px, 0.0f, 4096.0f);
    v("hough_theta_deg", hough_theta_deg, 0.01f, 45.0f);
    v("hough_votes_px", hough_votes_px, 1.0f, 4096.0f);
    v("hough_min_length_px", hough_min_length_px, 0.0f, 4096.0f);
    v("hough_max_gap_px", hough_max_gap_px, 0.0f, 4096.0f);
    v("side_cells", side_cells, 1, 16);
    v("min_bend_deg", min_bend_deg, 0.0f, 180.0f);
    v("max_tilt_deg", max_tilt_deg, 0.0f, 90.0f);
    v("max_axis_deg", max_axis_deg, 0.0f, 90.0f);
    v("axis_search_deg", axis_search_deg, 0.0f, 90.0f);
    v("axis_cluster_deg", axis_cluster_deg, 0.0f, 90.0f);
    v("max_range_m", max_range_m, 0.0f, 100.0f);
    v("merge_bin_m", merge_bin_m, 0.001f, 10.0f);
    v("merge_bin_deg", merge_bin_deg, 0.01f, 180.0f);
  }
};

// --- plane_geometry (thesis 3.5): treads, risers and others; merging; extents
struct PlaneGeometryConfig {
  float horizontal_tol_deg = 12.0f;  // deg; tread/landing: normal within this of up
  float vertical_tol_deg = 15.0f;    // deg; riser: normal within this of horizontal
  float parallel_deg = 4.0f;          // deg; vertical planes this parallel are one family, merged by depth
  float axis_riser_max_deg = 60.0f;   // deg; vertical planes facing the camera within this give the stair axis
  float axis_riser_min_width_m = 0.3f;  // m; if this wide (as the narrowest tread): a riser spans its flight;
                                        // balusters, posts and a person's body (strips of 0.2-0.3 m) do not
  float axis_riser_max_height_m = 0.3f;  // m; and no taller than a rise (DIN's highest, 0.2 m, with the 0.4
                                         // tolerance); taller ones (walls, cabinets, people) give it only
                                         // where neither risers nor the nosings' lines do
  float axis_riser_min_spacing_m = 0.14f;  // m; parallel ones this far apart are a flight's risers (the shortest
                                           // DIN tread, 0.23 m, less the 0.4 tolerance): they alone give the axis
  float edge_axis_min_change_deg = 0.5f;  // deg; with none, the nosings' depth-jump lines give it (looking down a
                                          // flight at an angle): a smaller turn keeps the first pass (< 1 cm per m)
  float merge_bin_m = 0.05f;         // m; height/depth histogram bin
  float tread_split_min_seen_fraction = 0.5f;  // of their common width: a lower surface seen across this much
                                               // between two pieces at one height keeps them apart (nothing is
                                               // seen through a tread; a cell or two at their edges is noise)
  float extent_percentile = 0.02f;   // fraction trimmed at each end of an extent
  float tread_strip_m = 0.1f;        // m; a tread's extent along the stair is also taken in lateral strips this
                                     // wide (several under the narrowest step): where it ends under a step
  float view_edge_band_m = 0.02f;    // m; cells this close to a plane's top (bottom) height are its top
                                     // (bottom) row: in the grid's margin, the plane may go on out of view
  float riser_face_band_fraction = 0.25f;  // of a riser's seen height, left out at its top and at its foot
                                           // where its face is placed (median): a nosing's slab front stands
                                           // 2-5 cm before the face, a concave foot reads long (multipath)
  float occluder_min_gap_m = 0.1f;   // m; a surface this much nearer (optical depth) just above a riser's
                                     // top hides it: its top is where the view of it stops (a table's edge
                                     // before a sofa), not its top (a nosing's slab stands <= 5 cm before it)
  float occluded_top_fraction = 0.5f;  // of a riser's top cells: more with a nearer surface just above = top unseen

  template <class V>
  void visit(V& v) {
    v("horizontal_tol_deg", horizontal_tol_deg, 0.0f, 45.0f);
    v("vertical_tol_deg", vertical_tol_deg, 0.0f, 45.0f);
    v("parallel_deg", parallel_deg, 0.0f, 45.0f);
    v("axis_riser_max_deg", axis_riser_max_deg, 0.0f, 90.0f);
    v("axis_riser_min_width_m", axis_riser_min_width_m, 0.0f, 10.0f);
    v("axis_riser_max_height_m", axis_riser_max_height_m, 0.0f, 10.0f);
    v("axis_riser_min_spacing_m", axis_riser_min_spacing_m, 0.0f, 10.0f);
    v("edge_axis_min_change_deg", edge_axis_min_change_deg, 0.0f, 45.0f);
    v("merge_bin_m", merge_bin_m, 0.001f, 1.0f);
    v("tread_split_min_seen_fraction", tread_split_min_seen_fraction, 0.0f, 1.0f);
    v("extent_percentile", extent_percentile, 0.0f, 0.49f);
    v("tread_strip_m", tread_strip_m, 0.01f, 1.0f);
    v("view_edge_band_m", view_edge_band_m, 0.0f, 1.0f);
    v("riser_face_band_fraction", riser_face_band_fraction, 0.0f, 0.49f);
    v("occluder_min_gap_m", occluder_min_gap_m, 0.0f, 10.0f);
    v("occluded_top_fraction", occluded_top_fraction, 0.0f, 1.0f);
  }
};

// --- stair: the step model of steps, grammar and reconstruction (thesis 4; DIN 18065 with tolerance)
struct StairConfig {
  float riser_min_m = 0.14f;         // m; DIN 18065 rise bounds
  float riser_max_m = 0.20f;
  float tread_min_m = 0.23f;         // m; DIN 18065 going bounds
  float tread_max_m = 0.37f;
  float step_rule_min_m = 0.59f;     // m; 2R + T lower bound (step rule)
  float step_rule_max_m = 0.65f;     // m; 2R + T upper bound
  float din_tolerance = 0.4f;        // relative tolerance on every DIN bound (old and odd flights)
  float level_max_spread_of_rise = 0.5f;  // of the rise: a level's heights reach at most this far towards
                                          // the next (a tread is level within noise; a ramp is not)
  float landing_min_depth_m = static_cast<float>(StairDefinition{}.landing_min_depth_m);  // m; not a key here: the config
                                     // file's top-level stair.landing_min_depth_m, shared with the tracker
  float min_step_width_m = 0.3f;     // m; narrower horizontal planes (chair seats) are no treads
  float max_lateral_gap_m = 0.5f;    // m; consecutive treads must overlap laterally up to this gap
  float min_riser_seen_fraction = 0.1f;  // of the median rise: a riser standing on the last
                                         // tread, its top cut off by the view, still gives a step
  int min_steps = 2;                 // fewer detected steps = no staircase
  float same_level_m = 0.04f;        // m; a tread and a riser's top (or a depth jump) this close in height
                                     // are one level (noise of a tread's mean height at range)
  float riser_own_behind_m = 0.1f;   // m; a tread from this far behind a riser's face ...
  float riser_own_ahead_m = 0.4f;    // ... to this far ahead of it is that riser's own (about a run)
  float riser_at_nosing_m = 0.1f;    // m; a segmented riser this close to a level's front edge is its step's
  float riser_contact_m = 0.06f;     // m; a riser's bottom (top) this close to a level stands on (reaches) it
  float riser_min_width_m = 0.1f;    // m; a narrower plane facing the camera is no step's riser: a baluster or
                                     // post (2-8 cm) before a riser had stood for it (a 17 cm and a 32 cm run)
  float max_level_gap_m = 0.3f;      // m; a level ends this close to where the next one starts (the riser
                                     // between, its occluded strip)

  // The lowest and highest rise the grammar accepts: DIN's bounds widened by din_tolerance.
  float lowest_rise_m() const { return riser_min_m * (1 - din_tolerance); }
  float highest_rise_m() const { return riser_max_m * (1 + din_tolerance); }

  template <class V>
  void visit(V& v) {
    v("riser_min_m", riser_min_m, 0.0f, 1.0f);
    v("riser_max_m", riser_max_m, 0.0f, 1.0f);
    v("tread_min_m", tread_min_m, 0.0f, 2.0f);
    v("tread_max_m", tread_max_m, 0.0f, 2.0f);
    v("step_rule_min_m", step_rule_min_m, 0.0f, 4.0f);
    v("step_rule_max_m", step_rule_max_m, 0.0f, 4.0f);
    v("din_tolerance", din_tolerance, 0.0f, 1.0f);
    v("level_max_spread_of_rise", level_max_spread_of_rise, 0.01f, 1.0f);
    v("min_step_width_m", min_step_width_m, 0.0f, 10.0f);
    v("max_lateral_gap_m", max_lateral_gap_m, 0.0f, 10.0f);
    v("min_riser_seen_fraction", min_riser_seen_fraction, 0.0f, 1.0f);
    v("min_steps", min_steps, 1, 64);
    v("same_level_m", same_level_m, 0.0f, 1.0f);
    v("riser_own_behind_m", riser_own_behind_m, 0.0f, 2.0f);
    v("riser_own_ahead_m", riser_own_ahead_m, 0.0f, 2.0f);
    v("riser_at_nosing_m", riser_at_nosing_m, 0.0f, 1.0f);
    v("riser_contact_m", riser_contact_m, 0.0f, 1.0f);
    v("riser_min_width_m", riser_min_width_m, 0.0f, 10.0f);
    v("max_level_gap_m", max_level_gap_m, 0.0f, 5.0f);
  }
};

// --- output: what an observation carries (stair_observation_t caps)
struct OutputConfig {
  int max_sample_points = 1024;  // per tread/riser, spatially even grid subsample
  int max_other_points = 64;     // per other plane
  int max_planes = 64;           // segmented planes reported, treads/risers first
  int max_edges = 256;           // edges reported, depth-jump edges first

  template <class V>
  void visit(V& v) {
    v("max_sample_points", max_sample_points, 1, limits::kPlanePoints);
    v("max_other_points", max_other_points, 0, limits::kPlanePoints);
    // Segmented planes leave a quarter of the message's planes to reconstruction (thesis 4.5).
    v("max_planes", max_planes, 1, limits::kObservationPlanes * 3 / 4);
    v("max_edges", max_edges, 0, limits::kObservationEdges);
  }
};

// The whole pipeline: one section per stage, read by that stage only.
struct PerceptionConfig {
  NormalsConfig normals;
  RegionGrowingConfig region_growing;
  BridgedSurfacesConfig bridged_surfaces;
  ConcaveCornersConfig concave_corners;
  GravityConfig gravity;
  ImuConfig imu;
  PlaneGeometryConfig plane_geometry;
  DepthJumpEdgesConfig edges_depth_jumps;
  NormalImageEdgesConfig edges_normal_image;
  StairConfig stair;
  VerificationConfig verification;
  CameraHeightConfig camera_height;
  OutputConfig output;
  MountConfig mount;  // not a key of "perception": the config file's top-level "mount"

  template <class V>
  void visit(V& v) {
    v.section("normals", normals);
    v.section("region_growing", region_growing);
    v.section("bridged_surfaces", bridged_surfaces);
    v.section("concave_corners", concave_corners);
    v.section("gravity", gravity);
    v.section("imu", imu);
    v.section("plane_geometry", plane_geometry);
    v.section("edges_depth_jumps", edges_depth_jumps);
    v.section("edges_normal_image", edges_normal_image);
    v.section("stair", stair);
    v.section("verification", verification);
    v.section("camera_height", camera_height);
    v.section("output", output);
  }
};

// The "perception" object of a config (any subset of the sections and their
// keys). Throws std::runtime_error naming `file`, the key and its allowed range
// on an unknown key, a wrong type, a value out of range or values that
// contradict each other (riser_min_m above riser_max_m).
PerceptionConfig perception_config_from_json(const nlohmann::json& object, const std::string& file);
// The config file's "perception" object with the top-level "stair" and "mount" objects applied.
PerceptionConfig perception_config_from_sections(const ConfigSections& sections, const std::string& file);
// The config file at `path` (common/config_file.hpp); "" = defaults.
PerceptionConfig load_perception_config(const std::string& path);
// The shared "stair" object this config was given (--print-config).
StairDefinition stair_definition(const PerceptionConfig& c);
// The effective values, as the config file's "perception" object (--print-config).
nlohmann::ordered_json to_json(const PerceptionConfig& c);

}  // namespace stairs
