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
    if (p.z() < kMinDepth_m) return Probe::Undecided;
    const double u = column(p), v = K_.fy * p.y() / p.z() + K_.cy;
    if (u < 0 || v < 0 || u >= K_.width || v >= K_.height) return Probe::Undecided;
    const int gx = static_cast<int>(u) / g_.cell_px, gy = static_cast<int>(v) / g_.cell_px;
    // A cell its surface does not fill decides nothing: its pixels on the probed surface may be the
    // ones missing (grazing incidence), and its point the surface behind.
    if (gx >= g_.width || gy >= g_.height || !g_.filled[g_.index(gx, gy)]) return Probe::Undecided;
    const float z = g_.points[g_.index(gx, gy)].z();
    const float tol = c_.solid_tolerance_m + c_.solid_tolerance_per_m2 * p.z() * p.z();
    if (z > std::max(p.z(), known_beyond_m) + tol) return Probe::Through;
    return std::abs(z - p.z()) <= tol ? Probe::Solid : Probe::Undecided;
  }

  float depth(const Eigen::Vector3f& p_gravity) const { return (to_optical_ * p_gravity).z(); }

  // Pixel column of a gravity-frame point, or NaN behind the camera.
  double column_of(const Eigen::Vector3f& p_gravity) const {
    const Eigen::Vector3f p = to_optical_ * p_gravity;
    return p.z() > kMinDepth_m ? column(p) : std::nan("");
  }

 private:
  static constexpr float kMinDepth_m = 0.1f;  // nearer points project nowhere useful (behind or at the lens)
  double column(const Eigen::Vector3f& p_optical) const { return K_.fx * p_optical.x() / p_optical.z() + K_.cx; }

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
  const float t = ps.lateral(st.nosing_m);
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
  for (float lat : lateral_positions(f, c)) t.add(pr.at(ps.to_camera(f.s + c.probe_offset_m, lat, f.z)));
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
  float s = f.s - c.probe_offset_m;
  if (!up) {
    if (f.z >= 0) return t;
    s = f.s * z_lo / f.z + c.probe_offset_m;  // the ray over the nosing meets the lower level there
    if (s > next_s - c.probe_offset_m) return t;
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
    for (int i = 1; i <= c.end_probes; ++i) {
      const float ds = tread_m * static_cast<float>(i) / static_cast<float>(c.end_probes + 1);
      t.add(pr.at(ps.to_camera(up ? f.s + ds : f.s - ds, t_out, f.z)));
    }
    if (t.through < c.end_probes_through) return false;
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
  // Two values: their median is their mean, and each lies within `tolerance` of it up to twice the
  // tolerance apart; neither is the flight's, so both fail where they differ by more than it.
  const bool two_disagree = values.size() == 2 && std::abs(v[0] - v[1]) > tolerance;
  std::vector<std::pair<size_t, double>> off;
  for (const auto& [k, x] : values)
    if (std::abs(x - m) > tolerance || two_disagree) off.emplace_back(k, x - m);
  const int regular = static_cast<int>(values.size() - off.size());
  if (off.size() == 1 && regular >= regular_needed && std::abs(off[0].second) <= outlier) return;
  const std::string why = std::string(what) + " irregular vs. the median (m)";
  for (const auto& [k, d] : off) fail(k, why.c_str(), d);
}

float yaw_of(const Plane& p) { return std::atan2(-p.normal.y(), -p.normal.x()); }

// The checks over one hypothesis; a failing step truncates the verdict there.
class Verifier {
 public:
  Verifier(const NormalGrid& grid, const Intrinsics& K, const Eigen::Matrix3f& gravity, const PlaneSet& ps, bool up,
           std::vector<Step>& steps, const VerificationConfig& c)
      : pr_(grid, K, gravity, c), K_(K), ps_(ps), up_(up), steps_(steps), c_(c) {
    verdict_.kept = steps.size();
    for (const Step& st : steps) frames_.push_back(step_frame(ps, st));
  }

  // Flags the width partial unless the tread lies inside the image and ends in open space on both sides.
  void width_seen(size_t k) {
    const StepFrame& f = frames_[k];
    const float s = f.s + (up_ ? c_.probe_offset_m : -c_.probe_offset_m);
    const double lo = pr_.column_of(ps_.to_camera(s, f.t_lo, f.z)), hi = pr_.column_of(ps_.to_camera(s, f.t_hi, f.z));
    const float margin_px = c_.border_margin_px * K_.width / 640.0f;
    const bool in_image = std::min(lo, hi) > margin_px && std::max(lo, hi) < K_.width - margin_px;
    if (!in_image || !both_ends_open(pr_, ps_, f, up_, probe_depth(k), c_)) steps_[k].inferred |= kStepWidthPartial;
  }

