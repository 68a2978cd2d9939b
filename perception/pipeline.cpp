#include "perception/pipeline.hpp"

#include "perception/camera_height.hpp"
#include "perception/edges_depth_jumps.hpp"
#include "perception/edges_normal_image.hpp"
#include "perception/gravity.hpp"
#include "perception/grammar.hpp"
#include "perception/plane_geometry.hpp"
#include "perception/reconstruction.hpp"
#include "perception/region_growing.hpp"
#include "perception/steps.hpp"
#include "perception/verification.hpp"

#include <chrono>
#include <cmath>

namespace stairs {

namespace {

class StageClock {
 public:
  explicit StageClock(Observation& obs) : obs_(obs), start_(now()), last_(start_) {}
  // A stage run again (plane_geometry on the nosings' axis) adds to its first entry.
  void mark(const char* name) {
    const auto t = now();
    const double ms = std::chrono::duration<double, std::milli>(t - last_).count();
    last_ = t;
    for (StageLatency& s : obs_.stages)
      if (s.name == name) {
        s.ms += ms;
        return;
      }
    obs_.stages.push_back({name, ms});
  }
  void finish() { obs_.latency_ms = std::chrono::duration<double, std::milli>(now() - start_).count(); }

 private:
  static std::chrono::steady_clock::time_point now() { return std::chrono::steady_clock::now(); }
  Observation& obs_;
  std::chrono::steady_clock::time_point start_, last_;
};

bool usable(const DepthImage& f, std::string& why) {
  const Intrinsics& K = f.K;
  if (K.width <= 0 || K.height <= 0) return why = "empty frame", false;
  if (f.depth.size() != static_cast<size_t>(K.width) * K.height) return why = "depth size != width*height", false;
  if (!(std::isfinite(K.fx) && std::isfinite(K.fy) && std::isfinite(K.cx) && std::isfinite(K.cy) && K.fx > 0 &&
        K.fy > 0))
    return why = "invalid intrinsics", false;
  if (!(std::isfinite(f.depth_scale) && f.depth_scale > 0)) return why = "invalid depth_scale", false;
  return true;
}

// Why a frame shows no staircase when verification refuted nothing: the grammar's evidence
// fell short (issue 14: "report no staircase and say why in the observation's status").
std::string shortfall(size_t levels, int chain_steps, size_t steps, int min_steps) {
  if (levels == 0) return "no level surface in view";
  if (chain_steps == 0) return "no two levels in view a plausible step apart (DIN 18065)";
  return std::to_string(steps) + " step" + (steps == 1 ? "" : "s") + " in view, a staircase needs " +
         std::to_string(min_steps);
}

}  // namespace

Pipeline::Pipeline(PerceptionConfig cfg) : cfg_(cfg), imu_(cfg_.imu) {}

Observation Pipeline::process(const DepthImage& frame) {
  Observation obs;
  obs.source_utime = frame.utime;
  obs.source_seq = frame.seq;
  StageClock clock(obs);
  if (!usable(frame, obs.status)) {
    clock.finish();
    return obs;
  }
  compute_normals(frame, cfg_.normals, grid_);
  clock.mark("normals");
  std::vector<Segment> segments = grow_regions(grid_, cfg_.region_growing, frame.K.width, frame.K.height, labels_);
  clock.mark("region_growing");
  fit_away_from_concave_corners(grid_, cfg_.concave_corners, segments, corners_);
  clock.mark("concave_corners");
  fit_away_from_bridged_surfaces(grid_, cfg_.bridged_surfaces, segments, bridged_);
  clock.mark("bridged_surfaces");
  // The previous up is forgotten after a gap between frames (the camera may have been moved
  // anywhere meanwhile), not while frames keep coming whose planes do not measure it: it then bounds
  // the turn, as far as the camera may have swayed since (a level Kinect v2 descent's pitch, unmeasured
  // for a second, was then set 33 deg off by a strip of treads at the image's bottom edge).
  const int64_t frame_gap_us = frame.utime - last_utime_;
  last_utime_ = frame.utime;
  if (frame_gap_us < 0 || frame_gap_us > cfg_.gravity.prior_max_gap_s * 1e6) up_prior_.reset();
  // The prior's pitch is known to the sway since it was measured (a frame's worth at least).
  const double since_measured_s = std::max(1e-6 * static_cast<double>(frame.utime - measured_utime_), 0.0);
  GravityConfig gravity = cfg_.gravity;
  gravity.prior_max_deg =
      static_cast<float>(std::max<double>(gravity.prior_max_deg, gravity.sway_deg_per_s * since_measured_s));
  bool carried = false;
  const double prior_sigma_rad = gravity.sway_deg_per_s * M_PI / 180.0 * since_measured_s;
  std::optional<Eigen::Vector3f> planes_up = estimate_up(
      segments, gravity, up_prior_, &carried,
      prior_sigma_rad > 0.0 ? 1.0 / (prior_sigma_rad * prior_sigma_rad) : std::numeric_limits<double>::infinity());
  // A pitch no plane measures is carried from the last frame that measured it,
  // for a while only: the camera turns meanwhile.
  const bool carried_too_long =
      planes_up && carried && frame.utime - measured_utime_ > cfg_.gravity.carry_max_s * 1e6;
  if (carried_too_long) planes_up.reset();
  if (planes_up) {
    up_prior_ = planes_up;
    if (!carried) measured_utime_ = frame.utime;
  }
  const FusedUp fused = fuse_up(planes_up, imu_.up_at(frame.utime), cfg_.imu);
  const auto& up = fused.up;
  clock.mark("gravity");
  if (!up) {
    obs.status = carried_too_long ? "pitch unmeasured (walls along the view, no level plane that fixes it) for "
                                    "longer than gravity.carry_max_s: pose unknown"
                                  : "no horizontal plane: pose unknown";
    clock.finish();
    return obs;
  }
  obs.camera = pose_from_up(*up);
  const Eigen::Matrix3f R = obs.camera.gravity_rotation.toRotationMatrix().cast<float>();
  PlaneSet ps = plane_geometry(grid_, segments, R, cfg_.plane_geometry, cfg_.output);
  clock.mark("plane_geometry");
  std::vector<JumpEdge> jump_edges =
      depth_jump_edges(grid_, frame, R, ps.yaw_rad, cfg_.edges_depth_jumps, cfg_.stair.min_step_width_m);
  clock.mark("edges_depth_jumps");
  // Looking down a flight the risers are hidden: without one facing the camera the axis was taken
  // forward, and a camera turned from the flight then places each nosing by where its seen part's
  // middle lies (an 8-13 deg turn shortened treads by 0.5-1 cm). The nosings' lines give the axis;
  // where none lies near across forward, lines farther off are searched (a walker 35 deg off a
  // descent's axis saw no step in any frame). A wall facing the camera (taller than a rise) gives it
  // where they do not, or only at one height: a side wall seen obliquely is one, but so is the end
  // wall of a top landing, and one line (a hole's rim in a dark tread) is less than a wall.
  if (!ps.axis_from_risers) {
    const DepthJumpEdgesConfig& ec = cfg_.edges_depth_jumps;
    std::optional<EdgeAxis> edge_axis = axis_from_edges(jump_edges, ec.axis_cluster_deg, ec.height_gap_m);
    if (!edge_axis && ec.axis_search_deg > ec.max_axis_deg) {
      DepthJumpEdgesConfig wide = ec;
      wide.max_axis_deg = ec.axis_search_deg;
      edge_axis = axis_from_edges(depth_jump_edges(grid_, frame, R, ps.yaw_rad, wide, cfg_.stair.min_step_width_m),
                                  ec.axis_cluster_deg, ec.height_gap_m);
      clock.mark("edges_depth_jumps");
    }
    std::optional<float> axis;
    if (edge_axis) axis = edge_axis->yaw_rad;
    if (ps.tall_facing_yaw_rad && (!edge_axis || edge_axis->heights < 2)) axis = ps.tall_facing_yaw_rad;
    if (axis && std::abs(*axis - ps.yaw_rad) > cfg_.plane_geometry.edge_axis_min_change_deg * M_PI / 180.0) {
      ps = plane_geometry(grid_, segments, R, cfg_.plane_geometry, cfg_.output, axis);
      clock.mark("plane_geometry");
      jump_edges = depth_jump_edges(grid_, frame, R, ps.yaw_rad, ec, cfg_.stair.min_step_width_m);
      clock.mark("edges_depth_jumps");
    }
  }
  std::vector<Edge> normal_edges;
  if (cfg_.edges_normal_image.enabled) {  // a diagnostic: nothing below reads these edges
    normal_edges = normal_image_edges(grid_, R, ps.yaw_rad, cfg_.edges_normal_image, cfg_.normals.grid_cell_px,
                                      cfg_.stair.min_step_width_m);
    clock.mark("edges_normal_image");
  }
  const std::vector<Level> levels = tread_levels(ps, jump_edges, cfg_.stair);
  clock.mark("steps");
  const StairChain chain = best_chain(levels, cfg_.stair);
  std::vector<Step> steps = steps_from_chain(ps, chain, cfg_.stair);
  clock.mark("grammar");
  reconstruct(ps, chain, steps, cfg_.stair);
  const size_t n_reconstructed = steps.size();
  clock.mark("reconstruction");
  std::string refuted;
  if (static_cast<int>(steps.size()) >= cfg_.stair.min_steps) {
    const Verdict verdict = verify(grid_, frame.K, R, ps, chain.direction, steps, cfg_.verification,
                                   cfg_.stair.highest_rise_m());
    steps.resize(verdict.kept);
    refuted = verdict.reason;
  }
  clock.mark("verification");
  if (static_cast<int>(steps.size()) < cfg_.stair.min_steps) steps.clear();
  obs.camera.height_m = camera_height(ps, grid_, R, frame.K, obs.camera.pitch_deg, obs.camera.roll_deg, cfg_.camera_height,
                                     cfg_.mount);
  if (!steps.empty()) {
    obs.direction = chain.direction;
    obs.steps = std::move(steps);
    const double d = ps.axial(obs.steps.front().nosing_m);
    if (d > 0) obs.camera.distance_m = d;
    obs.status = refuted.empty() ? "ok" : "ok; verification dropped " + refuted;
  } else {
    obs.status = "no staircase: " + (refuted.empty() ? shortfall(levels.size(), chain.steps(), n_reconstructed,
                                                                 cfg_.stair.min_steps)
                                                       : "verification: " + refuted);
  }
  if (!fused.note.empty()) obs.status += "; " + fused.note;
  obs.planes = std::move(ps.planes);
  for (const JumpEdge& j : jump_edges) obs.edges.push_back(j.edge);
  obs.edges.insert(obs.edges.end(), normal_edges.begin(), normal_edges.end());
  if (obs.edges.size() > static_cast<size_t>(cfg_.output.max_edges)) obs.edges.resize(cfg_.output.max_edges);
  clock.finish();
  return obs;
}

}  // namespace stairs
