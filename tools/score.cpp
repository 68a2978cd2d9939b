#include "tools/score.hpp"

#include "common/gravity_frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>

namespace stairs::eval {
namespace {

struct Candidate {
  double cost;
  int detected;
  int real;
};

// One-to-one assignment, nearest pair first: greedy is exact enough here
// because the tolerances (half a step) keep candidates nearly disjoint.
std::vector<StepMatch> assign(std::vector<Candidate> candidates, size_t n_detected, size_t n_real,
                              double* total_cost = nullptr) {
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    if (a.cost != b.cost) return a.cost < b.cost;
    if (a.detected != b.detected) return a.detected < b.detected;
    return a.real < b.real;
  });
  std::vector<bool> used_d(n_detected, false), used_r(n_real, false);
  std::vector<StepMatch> out;
  double cost = 0.0;
  for (const Candidate& c : candidates) {
    if (used_d[c.detected] || used_r[c.real]) continue;
    used_d[c.detected] = used_r[c.real] = true;
    out.push_back({c.detected, c.real});
    cost += c.cost;
  }
  std::sort(out.begin(), out.end(), [](const StepMatch& a, const StepMatch& b) { return a.detected < b.detected; });
  if (total_cost) *total_cost = cost;
  return out;
}

// Squared distance (m^2) when within half the real tread (dx) and half the real
// riser (dz). Not normalised by the tolerance: a landing's deep tread would
// make it the cheapest match of all.
std::optional<double> match_cost(double dx_m, double dz_m, const Step& real) {
  if (!real.tread_depth_m || !real.riser_height_m) return std::nullopt;
  const double tx = 0.5 * *real.tread_depth_m, tz = 0.5 * *real.riser_height_m;
  if (!(std::abs(dx_m) <= tx) || !(std::abs(dz_m) <= tz)) return std::nullopt;
  return dx_m * dx_m + dz_m * dz_m;
}

struct Accumulator {
  int n = 0;
  double sum = 0.0, sum_abs = 0.0;
  void add(double v) {
    ++n;
    sum += v;
    sum_abs += std::abs(v);
  }
  ErrorStats stats() const {
    ErrorStats s;
    s.n = n;
    if (n > 0) {
      s.mean_signed = sum / n;
      s.mean_abs = sum_abs / n;
    }
    return s;
  }
};

// Foot of real step k's riser in the stair frame (x, z); below step 0 the
// stair is extrapolated with step 0's dimensions.
Eigen::Vector2d riser_foot(const std::vector<Step>& real, int k) {
  const Step& s0 = real.front();
  const Eigen::Vector2d foot0(s0.nosing_m.x(), s0.nosing_m.z() - s0.riser_height_m.value_or(0.0));
  if (k >= 0) {
    const Step& s = real[static_cast<size_t>(k)];
    return {s.nosing_m.x(), s.nosing_m.z() - s.riser_height_m.value_or(0.0)};
  }
  return foot0 + k * Eigen::Vector2d(s0.tread_depth_m.value_or(0.0), s0.riser_height_m.value_or(0.0));
}

// The whole-step offset (real index - model index) that most of one frame's
// tracked-step matches agree on (the smaller one on a tie); none without a match.
std::optional<int> frame_model_offset(const std::vector<int>& tracked_real) {
  std::map<int, int> votes;
  for (size_t i = 0; i < tracked_real.size(); ++i)
    if (tracked_real[i] >= 0) ++votes[tracked_real[i] - static_cast<int>(i)];
  std::optional<int> best;
  int most = 0;
  for (const auto& [offset, n] : votes)
    if (n > most) best = offset, most = n;
  return best;
}

}  // namespace

int true_step_at(double x_m, const std::vector<Step>& real) {
  int level = -1;  // the highest step whose nosing is behind x
  for (size_t k = 0; k < real.size(); ++k)
    if (real[k].nosing_m.x() <= x_m) level = static_cast<int>(k);
  return level;
}

// The real surface's height at a level of true_step_at: the floor (0) below the first step.
double true_surface_z(int level, const std::vector<Step>& real) {
  return level < 0 ? 0.0 : real[static_cast<size_t>(level)].nosing_m.z();
}