  // riser_support, foot_support and the tread probes of `widths`: the surfaces a step is made of.
  void surfaces(size_t k) {
    const StepFrame& f = frames_[k];
    const auto fraction = [](const Tally& t) { return t.through / double(t.solid + t.through); };
    if (c_.riser_support && up_) {
      const Tally t = riser_probes(pr_, ps_, f, c_);
      if (t.refuted(c_)) fail(k, "seen through beneath the nosing: no riser", fraction(t));
    }
    if (c_.foot_support && !up_ && !f.rise_measured) {
      // Going down, a level whose riser below is unseen is no step where the
      // level runs on beyond its edge (a floor past a noisy depth jump).
      const Tally t = drop_probes(pr_, ps_, f, c_);
      if (t.solid + t.through >= c_.min_decided_probes && t.through * 2 < t.solid + t.through)
        fail(k, "the level runs on beyond its edge: no drop", fraction(t));
    }
    if (c_.foot_support) {
      const Tally t = foot_probes(pr_, ps_, f, up_, k + 1 < frames_.size() ? frames_[k + 1].s : 1e9f, c_);
      if (t.refuted(c_)) fail(k, "the level below does not reach the riser", fraction(t));
    }
    if (c_.widths) {
      const Tally t = tread_probes(pr_, ps_, f, up_, probe_depth(k), c_);
      if (t.refuted(c_)) fail(k, "seen through the tread across its width", fraction(t));
    }
  }

  // widths: consecutive treads overlap, and agree where the narrower one's width is its whole.
  void widths(size_t k) {
    if (!c_.widths || k == 0) return;
    const StepFrame &a = frames_[k - 1], &b = frames_[k];
    const float wa = a.t_hi - a.t_lo, wb = b.t_hi - b.t_lo, narrow = std::min(wa, wb), wide = std::max(wa, wb);
    const float overlap = std::min(a.t_hi, b.t_hi) - std::max(a.t_lo, b.t_lo);
    if (narrow > 0 && overlap < c_.min_lateral_overlap * narrow) fail(k, "treads do not overlap laterally", overlap);
    const bool narrow_cut = (wa <= wb ? steps_[k - 1].inferred : steps_[k].inferred) & kStepWidthPartial;
    if (!narrow_cut && narrow < c_.min_width_ratio * wide) fail(k, "tread widths disagree", narrow / wide);
  }

  // alignment: the segmented risers are parallel in plan view.
  void alignment() {
    if (!c_.alignment) return;
    const auto segmented = [&](const Step& st) {
      return st.riser_plane >= 0 && ps_.planes[st.riser_plane].source == PlaneSource::Segmented;
    };
    std::vector<double> yaws;
    for (const Step& st : steps_)
      if (segmented(st)) yaws.push_back(yaw_of(ps_.planes[st.riser_plane]));
    if (yaws.size() < 2) return;
    const double m = median(yaws), limit = c_.max_riser_yaw_spread_deg * M_PI / 180.0;
    for (size_t k = 0; k < steps_.size(); ++k) {
      const double d = segmented(steps_[k]) ? std::abs(yaw_of(ps_.planes[steps_[k].riser_plane]) - m) : 0.0;
      if (d > limit) fail(k, "riser not parallel to the others (deg)", d * 180.0 / M_PI);
    }
  }

  // regularity: measured rises and runs plausible and regular (inferred values take no part).
  void regularity(float max_rise_m) {
    if (!c_.regularity) return;
    std::vector<std::pair<size_t, double>> rises, runs;  // (step, measured value)
    for (size_t k = 0; k < steps_.size(); ++k) {
      const Step& st = steps_[k];
      if (st.riser_height_m && !(st.inferred & kStepRiserInferred)) {
        if (*st.riser_height_m > max_rise_m) fail(k, "rise too high to climb (m)", *st.riser_height_m);
        rises.emplace_back(k, *st.riser_height_m);
      }
      if (st.tread_depth_m && !st.landing && !(st.inferred & kStepTreadPartial)) {
        if (*st.tread_depth_m < c_.min_run_m) fail(k, "run too short to stand on (m)", *st.tread_depth_m);
        runs.emplace_back(k, *st.tread_depth_m);
      }
    }
    const auto f = [this](size_t k, const char* what, double value) { fail(k, what, value); };
    irregular(rises, c_.rise_tolerance_m, c_.rise_outlier_m, c_.regular_steps_for_an_outlier, "rise", f);
    if (runs.size() >= 2) irregular(runs, c_.run_tolerance_m, c_.run_outlier_m, c_.regular_steps_for_an_outlier, "run", f);
  }

  const Verdict& verdict() const { return verdict_; }

 private:
  // How far into the tread its probes reach: its measured depth, at most probe_depth_m.
  float probe_depth(size_t k) const {
    return static_cast<float>(std::min<double>(steps_[k].tread_depth_m.value_or(c_.probe_depth_m), c_.probe_depth_m));
  }
  // The nearest failing step keeps the verdict: it and every step beyond are dropped.
  void fail(size_t k, const char* what, double value) {
    if (k >= verdict_.kept) return;
    verdict_.kept = k;
    char buf[160];
    std::snprintf(buf, sizeof buf, "step %zu: %s (%.2f)", k + 1, what, value);
    verdict_.reason = buf;
  }

  const Prober pr_;
  const Intrinsics& K_;
  const PlaneSet& ps_;
  const bool up_;
  std::vector<Step>& steps_;
  const VerificationConfig& c_;
  std::vector<StepFrame> frames_;
  Verdict verdict_;
};

}  // namespace

Verdict verify(const NormalGrid& grid, const Intrinsics& K, const Eigen::Matrix3f& gravity, const PlaneSet& ps,
               Direction direction, std::vector<Step>& steps, const VerificationConfig& c, float max_rise_m) {
  Verifier v(grid, K, gravity, ps, direction == Direction::Up, steps, c);
  for (size_t k = 0; k < steps.size(); ++k) {
    v.width_seen(k);
    v.surfaces(k);
    v.widths(k);
  }
  v.alignment();
  v.regularity(max_rise_m);
  return v.verdict();
}

}  // namespace stairs
