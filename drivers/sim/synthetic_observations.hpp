// Hand-built observations of a known staircase for the tracker's unit tests and
// benchmark: what perception would report from a camera walking the stair, with
// realistic partial visibility (field of view, range, occlusion by nosings,
// risers hidden when descending) and depth-dependent noise. Ground truth comes
// from the same geometry.
#pragma once

#include "common/types.hpp"

#include <cmath>
#include <random>
#include <utility>
#include <vector>

namespace stairs::synthetic {

struct StairGeometry {
  std::vector<double> riser_m, tread_m;  // per step, bottom to top (last tread = top landing)
  double width_m = 1.0;
  bool end_wall = false;  // a wall stands where the top landing ends (its tread depth beyond its nosing)
  double floor_depth_m = 0.0;  // m; the floor before the first riser as deep as this is reported (0: none)
  // Nosing of step i in the stair frame: (x, z).
  double nosing_x(size_t i) const {
    double x = 0;
    for (size_t k = 0; k < i; ++k) x += tread_m[k];
    return x;
  }
  double nosing_z(size_t i) const {
    double z = 0;
    for (size_t k = 0; k <= i; ++k) z += riser_m[k];
    return z;
  }
  // Height of the surface beneath stair-frame x.
  double surface_z(double x) const {
    double z = 0;
    for (size_t i = 0; i < riser_m.size() && x >= nosing_x(i); ++i) z = nosing_z(i);
    return z;
  }
};

// n steps of riser x tread; a mid landing after `landing_after` (>= 0) when given.
inline StairGeometry make_stair(int n, double riser, double tread, double top_landing, int landing_after = -1,
                                double mid_landing = 1.2) {
  StairGeometry g;
  for (int i = 0; i < n; ++i) {
    g.riser_m.push_back(riser + 0.002 * ((i * 7) % 3 - 1));  // real stairs are not perfectly regular
    g.tread_m.push_back(i == n - 1 ? top_landing : i == landing_after ? mid_landing : tread);
  }
  return g;
}

struct CameraState {
  Eigen::Vector3d position_m;  // stair frame
  double heading_rad;          // direction the camera faces, about z
  double pitch_rad = -0.6;
};

struct Noise {
  double plane_sigma_at_1m = 0.002;  // m, grows with the square of the distance
  double nosing_sigma_m = 0.008;
  double riser_sigma_m = 0.004;
  double tilt_sigma_deg = 0.3;  // per-frame error of perception's gravity estimate (pitch and roll)
};

class ObservationMaker {
 public:
  ObservationMaker(StairGeometry g, uint64_t seed, int points_per_plane = 400, Noise noise = {})
      : g_(std::move(g)), rng_(seed), points_(points_per_plane), noise_(noise) {}