int true_step_beneath(const GroundTruthFrame& frame, const std::vector<Step>& real) {
  return true_step_at(frame.position_m.x(), real);
}

std::vector<Step> real_steps(const GroundTruth& truth) {
  std::vector<Step> out;
  for (const Flight& f : truth.flights) out.insert(out.end(), f.steps.begin(), f.steps.end());
  return out;
}

Eigen::Isometry3d gravity_frame_in_stair(const GroundTruthFrame& frame) {
  return gravity_frame_pose(frame.position_m, frame.orientation);
}

Eigen::Vector3d true_nosing_in_gravity_frame(const Step& real, const GroundTruthFrame& frame, double left_m) {
  const Eigen::Isometry3d to_gravity = gravity_frame_in_stair(frame).inverse();
  const Eigen::Vector3d p0 = to_gravity * Eigen::Vector3d(real.nosing_m.x(), 0.0, real.nosing_m.z());
  const Eigen::Vector3d dir = to_gravity.linear() * Eigen::Vector3d::UnitY();  // horizontal, unit
  const double t = std::abs(dir.y()) >= 0.5 ? (left_m - p0.y()) / dir.y()
                                            : -(p0.x() * dir.x() + p0.y() * dir.y());
  return p0 + t * dir;
}

bool beneath_in_view(const GroundTruthFrame& frame, const std::vector<Step>& real, const Intrinsics& K) {
  const Eigen::Vector3d& p = frame.position_m;
  const double forward_x = gravity_frame_in_stair(frame).linear()(0, 0);  // +1 walking up the x axis
  const int level = true_step_beneath(frame, real);
  const double surface_z = true_surface_z(level, real);
  // Where that level ends ahead of the camera (none: it runs on).
  std::optional<double> end_x;
  if (forward_x > 0 && level + 1 < static_cast<int>(real.size())) end_x = real[static_cast<size_t>(level + 1)].nosing_m.x();
  if (forward_x < 0 && level >= 0) end_x = real[static_cast<size_t>(level)].nosing_m.x();
  const double below_deg = -frame.pitch_deg + std::atan((K.height - 1 - K.cy) / K.fy) * 180.0 / M_PI;
  if (below_deg >= 90.0) return true;  // the point straight beneath is in view
  if (below_deg <= 0.0) return false;
  const double nearest_m = (p.z() - surface_z) / std::tan(below_deg * M_PI / 180.0);
  constexpr double kMargin_m = 0.05;
  return !end_x || nearest_m + kMargin_m < std::abs(*end_x - p.x()) * std::abs(forward_x);
}

bool nosing_in_view(const GroundTruthFrame& frame, const Step& real, const Intrinsics& K) {
  const Eigen::Vector3d p = frame.orientation.normalized().conjugate() *
                            (Eigen::Vector3d(real.nosing_m.x(), 0.0, real.nosing_m.z()) - frame.position_m);
  if (p.z() <= 0.0) return false;
  const double u = K.fx * p.x() / p.z() + K.cx, v = K.fy * p.y() / p.z() + K.cy;
  return u >= 0 && u <= K.width - 1 && v >= 0 && v <= K.height - 1;
}

std::vector<StepMatch> match_frame_steps(const std::vector<Step>& detected, const std::vector<Step>& real,
                                         const GroundTruthFrame& frame) {
  std::vector<Candidate> candidates;
  for (size_t i = 0; i < detected.size(); ++i) {
    const Eigen::Vector3d& d = detected[i].nosing_m;
    for (size_t j = 0; j < real.size(); ++j) {
      const Eigen::Vector3d t = true_nosing_in_gravity_frame(real[j], frame, d.y());
      if (auto c = match_cost(d.x() - t.x(), d.z() - t.z(), real[j]))
        candidates.push_back({*c, static_cast<int>(i), static_cast<int>(j)});
    }
  }
  return assign(std::move(candidates), detected.size(), real.size());
}

