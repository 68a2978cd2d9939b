#include "perception/verification.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace stairs {

namespace {

enum class Probe { Solid, Through, Undecided };

// What the depth image shows along the ray to a point of a hypothesised
// surface: that surface (Solid), something beyond it (Through: the surface is
// not there), or nothing that decides (occluded by a nearer surface, no depth,
// off the image).
class Prober {
 public:
  Prober(const NormalGrid& g, const Intrinsics& K, const Eigen::Matrix3f& gravity, const VerificationConfig& c)
      : g_(g), K_(K), to_optical_(gravity.transpose()), c_(c) {}

  // `known_beyond_m`: depth along the optical axis of a surface known to lie
  // behind the probe on its ray (a riser behind a tread's far end seen at a
  // grazing angle); seeing it is no view through.
  Probe at(const Eigen::Vector3f& p_gravity, float known_beyond_m = 0) const {
    const Eigen::Vector3f p = to_optical_ * p_gravity;
    if (p.z() < 0.1f) return Probe::Undecided;
    const double u = K_.fx * p.x() / p.z() + K_.cx, v = K_.fy * p.y() / p.z() + K_.cy;
    if (u < 0 || v < 0 || u >= K_.width || v >= K_.height) return Probe::Undecided;
    const int gx = static_cast<int>(u) / g_.cell_px, gy = static_cast<int>(v) / g_.cell_px;
    if (gx >= g_.width || gy >= g_.height || !g_.has_point[g_.index(gx, gy)]) return Probe::Undecided;
    const float z = g_.points[g_.index(gx, gy)].z();
    const float tol = c_.solid_tolerance_m + c_.solid_tolerance_per_m2 * p.z() * p.z();
    if (z > std::max(p.z(), known_beyond_m) + tol) return Probe::Through;
    return std::abs(z - p.z()) <= tol ? Probe::Solid : Probe::Undecided;
  }

  float depth(const Eigen::Vector3f& p_gravity) const { return (to_optical_ * p_gravity).z(); }

  // Pixel column of a gravity-frame point, or NaN behind the camera.
  double column(const Eigen::Vector3f& p_gravity) const {
    const Eigen::Vector3f p = to_optical_ * p_gravity;
    return p.z() > 0.1f ? K_.fx * p.x() / p.z() + K_.cx : std::nan("");
  }

