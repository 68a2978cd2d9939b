// Hand-built scenes for the viewer tests: a flat depth image, an observation
// with one tread, riser and edge in front of a level camera, a model of N steps.
#pragma once

#include "common/types.hpp"

namespace stairs::viewer::test {

// Level camera: optical (x right, y down, z forward) -> gravity (x forward, y left, z up).
inline Eigen::Quaterniond level_camera() {
  Eigen::Matrix3d R;
  R << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return Eigen::Quaterniond(R);
}

inline DepthImage flat_depth(int width, int height, uint16_t mm, int64_t utime = 1000, int32_t seq = 1) {
  DepthImage img;
  img.K = {width, height, 525.0 * width / 640, 525.0 * height / 480, (width - 1) / 2.0, (height - 1) / 2.0};
  img.depth.assign(static_cast<size_t>(width) * height, mm);
  img.utime = utime;
  img.seq = seq;
  return img;
}

// A rectangle of points at x in [x0, x1], y in [-w/2, w/2], z = z0 (tread) or a
// vertical one at x = x0, z in [z0, z1] (riser), in the gravity-aligned frame.
inline Plane horizontal_plane(PlaneKind kind, double x0, double x1, double w, double z0) {
  Plane p;
  p.kind = kind;
  p.normal = Eigen::Vector3f::UnitZ();
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j)
      p.points.emplace_back(float(x0 + (x1 - x0) * i / 10), float(-w / 2 + w * j / 10), float(z0));
  p.corners = {Eigen::Vector3f(x1, w / 2, z0), Eigen::Vector3f(x1, -w / 2, z0), Eigen::Vector3f(x0, w / 2, z0),
               Eigen::Vector3f(x0, -w / 2, z0)};
  p.centroid = Eigen::Vector3f((x0 + x1) / 2, 0, z0);
  return p;
}

inline Plane vertical_plane(PlaneKind kind, double x0, double w, double z0, double z1) {
  Plane p;
  p.kind = kind;
  p.normal = -Eigen::Vector3f::UnitX();
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j)
      p.points.emplace_back(float(x0), float(-w / 2 + w * j / 10), float(z0 + (z1 - z0) * i / 10));
  p.centroid = Eigen::Vector3f(x0, 0, (z0 + z1) / 2);
  return p;
}

// Tread 0.5 m below a level camera, 1.0-1.6 m ahead (lower half of the image);
// a riser 0.3-0.6 m above the camera at 2 m (upper half); a convex edge along the
// tread's far border.
inline Observation simple_observation(const DepthImage& img) {
  Observation obs;
  obs.source_utime = img.utime;
  obs.source_seq = img.seq;
  obs.camera.valid = true;
  obs.camera.gravity_rotation = level_camera();
  obs.direction = Direction::Up;
  obs.planes.push_back(horizontal_plane(PlaneKind::Tread, 1.0, 1.6, 0.8, -0.5));
  obs.planes.push_back(vertical_plane(PlaneKind::Riser, 2.0, 0.8, 0.3, 0.6));
  Edge e;
  e.type = EdgeType::Convex;
  e.start = {1.6f, 0.4f, -0.5f};
  e.end = {1.6f, -0.4f, -0.5f};
  obs.edges.push_back(e);
  Step s;
  s.riser_height_m = 0.17;
  s.tread_depth_m = 0.28;
  s.nosing_m = {1.0, 0.0, -0.5};
  obs.steps.push_back(s);
  obs.latency_ms = 7.5;
  return obs;
}

// One flight of n steps (rise 0.17 m, going 0.28 m), the last a landing; the
// camera 1 m before the first riser, 1.2 m high, looking up the stair.
inline StairModel stair_model(int n) {
  StairModel m;
  m.state = TrackingState::Ok;
  m.direction = Direction::Up;
  Flight f;
  f.width_m = 1.0;
  for (int i = 0; i < n; ++i) {
    Step s;
    s.riser_height_m = 0.17;
    s.tread_depth_m = i + 1 == n ? 1.2 : 0.28;
    s.landing = i + 1 == n;
    s.nosing_m = {0.28 * i, 0.0, 0.17 * (i + 1)};
    s.width_m = 1.0;
    f.steps.push_back(s);
  }
  m.flights.push_back(f);
  m.camera_valid = true;
  m.camera_position_m = {-1.0, 0.0, 1.2};
  // Optical -> stair: level camera looking along +x (pitched down 30 deg).
  m.camera_orientation = Eigen::AngleAxisd(30.0 * M_PI / 180, Eigen::Vector3d::UnitY()) * level_camera();
  return m;
}

}  // namespace stairs::viewer::test