ModelMatch match_model_steps(const std::vector<Step>& model, const std::vector<Step>& real) {
  ModelMatch best;
  if (model.empty() || real.empty()) return best;
  const int n_model = static_cast<int>(model.size()), n_real = static_cast<int>(real.size());
  const Eigen::Vector2d foot0 = riser_foot(real, 0);
  double best_cost = 0.0;
  int best_agree = 0;
  bool have = false;
  // Offsets in order of |o| so that strict comparisons keep the smaller one.
  for (int k = 0; k <= std::max(n_model, n_real); ++k) {
    for (int o : {k, -k}) {
      if (o < -n_model || o > n_real - 1) continue;
      const Eigen::Vector2d shift = riser_foot(real, o) - foot0;
      std::vector<Candidate> candidates;
      for (int i = 0; i < n_model; ++i) {
        const Eigen::Vector2d m(model[i].nosing_m.x() + shift.x(), model[i].nosing_m.z() + shift.y());
        for (int j = 0; j < n_real; ++j)
          if (auto c = match_cost(m.x() - real[j].nosing_m.x(), m.y() - real[j].nosing_m.z(), real[j]))
            candidates.push_back({*c, i, j});
      }
      double cost = 0.0;
      auto matches = assign(std::move(candidates), model.size(), real.size(), &cost);
      int agree = 0;
      for (const StepMatch& m : matches) agree += model[m.detected].landing == real[m.real].landing ? 1 : 0;
      // On a uniform flight several offsets match equally many steps; the one
      // that also agrees on which step is the landing is the right one.
      const bool better = !have || matches.size() > best.matches.size() ||
                          (matches.size() == best.matches.size() &&
                           (agree > best_agree || (agree == best_agree && cost < best_cost)));
      if (better) {
        best = {o, std::move(matches)};
        best_cost = cost;
        best_agree = agree;
        have = true;
      }
      if (k == 0) break;
    }
  }
  return best;
}

LatencyStats latency_stats(std::vector<double> samples_ms) {
  LatencyStats s;
  s.n = static_cast<int>(samples_ms.size());
  if (samples_ms.empty()) return s;
  std::sort(samples_ms.begin(), samples_ms.end());
  const size_t n = samples_ms.size();
  s.median_ms = n % 2 ? samples_ms[n / 2] : 0.5 * (samples_ms[n / 2 - 1] + samples_ms[n / 2]);
  const size_t rank = static_cast<size_t>(std::ceil(0.95 * static_cast<double>(n)));
  s.p95_ms = samples_ms[std::max<size_t>(rank, 1) - 1];
  return s;
}

std::map<std::string, LatencyStats> latency_by_stage(const std::vector<FrameResult>& frames) {
  std::map<std::string, std::vector<double>> samples;
  for (const FrameResult& f : frames)
    for (const StageLatency& l : f.latency) samples[l.name].push_back(l.ms);
  std::map<std::string, LatencyStats> out;
  for (auto& [name, v] : samples) out[name] = latency_stats(std::move(v));
  return out;
}