 private:
  const NormalGrid& g_;
  const Intrinsics& K_;
  Eigen::Matrix3f to_optical_;
  const VerificationConfig& c_;
};

struct Tally {
  int solid = 0, through = 0;
  void add(Probe p) {
    solid += p == Probe::Solid;
    through += p == Probe::Through;
  }
  // Refuted: enough decided probes, and too many of them see beyond the surface.
  bool refuted(const VerificationConfig& c) const {
    const int decided = solid + through;
    return decided >= c.min_decided_probes && through > c.max_see_through * decided;
  }
};

// A step in the stair-aligned frame of the plane set.
struct StepFrame {
  float s = 0, t_lo = 0, t_hi = 0, z = 0, rise = 0;
  bool rise_measured = false;
};

StepFrame step_frame(const PlaneSet& ps, const Step& st) {
  const float c = std::cos(ps.yaw_rad), sn = std::sin(ps.yaw_rad);
  const float t = -sn * static_cast<float>(st.nosing_m.x()) + c * static_cast<float>(st.nosing_m.y());
  const float half = 0.5f * static_cast<float>(st.width_m);
  return {ps.axial(st.nosing_m), t - half, t + half, static_cast<float>(st.nosing_m.z()),
          st.riser_height_m ? static_cast<float>(*st.riser_height_m) : 0.0f,
          st.riser_height_m && !(st.inferred & kStepRiserInferred)};
}

// Lateral sample positions across the step, margins left out.
std::vector<float> lateral_positions(const StepFrame& f, const VerificationConfig& c) {
  std::vector<float> out;
  const float w = f.t_hi - f.t_lo, lo = f.t_lo + c.lateral_margin * w, span = (1 - 2 * c.lateral_margin) * w;
  for (int i = 0; i < c.lateral_samples; ++i)
    out.push_back(lo + span * (c.lateral_samples == 1 ? 0.5f : i / static_cast<float>(c.lateral_samples - 1)));
  return out;
}

// Going up the riser faces the camera: the middle of its face must be there,
// not a view through beneath the nosing (a chair seat, a table top).
Tally riser_probes(const Prober& pr, const PlaneSet& ps, const StepFrame& f, const VerificationConfig& c) {
  Tally t;
  if (f.s <= 0 || f.rise <= 0) return t;
  const float z0 = f.z - f.rise + c.vertical_margin * f.rise, span = (1 - 2 * c.vertical_margin) * f.rise;
  for (float lat : lateral_positions(f, c))
    for (int j = 0; j < c.vertical_samples; ++j) {
      const float z = z0 + span * (c.vertical_samples == 1 ? 0.5f : j / static_cast<float>(c.vertical_samples - 1));
      t.add(pr.at(ps.to_camera(f.s, lat, z)));
    }
  return t;
}

// The level a step stands on reaches its riser: going up, just in front of
// the riser's foot; going down, where the lower tread first shows beyond the
// nosing (its part under the nosing is hidden), before the next nosing.
Tally foot_probes(const Prober& pr, const PlaneSet& ps, const StepFrame& f, bool up, float next_s,
                  const VerificationConfig& c) {
  Tally t;
  const float z_lo = f.z - f.rise;
  if (!f.rise_measured || z_lo >= 0) return t;  // a level we saw, and the camera looks down on it
  float s = f.s - c.foot_offset_m;
  if (!up) {
    if (f.z >= 0) return t;
    s = f.s * z_lo / f.z + c.foot_offset_m;  // the ray over the nosing meets the lower level there
    if (s > next_s - c.foot_offset_m) return t;
  }
  if (s <= 0) return t;
  // Going up the ray over the foot may meet this step's riser behind it.
  const float to_riser = f.s / s;
  const bool riser_behind = up && z_lo * to_riser <= f.z;
  for (float lat : lateral_positions(f, c)) {
    const Eigen::Vector3f p = ps.to_camera(s, lat, z_lo);
    t.add(pr.at(p, riser_behind ? pr.depth(p) * to_riser : 0.0f));
  }
  return t;
}

// Whether both lateral ends of a tread are its real ends: just beyond each,
// at the tread's height, the view passes on to something farther (an open
// side, as of a chair seat). A wall, occlusion, no depth or the tread going on
// unsegmented leave the width seen a lower bound.
bool both_ends_open(const Prober& pr, const PlaneSet& ps, const StepFrame& f, bool up, float tread_m,
                    const VerificationConfig& c) {
  for (float side : {-1.0f, 1.0f}) {
    Tally t;
    const float t_out = (side < 0 ? f.t_lo : f.t_hi) + side * c.end_offset_m;
    for (int i = 1; i <= 3; ++i) {
      const float ds = tread_m * i / 4.0f;
      t.add(pr.at(ps.to_camera(up ? f.s + ds : f.s - ds, t_out, f.z)));
    }
    if (t.through < 2) return false;
  }
  return true;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

float yaw_of(const Plane& p) { return std::atan2(-p.normal.y(), -p.normal.x()); }

}  // namespace

Verdict verify(const NormalGrid& grid, const Intrinsics& K, const Eigen::Matrix3f& gravity, const PlaneSet& ps,
               Direction direction, std::vector<Step>& steps, const VerificationConfig& c) {
  Verdict v;
  v.kept = steps.size();
  if (steps.empty()) return v;
  char buf[160];
  const auto fail = [&](size_t k, const char* what, double value) {
    if (k >= v.kept) return;
    v.kept = k;
    std::snprintf(buf, sizeof buf, "step %zu: %s (%.2f)", k + 1, what, value);
    v.reason = buf;
  };
  const bool up = direction == Direction::Up;
  const Prober pr(grid, K, gravity, c);
  const float margin_px = c.border_margin_px * K.width / 640.0f;
  std::vector<StepFrame> frames;
  for (const Step& st : steps) frames.push_back(step_frame(ps, st));

  for (size_t k = 0; k < steps.size(); ++k) {
    const StepFrame& f = frames[k];
    // Cut by the image border: the width seen is a lower bound.
    const float s_probe = f.s + (up ? 0.05f : -0.05f);
    const double lo = pr.column(ps.to_camera(s_probe, f.t_lo, f.z)), hi = pr.column(ps.to_camera(s_probe, f.t_hi, f.z));
    const bool in_image = std::min(lo, hi) > margin_px && std::max(lo, hi) < K.width - margin_px;
    const float tread_m = std::min(steps[k].tread_depth_m.value_or(0.2), 0.3);
    if (!in_image || !both_ends_open(pr, ps, f, up, static_cast<float>(tread_m), c))
      steps[k].inferred |= kStepWidthPartial;
    if (c.riser_support && up) {
      const Tally t = riser_probes(pr, ps, f, c);
      if (t.refuted(c)) fail(k, "seen through beneath the nosing: no riser", t.through / double(t.solid + t.through));
    }
    if (c.foot_support) {
      const float next_s = k + 1 < steps.size() ? frames[k + 1].s : 1e9f;
      const Tally t = foot_probes(pr, ps, f, up, next_s, c);
      if (t.refuted(c)) fail(k, "the level below does not reach the riser", t.through / double(t.solid + t.through));
    }
    if (c.widths && k > 0) {
      const StepFrame& a = frames[k - 1];
      const float wa = a.t_hi - a.t_lo, wb = f.t_hi - f.t_lo, narrow = std::min(wa, wb);
      const float overlap = std::min(a.t_hi, f.t_hi) - std::max(a.t_lo, f.t_lo);
      if (narrow > 0 && overlap < c.min_lateral_overlap * narrow) fail(k, "treads do not overlap laterally", overlap);
      const bool narrow_cut = (wa <= wb ? steps[k - 1].inferred : steps[k].inferred) & kStepWidthPartial;
      if (!narrow_cut && narrow < c.min_width_ratio * std::max(wa, wb))
        fail(k, "tread widths disagree", narrow / std::max(wa, wb));
    }
  }
  if (c.alignment) {
    std::vector<double> yaws;
    for (const Step& st : steps)
      if (st.riser_plane >= 0 && ps.planes[st.riser_plane].source == PlaneSource::Segmented)
        yaws.push_back(yaw_of(ps.planes[st.riser_plane]));
    if (yaws.size() >= 2) {
      const double m = median(yaws), limit = c.max_riser_yaw_spread_deg * M_PI / 180.0;
      for (size_t k = 0; k < steps.size(); ++k)
        if (steps[k].riser_plane >= 0 && ps.planes[steps[k].riser_plane].source == PlaneSource::Segmented) {
          const double d = std::abs(yaw_of(ps.planes[steps[k].riser_plane]) - m);
          if (d > limit) fail(k, "riser not parallel to the others (deg)", d * 180.0 / M_PI);
        }
    }
  }
  if (c.regularity) {
    std::vector<double> rises, runs;
    for (const Step& st : steps) {
      if (st.riser_height_m && !(st.inferred & kStepRiserInferred)) rises.push_back(*st.riser_height_m);
      if (st.tread_depth_m && !st.landing && !(st.inferred & kStepTreadPartial)) runs.push_back(*st.tread_depth_m);
    }
    const double mr = rises.empty() ? 0 : median(rises), mt = runs.empty() ? 0 : median(runs);
    for (size_t k = 0; k < steps.size(); ++k) {
      const Step& st = steps[k];
      if (!rises.empty() && st.riser_height_m && !(st.inferred & kStepRiserInferred) &&
          std::abs(*st.riser_height_m - mr) > c.rise_tolerance_m)
        fail(k, "rise irregular vs. the median (m)", *st.riser_height_m - mr);
      const bool run_measured = st.tread_depth_m && !st.landing && !(st.inferred & kStepTreadPartial);
      if (run_measured && *st.tread_depth_m < c.min_run_m) fail(k, "run too short to stand on (m)", *st.tread_depth_m);
      if (runs.size() >= 2 && run_measured && std::abs(*st.tread_depth_m - mt) > c.run_tolerance_m)
        fail(k, "run irregular vs. the median (m)", *st.tread_depth_m - mt);
    }
  }
  return v;
}

}  // namespace stairs
