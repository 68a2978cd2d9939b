// Every parameter of the stair tracker (thesis chapter 5 plus real-speed
// tracking): one struct per concept, each field with its unit, default,
// allowed range and a one-line reason; read only where that concept lives.
#pragma once

#include "common/config_file.hpp"
#include "common/limits.hpp"
#include "common/mount.hpp"
#include "common/stair_definition.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace stairs {

// --- stair: what the model assumes of a stair until it has measured one (stair_map.hpp)
struct StairPriorConfig {
  double default_riser_m = 0.17;        // m; used until the model has measured risers
  double default_tread_m = 0.28;        // m; used until the model has measured treads
  double landing_min_depth_m = StairDefinition{}.landing_min_depth_m;  // m; not a key here: the config
                                        // file's top-level stair.landing_min_depth_m, shared with perception
  double typical_riser_fraction = 0.3;  // of the typical riser: consecutive steps this regular give the
                                        // typical tread (a step missing between them would double the rise)
  double riser_bracket_fraction = 0.5;  // of default_riser_m: height steps this close to it count as rises
                                        // (half a riser off is a missing or a false step, not a rise)

  template <class V>
  void visit(V& v) {
    v("default_riser_m", default_riser_m, 0.01, 1.0);
    v("default_tread_m", default_tread_m, 0.01, 2.0);
    v("typical_riser_fraction", typical_riser_fraction, 0.01, 1.0);
    v("riser_bracket_fraction", riser_bracket_fraction, 0.01, 1.0);
  }
};

// --- confirmation: when a model starts and when it is published (thesis 5.1)
struct ConfirmationConfig {
  int min_seed_steps = 2;     // steps an observation needs to start a model, and confirmed steps to publish it
  int min_confirmations = 2;  // observations a step needs to be published
  // Observations a step needs to be published with the frame that saw it, when it continues the
  // confirmed steps that frame registered on (min_seed_steps of them): the next step of a flight comes
  // into view a frame before a second one confirms it, and it is the same flight's step (1 publishes it
  // with that frame only, min_confirmations switches it off).
  int min_confirmations_continuing = 1;

  template <class V>
  void visit(V& v) {
    v("min_seed_steps", min_seed_steps, 1, 64);
    v("min_confirmations", min_confirmations, 1, 1000);
    v("min_confirmations_continuing", min_confirmations_continuing, 1, 1000);
  }
};

// --- registration: 4-DoF ICP in the gravity-aligned frame (x, y, z, yaw; thesis 5.1)
struct RegistrationConfig {
  double icp_max_distance_m = 1.0;      // m; first (coarsest) correspondence threshold, at most
  double icp_max_tread_fraction = 0.4;  // of the typical tread: the first threshold's cap (aliasing)
  double icp_min_distance_m = 0.01;     // m; last (finest) threshold
  double icp_distance_factor = 0.5;     // threshold shrink per stage
  int icp_iterations_per_stage = 2;     // closed-form updates per threshold
  int points_per_plane = 128;           // observation points used per tread/riser (even stride)
  double nosing_weight_points = 40.0;   // one observed nosing counts as this many plane points
  double accept_distance_m = 0.04;      // m; a point within this of the model counts as agreeing
  double foot_max_offset_rise_fraction = 0.25;  // of the lowest step's rise: a level this close to where its
                                                // riser begins is the one it stands on (levels differ by a rise)
  double foot_max_gap_m = 0.15;  // m; ... and reaches to within this of its riser along the stair (a nosing
                                 // overhangs by up to 5 cm, a plane's trimmed extent stops a few cm short)
  double position_uncertainty_m = 0.01;  // m; a registered camera's position along the stair may be this far
                                         // off: the nosings it rests on are located to about a grid cell (4 px
                                         // at 1.3 m with a 525 px focal length: 1 cm); nearer a nosing, the step
                                         // beneath is unknown