namespace {

// Running sums of one run's per-frame errors (table 6.1's pose columns, the tracked camera).
struct RunSums {
  Accumulator pitch, roll, height, height_visible, tracked_height, tracked_position, tracked_base_height;
  int tracked_right_step = 0, frames_since_tracked = 0, tracked_base_right_step = 0;
};

std::vector<int> matched_real(const std::vector<StepMatch>& ms, size_t detected) {
  std::vector<int> out(detected, -1);
  for (const StepMatch& m : ms) out[static_cast<size_t>(m.detected)] = m.real;
  return out;
}

// Table 6.1 for one frame: perception's and the tracker's steps matched to the
// visible real steps, over all visible ones and those whose nosing is in view.
void score_detections(const FrameResult& f, const GroundTruthFrame& gt, const std::vector<Step>& real, FrameScore& fs,
                      Score& s) {
  std::set<int> visible;
  for (int v : gt.visible_steps)
    if (v >= 0 && v < static_cast<int>(real.size())) visible.insert(v);
  s.visible_steps += static_cast<int>(visible.size());
  fs.visible.assign(visible.begin(), visible.end());
  const auto matches = match_frame_steps(f.steps, real, gt);
  fs.matched = matched_real(matches, f.steps.size());
  const auto matched_visible = [&](const std::vector<StepMatch>& ms) {
    return static_cast<int>(std::count_if(ms.begin(), ms.end(), [&](const StepMatch& m) { return visible.count(m.real) > 0; }));
  };
  s.frame_steps_matched += matched_visible(matches);
  if (f.tracked_steps) {
    s.tracked_scored = true;
    const auto tracked = match_frame_steps(*f.tracked_steps, real, gt);
    fs.tracked = matched_real(tracked, f.tracked_steps->size());
    s.tracked_steps_matched += matched_visible(tracked);
    s.tracked_false_steps += static_cast<int>(f.tracked_steps->size() - tracked.size());
  }
  if (f.K) {
    std::set<int> with_nosing;
    for (int v : visible)
      if (nosing_in_view(gt, real[static_cast<size_t>(v)], *f.K)) with_nosing.insert(v);
    s.visible_steps_nosing_in_view += static_cast<int>(with_nosing.size());
    fs.nosing_in_view.assign(with_nosing.begin(), with_nosing.end());
    for (const StepMatch& m : matches) s.frame_steps_matched_nosing_in_view += with_nosing.count(m.real) ? 1 : 0;
  }
  const int false_steps = static_cast<int>(f.steps.size() - matches.size());
  s.frame_false_steps += false_steps;
  s.frames_with_false_steps += false_steps > 0 ? 1 : 0;
}

// The tracker's camera against the truth: height, step beneath (as a real
// index through this frame's tracked-step matches) and position along the
// stair; coverage counts the frames since the tracker first gave a camera.
void score_tracked_camera(const FrameResult& f, const GroundTruthFrame& gt, const std::vector<Step>& real,
                          FrameScore& fs, Score& s, RunSums& sums) {
  if (!f.tracked_camera || !(f.tracked_camera->valid || sums.frames_since_tracked > 0)) return;
  ++sums.frames_since_tracked;
  const TrackedCamera& tc = *f.tracked_camera;
  if (!tc.valid) return;
  ++s.tracked_camera_frames;
  if (tc.height_m) sums.tracked_height.add(100.0 * (*tc.height_m - gt.height_m));
  const auto offset = fs.tracked ? frame_model_offset(*fs.tracked) : std::nullopt;
  if (tc.step_index) {
    ++s.tracked_beneath_frames;
    if (offset) fs.tracked_step_index = *tc.step_index + *offset;
    sums.tracked_right_step += fs.tracked_step_index == fs.true_step_index ? 1 : 0;
  }
  if (offset) {
    fs.tracked_position_error_cm = 100.0 * (tc.position_m.x() + riser_foot(real, *offset).x() - gt.position_m.x());
    sums.tracked_position.add(*fs.tracked_position_error_cm);
  }
}

// The tracker's robot base against the true camera carried back through the mount: its height
// over the real surface beneath and its step beneath (through this frame's tracked-step offset).
void score_tracked_base(const FrameResult& f, const GroundTruthFrame& gt, const std::vector<Step>& real,
                        const MountConfig& mount, FrameScore& fs, Score& s, RunSums& sums) {
  if (!mount.configured() || !f.tracked_base || !f.tracked_base->valid) return;
  const Eigen::Vector3d base = base_of_camera(gt.position_m, gt.orientation, mount).translation();
  const int level = true_step_at(base.x(), real);
  const double surface_z = true_surface_z(level, real);
  fs.true_base_step_index = level;
  ++s.tracked_base_frames;
  const TrackedCamera& tb = *f.tracked_base;
  if (tb.height_m) sums.tracked_base_height.add(100.0 * (*tb.height_m - (base.z() - surface_z)));
  if (!tb.step_index) return;
  ++s.tracked_base_beneath_frames;
  if (const auto offset = fs.tracked ? frame_model_offset(*fs.tracked) : std::nullopt)
    fs.tracked_base_step_index = *tb.step_index + *offset;
  sums.tracked_base_right_step += fs.tracked_base_step_index == level ? 1 : 0;
}

// Perception's camera pose against the truth.
void score_pose(const FrameResult& f, const GroundTruthFrame& gt, const std::vector<Step>& real, Score& s,
                RunSums& sums) {
  if (!f.camera.valid) return;
  ++s.pose_frames_valid;
  sums.pitch.add(f.camera.pitch_deg - gt.pitch_deg);
  sums.roll.add(f.camera.roll_deg - gt.roll_deg);
  if (!f.camera.height_m) return;
  sums.height.add(100.0 * (*f.camera.height_m - gt.height_m));
  if (f.K && beneath_in_view(gt, real, *f.K)) sums.height_visible.add(100.0 * (*f.camera.height_m - gt.height_m));
}

// Tables 6.2-6.4: the final model's steps matched to the real ones.
void score_model(const std::vector<Flight>& model, const std::vector<Step>& real, Score& s) {
  s.model_scored = true;
  std::vector<Step> model_steps;
  for (const Flight& f : model) model_steps.insert(model_steps.end(), f.steps.begin(), f.steps.end());
  const ModelMatch mm = match_model_steps(model_steps, real);
  s.model_steps_real = static_cast<int>(real.size());
  s.model_steps_detected = static_cast<int>(mm.matches.size());
  s.model_false_steps = static_cast<int>(model_steps.size() - mm.matches.size());
  s.model_step_offset = mm.offset_steps;
  Accumulator riser, tread;
  for (const StepMatch& m : mm.matches) {
    const Step& est = model_steps[m.detected];
    const Step& gt = real[m.real];
    if (est.riser_height_m && gt.riser_height_m) riser.add(100.0 * (*est.riser_height_m - *gt.riser_height_m));
    if (!gt.landing && est.tread_depth_m && gt.tread_depth_m) tread.add(100.0 * (*est.tread_depth_m - *gt.tread_depth_m));
  }
  s.riser_error_cm = riser.stats();
  s.tread_error_cm = tread.stats();
}

void finish_rates(const RunSums& sums, Score& s) {
  if (s.visible_steps > 0) s.frame_step_detection = double(s.frame_steps_matched) / s.visible_steps;
  if (s.visible_steps > 0 && s.tracked_scored)
    s.frame_step_detection_tracked = double(s.tracked_steps_matched) / s.visible_steps;
  if (s.visible_steps_nosing_in_view > 0)
    s.frame_step_detection_nosing_in_view = double(s.frame_steps_matched_nosing_in_view) / s.visible_steps_nosing_in_view;
  s.pitch_error_deg = sums.pitch.stats();
  s.roll_error_deg = sums.roll.stats();
  s.height_error_cm = sums.height.stats();
  s.height_error_beneath_visible_cm = sums.height_visible.stats();
  s.tracked_height_error_cm = sums.tracked_height.stats();
  s.tracked_position_error_cm = sums.tracked_position.stats();
  if (sums.frames_since_tracked > 0) s.tracked_camera_coverage = double(s.tracked_camera_frames) / sums.frames_since_tracked;
  if (s.tracked_beneath_frames > 0) s.tracked_step_index_accuracy = double(sums.tracked_right_step) / s.tracked_beneath_frames;
  s.tracked_base_height_error_cm = sums.tracked_base_height.stats();
  if (s.tracked_base_beneath_frames > 0)
    s.tracked_base_step_index_accuracy = double(sums.tracked_base_right_step) / s.tracked_base_beneath_frames;
}

}  // namespace

Score score_run(const std::vector<FrameResult>& frames, const std::vector<Flight>* model,
                const GroundTruth& truth, const MountConfig& mount) {
  Score s;
  const std::vector<Step> real = real_steps(truth);
  RunSums sums;
  for (const FrameResult& f : frames) {
    s.frames.emplace_back();
    if (!f.truth) continue;
    const GroundTruthFrame& gt = *f.truth;
    ++s.frames_scored;
    FrameScore& fs = s.frames.back().emplace();
    fs.pitch_deg = gt.pitch_deg;
    fs.roll_deg = gt.roll_deg;
    fs.height_m = gt.height_m;
    fs.true_step_index = true_step_beneath(gt, real);
    score_detections(f, gt, real, fs, s);
    score_tracked_camera(f, gt, real, fs, s, sums);
    score_tracked_base(f, gt, real, mount, fs, s, sums);
    score_pose(f, gt, real, s, sums);
  }
  finish_rates(sums, s);
  if (model) score_model(*model, real, s);
  s.latency_ms = latency_by_stage(frames);
  return s;
}

}  // namespace stairs::eval
