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
  // The face may stand up to a nosing overhang behind the nosing: along the
  // ray that is as far as the probe's depth times (s + overhang) / s.
  const float behind = (f.s + c.max_nosing_overhang_m) / f.s;
  for (float lat : lateral_positions(f, c))
    for (int j = 0; j < c.vertical_samples; ++j) {
      const float z = z0 + span * (c.vertical_samples == 1 ? 0.5f : j / static_cast<float>(c.vertical_samples - 1));
      const Eigen::Vector3f p = ps.to_camera(f.s, lat, z);
      t.add(pr.at(p, pr.depth(p) * behind));
    }
  return t;
}

// The level continued past its far edge (going down): a drop shows beyond.
Tally drop_probes(const Prober& pr, const PlaneSet& ps, const StepFrame& f, const VerificationConfig& c) {
  Tally t;
  if (f.z >= 0) return t;
  for (float lat : lateral_positions(f, c)) t.add(pr.at(ps.to_camera(f.s + c.foot_offset_m, lat, f.z)));
  return t;
}

// A level seen this steeply from the camera (at s ahead, z below) decides a
// probe: at grazing incidence a centimetre of height error moves the ray's
// hit along the surface by more than the depth tolerance.
bool steep_enough(float s, float z, const VerificationConfig& c) {
  return z < 0 && -z >= s * std::tan(c.min_probe_elevation_deg * static_cast<float>(M_PI) / 180.0f);
}

// The tread is there across the width claimed for it: seen from above, the
// view beyond it means a gap (two arm rests of a sofa are no one tread).
Tally tread_probes(const Prober& pr, const PlaneSet& ps, const StepFrame& f, bool up, float tread_m,
                   const VerificationConfig& c) {
  Tally t;
  const float s = up ? f.s + 0.5f * tread_m : f.s - 0.5f * tread_m;
  if (tread_m <= 0 || !steep_enough(s, f.z, c)) return t;
  for (float lat : lateral_positions(f, c)) t.add(pr.at(ps.to_camera(s, lat, f.z)));
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
  if (s <= 0 || !steep_enough(s, z_lo, c)) return t;
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

// The median; of an even count the mean of the middle two (two rises that
// disagree are equally far from it).
double median(std::vector<double> v) {
  const size_t h = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + h, v.end());
  if (v.size() % 2) return v[h];
  return 0.5 * (v[h] + *std::max_element(v.begin(), v.begin() + h));
}

// Values farther than `tolerance` from their median fail, except one within
// `outlier` when at least `regular_needed` others agree: one odd step in an
// otherwise regular flight is a building's, two levels that disagree are no flight.
template <class Fail>
void irregular(const std::vector<std::pair<size_t, double>>& values, double tolerance, double outlier, int regular_needed,
               const char* what, const Fail& fail) {
  if (values.empty()) return;
  std::vector<double> v;
  for (const auto& kv : values) v.push_back(kv.second);
  const double m = median(v);
  std::vector<std::pair<size_t, double>> off;
  for (const auto& [k, x] : values)
    if (std::abs(x - m) > tolerance) off.emplace_back(k, x - m);
  const int regular = static_cast<int>(values.size() - off.size());
  if (off.size() == 1 && regular >= regular_needed && std::abs(off[0].second) <= outlier) return;
  const std::string why = std::string(what) + " irregular vs. the median (m)";
  for (const auto& [k, d] : off) fail(k, why.c_str(), d);
}

float yaw_of(const Plane& p) { return std::atan2(-p.normal.y(), -p.normal.x()); }

}  // namespace

Verdict verify(const NormalGrid& grid, const Intrinsics& K, const Eigen::Matrix3f& gravity, const PlaneSet& ps,
               Direction direction, std::vector<Step>& steps, const VerificationConfig& c, float max_rise_m) {
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
    if (c.foot_support && !up && !f.rise_measured) {
      // Going down, a level whose riser below is unseen is no step where the
      // level runs on beyond its edge (a floor past a noisy depth jump).
      const Tally t = drop_probes(pr, ps, f, c);
      if (t.solid + t.through >= c.min_decided_probes && t.through * 2 < t.solid + t.through)
        fail(k, "the level runs on beyond its edge: no drop", t.through / double(t.solid + t.through));
    }
    if (c.foot_support) {
      const float next_s = k + 1 < steps.size() ? frames[k + 1].s : 1e9f;
      const Tally t = foot_probes(pr, ps, f, up, next_s, c);
      if (t.refuted(c)) fail(k, "the level below does not reach the riser", t.through / double(t.solid + t.through));
    }
    if (c.widths) {
      const Tally t = tread_probes(pr, ps, f, up, static_cast<float>(tread_m), c);
      if (t.refuted(c)) fail(k, "seen through the tread across its width", t.through / double(t.solid + t.through));
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
    std::vector<std::pair<size_t, double>> rises, runs;  // (step, measured value)
    for (size_t k = 0; k < steps.size(); ++k) {
      const Step& st = steps[k];
      if (st.riser_height_m && !(st.inferred & kStepRiserInferred)) {
        if (*st.riser_height_m > max_rise_m) fail(k, "rise too high to climb (m)", *st.riser_height_m);
        rises.emplace_back(k, *st.riser_height_m);
      }
      if (st.tread_depth_m && !st.landing && !(st.inferred & kStepTreadPartial)) {
        if (*st.tread_depth_m < c.min_run_m) fail(k, "run too short to stand on (m)", *st.tread_depth_m);
        runs.emplace_back(k, *st.tread_depth_m);
      }
    }
    irregular(rises, c.rise_tolerance_m, c.rise_outlier_m, c.regular_steps_for_an_outlier, "rise", fail);
    if (runs.size() >= 2) irregular(runs, c.run_tolerance_m, c.run_outlier_m, c.regular_steps_for_an_outlier, "run", fail);
  }
  return v;
}

}  // namespace stairs
