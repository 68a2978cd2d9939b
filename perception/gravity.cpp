#include "perception/gravity.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <vector>

namespace stairs {

namespace {

struct Family {
  Eigen::Vector3f normal;  // support-weighted mean: large planes have the best-determined normals
  float support;           // cells
};

// The best-supported family of parallel segment normals around the segments `keep` accepts.
template <class Keep>
std::optional<Family> best_family(const std::vector<Segment>& segments, float cos_par, Keep keep) {
  Eigen::Vector3f best = Eigen::Vector3f::Zero();
  float best_support = 0;
  for (const Segment& c : segments) {
    if (c.bent || !keep(c)) continue;
    Eigen::Vector3f sum = Eigen::Vector3f::Zero();
    float support = 0;
    for (const Segment& s : segments)
      if (!s.bent && s.normal.dot(c.normal) > cos_par) {
        sum += static_cast<float>(s.cells.size()) * s.normal;
        support += static_cast<float>(s.cells.size());
      }
    if (support > best_support) {
      best = sum;
      best_support = support;
    }
  }
  if (best_support == 0.0f) return std::nullopt;
  return Family{best.normalized(), best_support};
}

// How well a least-squares plane knows its tilt towards in-plane axis k (1 / variance): the noise
// of its cells averages, rms^2 / (cells * spread). With `resolved`, also what does not average: the
// depth's resolution at its range (structured light and stereo quantise disparity; a far tread
// seen edge-on is a few terraces) knows a tilt across an extent L to resolution / L at best,
// L^2 = 12 * spread for an even spread. A K1 tread sliver at 4.3 m, 227 cells 30 cm deep, knew its
// tilt to 1.2 degrees by its noise and was 2.2 off.
double information_along(const Segment& s, int k, const GravityConfig& cfg, bool resolved = false) {
  const double z = s.centroid.z();
  const double resolution = std::max(static_cast<double>(cfg.fit_rms_floor_m), cfg.fit_rms_floor_per_m2 * z * z);
  const double rms = std::max(static_cast<double>(s.rms_m), resolution);
  const double systematic = resolved ? resolution * resolution / 12.0 : 0.0;
  return static_cast<double>(s.spread_m2[k]) / (rms * rms / static_cast<double>(s.cells.size()) + systematic);
}

// How well a plane's fit knows its normal in its worst direction (across its
// narrower in-plane axis). A thin strip or a riser cut at a nosing knows its
// normal poorly however many cells it has.
double information(const Segment& s, const GravityConfig& cfg, bool resolved = false) {
  return std::min(information_along(s, 0, cfg, resolved), information_along(s, 1, cfg, resolved));
}

// The information (1 / variance of a tilt) that knows up to within consensus_deg.
double consensus_information(const GravityConfig& cfg) {
  const double sin_agree = std::sin(cfg.consensus_deg * M_PI / 180.0);
  return 1.0 / (sin_agree * sin_agree);
}

// A plane whose fit knows its normal only to worse than consensus_deg cannot
// refine an up to within it: a far tread seen as a sliver, its tilt across it
// set by depth noise.
bool knows_normal_within_consensus(const Segment& s, const GravityConfig& cfg, bool resolved = false) {
  return information(s, cfg, resolved) >= consensus_information(cfg);
}

// What the horizontal planes within tol_deg of `up` know of its tilt: up is
// perpendicular to each plane's in-plane axes, each constraint weighted by how
// well the plane's fit knows it (information_along: a thin strip's tilt
// across it is poorly known, a large flat floor's well; `resolved`: as well as the depth's
// resolution at its range lets it). Planes that know their
// normal to worse than consensus_deg take no part. Zero without any.
Eigen::Matrix3d tilt_information(const std::vector<Segment>& segments, const Eigen::Vector3f& up, float tol_deg,
                                 const GravityConfig& cfg, bool resolved = false) {
  const float cos_tol = std::cos(tol_deg * static_cast<float>(M_PI) / 180.0f);
  Eigen::Matrix3d info = Eigen::Matrix3d::Zero();
  for (const Segment& s : segments) {
    if (s.bent || s.normal.dot(up) < cos_tol) continue;
    if (!knows_normal_within_consensus(s, cfg)) continue;
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector3d e = s.axis[k].cast<double>();
      info += information_along(s, k, cfg, resolved) * e * e.transpose();
    }
  }
  return info;
}

// The up that the horizontal planes within tol_deg of `up` fit best (tilt_information).
// Directions the planes constrain less than cfg.refine_prior_fraction of their
// total keep `up`. Without planes near it, `up` itself.
Eigen::Vector3f fit_up(const std::vector<Segment>& segments, const Eigen::Vector3f& up, float tol_deg,
                       const GravityConfig& cfg) {
  Eigen::Matrix3d info = tilt_information(segments, up, tol_deg, cfg);
  if (!(info.trace() > 0.0)) return up;
  const Eigen::Vector3d u0 = up.cast<double>();
  info += cfg.refine_prior_fraction * info.trace() * (Eigen::Matrix3d::Identity() - u0 * u0.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(info);
  Eigen::Vector3d u = es.eigenvectors().col(0).normalized();
  if (u.dot(u0) < 0) u = -u;
  return u.cast<float>();
}

// fit_up twice: the planes near the consensus up (wide enough for the treads
// when up came from walls and risers), then those near that fit.
Eigen::Vector3f refine(const std::vector<Segment>& segments, const Eigen::Vector3f& up, const GravityConfig& cfg) {
  return fit_up(segments, fit_up(segments, up, cfg.refine_first_deg, cfg), cfg.consensus_deg, cfg);
}

// How much the planes agree with `u`: the information (how well each knows its normal) of the
// segments parallel or perpendicular to it within cfg.consensus_deg. A face perpendicular to u and
// no taller than a rise (riser_max_height_m) argues for u no more than riser_lean_deg lets it,
// however well its fit knows its normal: a riser may lean by design (DIN 18065's undercut as an
// inclined riser), the front of its nosing is part of its fit and a time-of-flight camera bends its
// foot, none of which the fit's noise shows, while treads are level and walls plumb by construction
// (a level Kinect v2's risers 2.8-4 m off leaned 2.4-5.2 deg, each known to 1 deg by its noise, and
// set the pitch 4-6 deg off against four treads that agreed to 0.3 deg).
double agreement(const std::vector<Segment>& segments, const Eigen::Vector3f& u, const GravityConfig& cfg) {
  const float sin_agree = std::sin(cfg.consensus_deg * static_cast<float>(M_PI) / 180.0f);
  const float cos_agree = std::sqrt(1.0f - sin_agree * sin_agree);
  const double sin_lean = std::sin(cfg.riser_lean_deg * M_PI / 180.0);
  const double lean_information = 1.0 / (sin_lean * sin_lean);
  double sc = 0.0;
  for (const Segment& s : segments) {
    if (s.bent) continue;
    const float c = std::abs(s.normal.dot(u));
    if (c >= cos_agree)
      sc += information(s, cfg);
    else if (c <= sin_agree)
      sc += s.size_along_m(u) <= cfg.riser_max_height_m ? std::min(information(s, cfg), lean_information)
                                                           : information(s, cfg);
  }
  return sc;
}

// Up as most planes agree on it: horizontal segments parallel to it, vertical
// ones (risers, walls) perpendicular. Each candidate (the family's mean and
// the segments `candidate` accepts) is scored by the cells of the segments
// within cfg.consensus_deg of agreeing with it; up is then fitted to the
// horizontal segments near the best one (refine). The family's mean alone is pulled by a
// plane that is bent as a whole, and a large bent one can be the family (a
// floor or tread in a time-of-flight sensor's multipath band; thesis 3.5
// averages the family).
template <class Candidate>
Eigen::Vector3f consensus_up(const std::vector<Segment>& segments, const Eigen::Vector3f& family_up,
                             const GravityConfig& cfg, Candidate candidate) {
  const float sin_agree = std::sin(cfg.consensus_deg * static_cast<float>(M_PI) / 180.0f);
  const float cos_agree = std::sqrt(1.0f - sin_agree * sin_agree);
  auto score = [&](const Eigen::Vector3f& u) { return agreement(segments, u, cfg); };
  Eigen::Vector3f best = family_up;
  double best_score = score(family_up);
  // A candidate wins only by a margin that knows up to within consensus_deg:
  // walls agree with every up along them, so far slivers beside them would
  // otherwise set pitch on a few hundredths of the walls' information.
  const double min_margin = consensus_information(cfg);
  for (const Segment& c : segments) {
    if (c.bent || !candidate(c.normal)) continue;
    const double sc = score(c.normal);
    if (sc > best_score + min_margin) best_score = sc, best = c.normal;
  }
  // Fitted to the horizontal segments that agree with it, starting from their
  // support-weighted mean (vertical ones choose, they do not average: risers'
  // normals are the noisier, bent at both of their edges).
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  for (const Segment& s : segments)
    if (!s.bent && s.normal.dot(best) >= cos_agree) sum += static_cast<float>(s.cells.size()) * s.normal;
  return refine(segments, sum.squaredNorm() > 0.0f ? sum.normalized() : best, cfg);
}

// Whether this frame's horizontal planes near `up` measure its tilt along the
// horizontal direction `d` to within consensus_deg, their depth's resolution counted: far treads
// alone do not (their pitch is then carried, gravity.carry_max_s at most).
bool tilt_measured_along(const std::vector<Segment>& segments, const Eigen::Vector3f& up, const Eigen::Vector3f& d,
                         const GravityConfig& cfg) {
  const Eigen::Vector3d dd = d.cast<double>();
  return dd.dot(tilt_information(segments, up, cfg.refine_first_deg, cfg, true) * dd) >= consensus_information(cfg);
}

}  // namespace

std::optional<Eigen::Vector3f> estimate_up(const std::vector<Segment>& segments, const GravityConfig& cfg,
                                           const std::optional<Eigen::Vector3f>& prior, bool* carried,
                                           double prior_information) {
  if (carried) *carried = false;
  const float deg = static_cast<float>(M_PI) / 180.0f;
  const float cos_tilt = std::cos(cfg.max_tilt_from_image_up_deg * deg);
  const float cos_par = std::cos(cfg.parallel_deg * deg);
  const float cos_prior = std::cos(cfg.prior_max_deg * deg);
  const Eigen::Vector3f image_up(0, -1, 0);
  // Treads and risers both qualify on a stair; the previous frame's up tells
  // them apart when the risers dominate (a robot looking up a flight). With it,
  // nearness to it alone: a camera looking straight down (a robot tipping over
  // a nosing, 88 deg down) sees the treads face-on, more than
  // max_tilt_from_image_up_deg from image up, and had kept the previous pitch.
  auto near_up = [&](const Eigen::Vector3f& n) {
    return prior ? n.dot(*prior) >= cos_prior : n.dot(image_up) >= cos_tilt;
  };
  const auto horizontal = best_family(segments, cos_par, [&](const Segment& s) { return near_up(s.normal); });
  // Without a prior only the family's members may stand for up (a riser seen
  // from below is near image up too, and agrees with the treads as well as they
  // with it); with one, every plane near it may.
  if (!prior) {
    if (!horizontal) return std::nullopt;
    return consensus_up(segments, horizontal->normal, cfg, [&](const Eigen::Vector3f& n) {
      return near_up(n) && n.dot(horizontal->normal) >= cos_par;
    });
  }
  // Vertical planes (risers, walls) fix up too, perpendicular to their
  // normals: used when the treads near the prior are missing or too small to
  // trust beside them (a robot looking up a flight sees thin treads, if any).
  // A family stands on a plane that knows its normal to within consensus_deg: up is perpendicular
  // to it, and a second family's normal sets up's tilt outright (a 38-cell patch 4.5 m off with 1 cm
  // rms, crossed with a descent's side walls, set the pitch 12 degrees off and made six steps of the
  // near landing).
  const float sin_prior = std::sin(cfg.prior_max_deg * deg);
  auto vertical = [&](const Segment& s) {
    return std::abs(s.normal.dot(*prior)) < sin_prior && knows_normal_within_consensus(s, cfg);
  };
  // The largest vertical family and the largest one distinct from it: up perpendicular to both (or,
  // with one, to it, nearest the prior), if near the prior.
  const float cos_distinct = std::cos(cfg.second_family_min_angle_deg * deg);
  struct Vertical {
    std::optional<Family> v1;
    std::optional<Eigen::Vector3f> up;  // perpendicular to the vertical families, else nothing
    bool two_families = false;          // a second one: up is their cross product
  };
  auto vertical_families = [&](auto keep) {
    Vertical v;
    v.v1 = best_family(segments, cos_par, keep);
    if (!v.v1) return v;
    const auto v2 = best_family(segments, cos_par, [&](const Segment& s) {
      return keep(s) && std::abs(s.normal.dot(v.v1->normal)) < cos_distinct;
    });
    v.two_families = v2.has_value();
    Eigen::Vector3f u = v2 ? v.v1->normal.cross(v2->normal) : *prior - prior->dot(v.v1->normal) * v.v1->normal;
    if (u.dot(*prior) < 0) u = -u;
    u.normalize();
    if (u.dot(*prior) >= cos_prior) v.up = u;
    return v;
  };
  Vertical chosen = vertical_families(vertical);
  // Walls are plumb by construction, faces no taller than a rise need not be (riser_lean_deg): where
  // two families of walls fix up and agree with more than the largest families do, they stand for it.
  // A Kinect v2 robot on a flight, its risers 0.6-1.5 m off leaning 4-11 deg (multipath at their feet,
  // the nosing's front in their fit) and outnumbering a side wall and the landing's end wall, had its
  // pitch set 5-7 deg off by risers x side wall, and every rise came out 3 cm short. A wall must know
  // its normal as well as the depth's resolution at its range lets it (a D435's faces 4.9 m off, 2 cm
  // rms, leaned 8 deg).
  const Vertical walls = vertical_families([&](const Segment& s) {
    return vertical(s) && s.size_along_m(*prior) > cfg.riser_max_height_m && knows_normal_within_consensus(s, cfg, true);
  });
  if (walls.two_families && walls.up &&
      (!chosen.up || agreement(segments, *walls.up, cfg) > agreement(segments, *chosen.up, cfg)))
    chosen = walls;
  const auto& v1 = chosen.v1;
  const std::optional<Eigen::Vector3f>& vertical_up = chosen.up;
  const bool two_families = chosen.two_families;
  // The treads propose where they are large enough beside the walls and risers, unless those
  // agree with an up of their own by more than the treads' (a floor strip inside a time-of-flight
  // camera's multipath band, bent as a whole 8 degrees, set the pitch against every riser in view).
  if (horizontal && (!v1 || horizontal->support >= cfg.min_support_fraction * v1->support)) {
    const Eigen::Vector3f h = consensus_up(segments, horizontal->normal, cfg, near_up);
    if (!vertical_up ||
        agreement(segments, *vertical_up, cfg) <= agreement(segments, h, cfg) + consensus_information(cfg))
      return h;
  }
  if (!vertical_up) return std::nullopt;
  const Eigen::Vector3f up = *vertical_up;
  // Walls and risers propose; a tread too small to outweigh them may still be
  // the up more planes agree with (risers' normals are bent at both of their
  // edges, and a wall says nothing of pitch along it), and treads then fit it
  // where they agree (a level camera's far treads and floor: walls and risers,
  // noisy at 3 m, set it off by a degree or two).
  const Eigen::Vector3f fitted = consensus_up(segments, up, cfg, near_up);
  if (two_families) return fitted;
  // One vertical family fixes up only across its planes; along them up is the
  // previous frame's unless this frame's treads measure it: carried. Only a
  // pitch counts (the tilt along the view, where a flight is measured): an
  // error e there changes each rise by run * tan(e), 0.7 cm a degree on a 0.4 m
  // run; one across the view only what lies side by side.
  // A carried pitch is the prior's, weighed against what this frame's planes know of it: a tread
  // sliver that cannot measure it must not set it either (a level camera's landing-edge strip, 1.4 cm
  // of it, set it 3 degrees off, and a descent's first three frames measured every rise 1.5 cm short).
  Eigen::Vector3f along = fitted.cross(v1->normal);
  const Eigen::Vector3f forward = Eigen::Vector3f::UnitZ() - fitted.z() * fitted;  // optical axis, levelled
  bool pitch_carried = false;
  if (along.norm() > 0.0f && forward.norm() > 0.0f) {
    along.normalize();
    const bool pitch = std::abs(along.dot(forward.normalized())) >= std::sqrt(0.5f);
    pitch_carried = pitch && !tilt_measured_along(segments, fitted, along, cfg);
  }
  if (carried) *carried = pitch_carried;
  if (!pitch_carried) return fitted;
  // What the planes do know of the pitch weighs against the prior's, which wanders while unmeasured
  // (a level Kinect v1 descent's slivers followed a camera tilting 6.5 deg/s to within 0.7 degrees).
  const Eigen::Vector3d a = along.cast<double>();
  const double measured = a.dot(tilt_information(segments, fitted, cfg.refine_first_deg, cfg, true) * a);
  const double w = std::isinf(prior_information) ? 0.0 : measured / (measured + prior_information);
  const Eigen::Vector3f axis = up.cross(fitted);
  if (!(w > 0.0) || axis.norm() < 1e-9f) return up;
  const float angle = std::atan2(axis.norm(), up.dot(fitted));
  return (Eigen::AngleAxisf(static_cast<float>(w) * angle, axis.normalized()) * up).normalized();
}

CameraPose pose_from_up(const Eigen::Vector3f& up_optical) {
  const Eigen::Vector3d up = up_optical.cast<double>().normalized();
  CameraPose pose;
  pose.valid = true;
  pose.pitch_deg = std::asin(std::clamp(up.z(), -1.0, 1.0)) * 180.0 / M_PI;
  pose.roll_deg = std::atan2(-up.x(), -up.y()) * 180.0 / M_PI;
  // Forward = optical axis levelled; within ~6 deg of straight down (a levelled
  // axis shorter than sin 6 deg has no reliable heading), the image top.
  constexpr double kMinLevelledAxis = 0.1;
  Eigen::Vector3d fwd = Eigen::Vector3d::UnitZ() - up.z() * up;
  if (fwd.norm() < kMinLevelledAxis) fwd = -Eigen::Vector3d::UnitY() + up.y() * up;
  fwd.normalize();
  Eigen::Matrix3d R;
  R.row(0) = fwd.transpose();
  R.row(1) = up.cross(fwd).transpose();
  R.row(2) = up.transpose();
  pose.gravity_rotation = Eigen::Quaterniond(R).normalized();
  return pose;
}

}  // namespace stairs