  template <class V>
  void visit(V& v) {
    v("icp_max_distance_m", icp_max_distance_m, 0.001, 10.0);
    v("icp_max_tread_fraction", icp_max_tread_fraction, 0.01, 10.0);
    v("icp_min_distance_m", icp_min_distance_m, 0.0001, 10.0);
    v("icp_distance_factor", icp_distance_factor, 0.01, 0.99);
    v("icp_iterations_per_stage", icp_iterations_per_stage, 1, 100);
    v("points_per_plane", points_per_plane, 1, limits::kPlanePoints);
    v("nosing_weight_points", nosing_weight_points, 0.0, 10000.0);
    v("accept_distance_m", accept_distance_m, 0.0001, 1.0);
    v("foot_max_offset_rise_fraction", foot_max_offset_rise_fraction, 0.0, 1.0);
    v("foot_max_gap_m", foot_max_gap_m, 0.0, 10.0);
    v("position_uncertainty_m", position_uncertainty_m, 0.0, 1.0);
  }
};

// --- motion: the prior between registrations and the checks against it (tracker.cpp)
struct MotionConfig {
  double min_inlier_ratio = 0.5;         // registrations agreeing less are rejected
  double max_yaw_jump_deg = 15.0;        // deg; per observation, vs. the motion prior
  double max_translation_jump_m = 0.12;  // m; ICP correction vs. the motion prior (< half a tread)
  double velocity_window_s = 0.5;        // s; constant velocity from the poses this far back (noise / window)
  double max_prediction_s = 1.5;         // s; longer gaps since the last registration or placement predict
                                         // no motion (relocalise instead)
  double observed_height_max_riser_fraction = 0.5;  // of a riser: perception's height over the surface
                                                    // beneath corrects the prior's only this close (else
                                                    // that surface may be the next level ahead)
  double predict_camera_s = 1.0;  // s; an update that registers nothing (no steps in view, a rejected
                                  // registration) still places the camera by the motion prior this long,
                                  // and on the model's risers, nosings or end wall in view this long
                                  // after the last such placement
  double max_accel_mps2 = 1.0;  // m/s^2; a walker's or a climbing robot's speed along the stair changes
                                // this fast at most (~0.1 g): the prior's position may be a*t^2/2 off

  template <class V>
  void visit(V& v) {
    v("min_inlier_ratio", min_inlier_ratio, 0.0, 1.0);
    v("max_yaw_jump_deg", max_yaw_jump_deg, 0.0, 180.0);
    v("max_translation_jump_m", max_translation_jump_m, 0.0, 10.0);
    v("velocity_window_s", velocity_window_s, 0.001, 60.0);
    v("max_prediction_s", max_prediction_s, 0.0, 60.0);
    v("observed_height_max_riser_fraction", observed_height_max_riser_fraction, 0.0, 2.0);
    v("predict_camera_s", predict_camera_s, 0.0, 60.0);
    v("max_accel_mps2", max_accel_mps2, 0.0, 100.0);
  }
};

// --- odometry (optional input, tracker/odometry_prior.hpp): the motion prior where it covers
struct OdometryConfig {
  double max_age_s = 0.25;  // s; odometry this old at a frame still holds (late samples, 4 Hz odometry
                            // at worst); older is no prior
  int max_samples = 20000;  // history cap (200 s at 100 Hz): memory stays bounded

  template <class V>
  void visit(V& v) {
    v("max_age_s", max_age_s, 0.0, 10.0);
    v("max_samples", max_samples, 2, 1000000);
  }
};

// --- relocalisation after a gap, a loss, or a registration all of whose risers and nosings disagree:
// a search over step shifts (relocalisation.hpp)
struct RelocalisationConfig {
  double after_s = 0.2;     // s; a gap longer than this triggers a whole-step search
  int step_range = 2;       // whole-step shifts tried each way (starts half a step apart)
  double min_gain = 0.05;   // of the prior's agreeing points: a shift must add this many more

  template <class V>
  void visit(V& v) {
    v("after_s", after_s, 0.0, 60.0);
    v("step_range", step_range, 0, 10);
    v("min_gain", min_gain, 0.0, 10.0);
  }
};