  Observation make(const CameraState& cam, int64_t utime) {
    Observation obs;
    obs.source_utime = utime;
    obs.camera.valid = true;
    obs.camera.pitch_deg = cam.pitch_rad * 180 / M_PI;
    obs.camera.height_m = cam.position_m.z() - g_.surface_z(cam.position_m.x());
    // optical (x right, y down, z forward) -> gravity-aligned (x forward, y left, z up), pitched down.
    Eigen::Matrix3d base;
    base << 0, 0, 1, -1, 0, 0, 0, -1, 0;
    obs.camera.gravity_rotation = Eigen::Quaterniond(Eigen::AngleAxisd(-cam.pitch_rad, Eigen::Vector3d::UnitY()) * base);
    const bool descending = std::cos(cam.heading_rad) < 0;
    obs.direction = descending ? Direction::Down : Direction::Up;
    const Eigen::Matrix3d to_cam = Eigen::AngleAxisd(-cam.heading_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    auto to_g = [&](const Eigen::Vector3d& s) { return Eigen::Vector3d(to_cam * (s - cam.position_m)); };

    std::vector<Step> steps;
    for (size_t i = 0; i < g_.riser_m.size(); ++i) {
      const double X = g_.nosing_x(i), Z = g_.nosing_z(i), R = g_.riser_m[i], T = g_.tread_m[i];
      const double ahead = std::abs(X - cam.position_m.x());
      if (!in_front(X, cam, descending) || ahead > 3.5 || Z > cam.position_m.z() - 0.3) continue;
      const auto [y_lo, y_hi] = seen_across(cam, ahead);
      if (y_hi - y_lo < 0.2) continue;
      Step s;
      s.nosing_m = to_g(Eigen::Vector3d(X, 0.5 * (y_lo + y_hi), Z)) + gauss3(noise_.nosing_sigma_m);
      s.riser_height_m = R + gauss(noise_.riser_sigma_m);
      s.width_m = y_hi - y_lo;
      // Tread: from the nosing to the next riser, less what the next nosing hides when descending.
      double x_far = X + std::min(T, 2.5);
      if (descending && i + 1 < g_.riser_m.size()) {
        const double Xn = g_.nosing_x(i + 1), Zn = g_.nosing_z(i + 1);
        x_far = std::min(x_far, Xn - (cam.position_m.x() - Xn) * (Zn - Z) / (cam.position_m.z() - Zn));
      }
      if (x_far - X > 0.05) {
        s.tread_plane = static_cast<int>(obs.planes.size());
        obs.planes.push_back(plane(PlaneKind::Tread, Eigen::Vector3d(X, y_hi, Z), Eigen::Vector3d(x_far - X, 0, 0),
                                   y_hi - y_lo, cam.position_m, to_cam));
        s.tread_depth_m = x_far - X;
        if (x_far < X + T) s.inferred |= kStepTreadPartial;  // as perception flags a cut tread
      }
      if (!descending) {
        s.riser_plane = static_cast<int>(obs.planes.size());
        obs.planes.push_back(plane(PlaneKind::Riser, Eigen::Vector3d(X, y_hi, Z - R), Eigen::Vector3d(0, 0, R),
                                   y_hi - y_lo, cam.position_m, to_cam));
      }
      steps.push_back(s);
    }
    // Nearest first; perception reports no stair below two steps, and then no plane of one.
    if (descending) std::reverse(steps.begin(), steps.end());
    // The floor before the first riser, a plane no step owns; going down, its near part is hidden
    // behind the first step's nosing.
    if (g_.floor_depth_m > 0.0 && !steps.empty()) {
      const double X = g_.nosing_x(0), Z = g_.nosing_z(0), ahead = std::abs(X - cam.position_m.x());
      const double near = descending ? X - (cam.position_m.x() - X) * Z / (cam.position_m.z() - Z) : X;
      const auto [y_lo, y_hi] = seen_across(cam, ahead);
      if (in_front(X, cam, descending) && ahead < 3.5 && near - (X - g_.floor_depth_m) > 0.05 && y_hi - y_lo > 0.2)
        obs.planes.push_back(plane(PlaneKind::Landing, Eigen::Vector3d(X - g_.floor_depth_m, y_hi, 0.0),
                                   Eigen::Vector3d(near - (X - g_.floor_depth_m), 0, 0), y_hi - y_lo, cam.position_m,
                                   to_cam));
    }
    if (steps.size() < 2) {
      obs.planes.clear();
      steps.clear();
    }
    // The end wall, facing down the flight: a plane no step owns, reported with or without steps.
    if (g_.end_wall && !descending) {
      const size_t top = g_.riser_m.size() - 1;
      const double X = g_.nosing_x(top) + g_.tread_m[top], ahead = X - cam.position_m.x();
      const auto [y_lo, y_hi] = seen_across(cam, ahead);
      if (ahead > 0.5 && ahead < 3.5 && y_hi - y_lo > 0.2)
        obs.planes.push_back(plane(PlaneKind::Riser, Eigen::Vector3d(X, y_hi, g_.nosing_z(top)),
                                   Eigen::Vector3d(0, 0, 1.2), y_hi - y_lo, cam.position_m, to_cam));
    }
    tilt(obs, steps);
    obs.steps = steps;
    return obs;
  }

 private:
  // Whether stair-frame x is in front of the camera far enough for a step there to be reported.
  static bool in_front(double x, const CameraState& cam, bool descending) {
    return descending ? x < cam.position_m.x() - 0.3 : x > cam.position_m.x() + 0.5;
  }
  // The part of the stair's width in the lateral field of view (+-28 deg) `ahead` metres on.
  std::pair<double, double> seen_across(const CameraState& cam, double ahead) const {
    const double half_fov = ahead * std::tan(28 * M_PI / 180);
    return {std::max(-0.5 * g_.width_m, cam.position_m.y() - half_fov),
            std::min(0.5 * g_.width_m, cam.position_m.y() + half_fov)};
  }

  // Perception's gravity estimate is off by a small random tilt each frame.
  void tilt(Observation& obs, std::vector<Step>& steps) {
    const double deg = M_PI / 180;
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(gauss(noise_.tilt_sigma_deg) * deg, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(gauss(noise_.tilt_sigma_deg) * deg, Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
    const Eigen::Matrix3f Rf = R.cast<float>();
    for (auto& s : steps) s.nosing_m = R * s.nosing_m;
    for (auto& p : obs.planes) {
      p.normal = Rf * p.normal;
      p.centroid = Rf * p.centroid;
      for (auto& c : p.corners) c = Rf * c;
      for (auto& q : p.points) q = Rf * q;
    }
  }

  double gauss(double sigma) { return std::normal_distribution<double>(0.0, sigma)(rng_); }
  Eigen::Vector3d gauss3(double sigma) { return Eigen::Vector3d(gauss(sigma), gauss(sigma), gauss(sigma)); }

  // A rectangle from its bottom-left corner (stair frame), `up` = its depth or height.
  Plane plane(PlaneKind kind, const Eigen::Vector3d& bottom_left, const Eigen::Vector3d& up, double width,
              const Eigen::Vector3d& cam, const Eigen::Matrix3d& to_cam) {
    auto to_g = [&](const Eigen::Vector3d& s) { return Eigen::Vector3d(to_cam * (s - cam)); };
    Plane p;
    p.kind = kind;
    const Eigen::Vector3d right(0, -width, 0);
    const Eigen::Vector3d n_stair = kind == PlaneKind::Riser ? Eigen::Vector3d(-1, 0, 0) : Eigen::Vector3d(0, 0, 1);
    p.normal = (to_cam * n_stair).cast<float>();
    p.corners[Plane::kBottomLeft] = to_g(bottom_left).cast<float>();
    p.corners[Plane::kBottomRight] = to_g(bottom_left + right).cast<float>();
    p.corners[Plane::kTopLeft] = to_g(bottom_left + up).cast<float>();
    p.corners[Plane::kTopRight] = to_g(bottom_left + up + right).cast<float>();
    p.centroid = to_g(bottom_left + 0.5 * (up + right)).cast<float>();
    p.length_m = static_cast<float>(width);
    p.extent_m = static_cast<float>(up.norm());
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < points_; ++k) {
      const Eigen::Vector3d q = to_g(bottom_left + u(rng_) * up + u(rng_) * right);
      const double sigma = noise_.plane_sigma_at_1m * q.squaredNorm();
      p.points.push_back((q + n_stair * gauss(sigma)).cast<float>());
    }
    p.support = points_;
    return p;
  }

  StairGeometry g_;
  std::mt19937_64 rng_;
  int points_;
  Noise noise_;
};

// A walk along the stair at `speed_mps`, `fps` frames a second; the camera
// stays 1.45 m above the stair's slope line and wobbles in heading and sideways.
inline std::vector<CameraState> walk(const StairGeometry& g, bool ascending, double speed_mps, double fps) {
  const size_t n = g.riser_m.size();
  const double top_x = g.nosing_x(n - 1);
  const double x0 = ascending ? -2.2 : top_x + std::min(1.0, 0.8 * g.tread_m.back());
  const double x1 = ascending ? top_x + 0.3 : -0.5;
  std::vector<CameraState> out;
  const double dx = speed_mps / fps * (ascending ? 1 : -1);
  for (int k = 0;; ++k) {
    const double x = x0 + k * dx;
    if (ascending ? x > x1 : x < x1) break;
    // Eye height follows the surface, smoothed over a stride.
    double z = 0;
    for (int j = -4; j <= 4; ++j) z += g.surface_z(x + 0.1 * j) / 9.0;
    const double t = k / fps;
    CameraState c;
    c.position_m = Eigen::Vector3d(x, 0.08 * std::sin(1.3 * t), z + 1.45);
    c.heading_rad = (ascending ? 0.0 : M_PI) + 0.05 * std::sin(0.9 * t);
    out.push_back(c);
  }
  return out;
}

// Whole-step offset between model and truth (the scorer's alignment), matched
// steps and mean absolute riser/tread errors (landing depths excluded).
struct Accuracy {
  int real_steps = 0, matched = 0, false_steps = 0;
  double riser_abs_cm = 0, tread_abs_cm = 0;
};

inline Accuracy score(const StairModel& model, const StairGeometry& g) {
  std::vector<Step> steps;
  for (const auto& f : model.flights) steps.insert(steps.end(), f.steps.begin(), f.steps.end());
  Accuracy best;
  best.real_steps = static_cast<int>(g.riser_m.size());
  best.false_steps = static_cast<int>(steps.size());
  best.matched = -1;
  for (int off = 0; off < static_cast<int>(g.riser_m.size()); ++off) {
    // Truth in the model's frame: its origin at the bottom of real step `off`.
    const double ox = g.nosing_x(off), oz = g.nosing_z(off) - g.riser_m[off];
    Accuracy a;
    a.real_steps = best.real_steps;
    std::vector<bool> used(g.riser_m.size(), false);
    int nr = 0, nt = 0;
    for (const Step& s : steps) {
      int hit = -1;
      for (size_t i = 0; i < g.riser_m.size(); ++i)
        if (!used[i] && std::abs(s.nosing_m.x() - (g.nosing_x(i) - ox)) < 0.5 * g.tread_m[0] &&
            std::abs(s.nosing_m.z() - (g.nosing_z(i) - oz)) < 0.5 * g.riser_m[i])
          hit = static_cast<int>(i);
      if (hit < 0) {
        ++a.false_steps;
        continue;
      }
      used[hit] = true;
      ++a.matched;
      if (s.riser_height_m) a.riser_abs_cm += 100 * std::abs(*s.riser_height_m - g.riser_m[hit]), ++nr;
      if (s.tread_depth_m && !s.landing && g.tread_m[hit] < 0.5)
        a.tread_abs_cm += 100 * std::abs(*s.tread_depth_m - g.tread_m[hit]), ++nt;
    }
    if (nr) a.riser_abs_cm /= nr;
    if (nt) a.tread_abs_cm /= nt;
    if (a.matched > best.matched) best = a;
  }
  return best;
}

}  // namespace stairs::synthetic