// --- end wall: where a top landing ends (tracker/end_wall.hpp)
struct EndWallConfig {
  double min_width_m = 0.4;  // m; a face this wide across the stair: a wall, a door, the next flight's first
                             // riser (all fixed where the landing ends); a post or a chair leg is narrower
  double max_foot_offset_rise_fraction = 0.25;  // of the typical riser: no point of it lower than this below the
                                                // top level (its foot may be hidden behind the top nosing)
  double max_normal_deg = 15.0;  // deg; its normal this close to the stair's axis faces down the flight
  double min_run_fraction = 0.5;  // of the typical tread: at least this far beyond the top nosing (else it
                                  // is that step's riser seen again)

  template <class V>
  void visit(V& v) {
    v("min_width_m", min_width_m, 0.0, 100.0);
    v("max_foot_offset_rise_fraction", max_foot_offset_rise_fraction, 0.0, 1.0);
    v("max_normal_deg", max_normal_deg, 0.0, 90.0);
    v("min_run_fraction", min_run_fraction, 0.0, 10.0);
  }
};

// --- merge: observed steps into the model (thesis 5.2)
struct MergeConfig {
  double match_riser_fraction = 0.5;    // steps match within this fraction of a riser height (z)
  double match_tread_fraction = 0.5;    // ... and of a tread depth (x)
  int max_average_weight = 30;          // running averages turn exponential after this many observations
  int max_plane_points = 1024;          // model points per plane (ICP rejections only)
  int max_model_steps = 128;            // cap on the model's steps (memory and message size)
  double monotonic_tolerance_m = 0.04;  // m; a new step must rise with x within this
  double min_rise_fraction = 0.5;       // of the typical riser: a new step lies at least this far above the
                                        // step before it and below the one after (else it is the same level)
  double min_run_fraction = 0.5;        // of the typical tread: ... and this far along the flight from each
                                        // (one riser has one nosing: two at one x are one step measured twice)
  int min_tread_plane_observations = 2;  // observations of a tread plane before its height overrides the
                                        // step's edges (one sliver at a grazing angle is no measurement)
  double link_shift_fraction = 0.25;    // of a tread: steps the motion prior placed move along the stair by at
                                        // most this to where one frame puts them (prior_links.hpp; matched to the
                                        // nearest step, the next one lies three times as far)

  template <class V>
  void visit(V& v) {
    v("match_riser_fraction", match_riser_fraction, 0.01, 1.0);
    v("match_tread_fraction", match_tread_fraction, 0.01, 1.0);
    v("max_average_weight", max_average_weight, 1, 1000000);
    v("max_plane_points", max_plane_points, 0, limits::kPlanePoints);
    v("max_model_steps", max_model_steps, 1, limits::kModelPlanes / 2);  // a riser and a tread plane each
    v("monotonic_tolerance_m", monotonic_tolerance_m, 0.0, 1.0);
    v("min_rise_fraction", min_rise_fraction, 0.0, 1.0);
    v("min_run_fraction", min_run_fraction, 0.0, 1.0);
    v("min_tread_plane_observations", min_tread_plane_observations, 1, 1000);
    v("link_shift_fraction", link_shift_fraction, 0.0, 0.5);
  }
};

// --- overhang: the nosing's edge before the riser's face (tracker/nosing_overhang.hpp)
struct OverhangConfig {
  double top_band_fraction = 0.2;  // of a riser's seen height below the nosing: the slab's front face (a 2-5 cm
                                   // slab on a 15-20 cm riser fills most of it)
  double face_band_from = 0.25;    // ... and the band between these fractions is its face (above a concave
  double face_band_to = 0.7;       // corner's multipath at its foot, below the slab)
  double top_tolerance_m = 0.03;   // m; the plane's top this close to the nosing's height: the slab is in view
  double min_height_m = 0.08;      // m; less of a riser seen says nothing of its face
  int min_points = 5;              // plane sample points in each band
  int min_steps = 2;               // steps with a measured overhang before the flight has one
  double max_m = 0.06;             // m; a larger offset is no nosing (DIN 18065: overhang <= 5 cm)

  template <class V>
  void visit(V& v) {
    v("top_band_fraction", top_band_fraction, 0.01, 0.5);
    v("face_band_from", face_band_from, 0.0, 1.0);
    v("face_band_to", face_band_to, 0.0, 1.0);
    v("top_tolerance_m", top_tolerance_m, 0.0, 1.0);
    v("min_height_m", min_height_m, 0.0, 10.0);
    v("min_points", min_points, 1, 100000);
    v("min_steps", min_steps, 1, 1000);
    v("max_m", max_m, 0.0, 1.0);
  }
};

// --- reconstruction: occluded steps filled in the model (thesis 4.5 applied to the model)
struct ModelReconstructionConfig {
  int max_gap_steps = 3;    // at most this many missing steps filled between two seen ones
  double tolerance = 0.25;  // fraction of a riser/tread a gap may deviate from whole steps

  template <class V>
  void visit(V& v) {
    v("max_gap_steps", max_gap_steps, 0, 64);
    v("tolerance", tolerance, 0.0, 1.0);
  }
};

// --- direction: hysteresis over the observations' up/down (direction.hpp)
struct DirectionConfig {
  int window = 7;    // last observations considered
  int majority = 5;  // votes needed to change the direction

  template <class V>
  void visit(V& v) {
    v("window", window, 1, 1000);
    v("majority", majority, 1, 1000);
  }
};

// --- lifecycle: lost, reset, new stream
struct LifecycleConfig {
  double lost_after_s = 0.5;      // s without an accepted registration: state Lost
  double reset_after_s = 5.0;     // s lost: the model is dropped when the next stair comes into view
  double time_jump_back_s = 1.0;  // s; an observation this much older than the last starts a new stream
                                  // (a log replayed, a camera restarted): the model is reset; a smaller
                                  // step back is an out-of-order observation and is dropped

  template <class V>
  void visit(V& v) {
    v("lost_after_s", lost_after_s, 0.001, 3600.0);
    v("reset_after_s", reset_after_s, 0.001, 86400.0);
    v("time_jump_back_s", time_jump_back_s, 0.001, 86400.0);
  }
};

// The whole tracker (thesis chapter 5 plus real-speed tracking): one section per concept.
struct TrackerConfig {
  StairPriorConfig stair;
  ConfirmationConfig confirmation;
  RegistrationConfig registration;
  MotionConfig motion;
  OdometryConfig odometry;
  RelocalisationConfig relocalisation;
  MergeConfig merge;
  EndWallConfig end_wall;
  OverhangConfig overhang;
  ModelReconstructionConfig reconstruction;
  DirectionConfig direction;
  LifecycleConfig lifecycle;
  MountConfig mount;  // not a key here: the config file's top-level "mount", shared with perception

  template <class V>
  void visit(V& v) {
    v.section("stair", stair);
    v.section("confirmation", confirmation);
    v.section("registration", registration);
    v.section("motion", motion);
    v.section("odometry", odometry);
    v.section("relocalisation", relocalisation);
    v.section("merge", merge);
    v.section("end_wall", end_wall);
    v.section("overhang", overhang);
    v.section("reconstruction", reconstruction);
    v.section("direction", direction);
    v.section("lifecycle", lifecycle);
  }
};

// The "tracker" object of a config (any subset of the keys). Throws
// std::runtime_error naming `file`, the key and its allowed range on an unknown
// key, a wrong type, a value out of range or values that contradict each other.
TrackerConfig tracker_config_from_json(const nlohmann::json& object, const std::string& file);
// The config file's "tracker" object with the shared "stair" object applied.
TrackerConfig tracker_config_from_sections(const ConfigSections& sections, const std::string& file);
// The config file at `path` (common/config_file.hpp); "" = defaults.
TrackerConfig load_tracker_config(const std::string& path);
// The shared "stair" object this config was given (--print-config).
StairDefinition stair_definition(const TrackerConfig& c);
// The effective values, as the config file's "tracker" object (--print-config).
nlohmann::ordered_json to_json(const TrackerConfig& c);

// Throws std::runtime_error naming the first parameter out of range (values
// set in code: a command-line override).
void validate(const TrackerConfig& c);

}  // namespace stairs
