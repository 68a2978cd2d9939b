#include "common/lcm_bridge.hpp"

#include "common/zlib_codec.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>

namespace stairs {
namespace {

template <class T>
int16_t count16(const std::vector<T>& v, int16_t cap) {
  return static_cast<int16_t>(std::min<size_t>(v.size(), static_cast<size_t>(cap)));
}

bool finite_all(const float* v, int n) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

// A pose as the messages carry it: position (x, y, z) and quaternion (w, x, y, z).
void put_pose(const Eigen::Vector3d& p, const Eigen::Quaterniond& q, double* position, double* wxyz) {
  for (int i = 0; i < 3; ++i) position[i] = p[i];
  wxyz[0] = q.w();
  wxyz[1] = q.x();
  wxyz[2] = q.y();
  wxyz[3] = q.z();
}
Eigen::Vector3d position_of(const double* p) { return {p[0], p[1], p[2]}; }
Eigen::Quaterniond quaternion_of(const double* wxyz) { return {wxyz[0], wxyz[1], wxyz[2], wxyz[3]}; }

int32_t read_be32(const uint8_t* p) {
  return static_cast<int32_t>((uint32_t(p[0]) << 24) | (uint32_t(p[1]) << 16) | (uint32_t(p[2]) << 8) |
                              uint32_t(p[3]));
}

// depth_frame_t keeps every scalar before its arrays, so the two int32 array
// sizes sit at fixed offsets (hash 8, utime 8, device ts 8, seq 4, width 4,
// height 4, fx..cy 16, depth_scale 4, encoding 1, uncompressed_size 4).
constexpr size_t kDepthDataSizeOffset = 8 + 8 + 8 + 4 + 4 + 4 + 16 + 4 + 1 + 4;
constexpr size_t kDepthColorSizeOffset = kDepthDataSizeOffset + 4 + 1 + 4 + 4;
constexpr size_t kDepthHeaderBytes = kDepthColorSizeOffset + 4;

bool precheck(const depth_frame_t*, const uint8_t* buf, size_t size, std::string& error) {
  if (size < kDepthHeaderBytes) {
    error = "depth_frame_t truncated: " + std::to_string(size) + " bytes";
    return false;
  }
  const int64_t data_size = read_be32(buf + kDepthDataSizeOffset);
  const int64_t color_size = read_be32(buf + kDepthColorSizeOffset);
  if (data_size < 0 || color_size < 0 || data_size + color_size > static_cast<int64_t>(size - kDepthHeaderBytes)) {
    error = "depth_frame_t declares data_size " + std::to_string(data_size) + " + color_size " +
            std::to_string(color_size) + " beyond the " + std::to_string(size) + "-byte message";
    return false;
  }
  return true;
}
template <class T>
bool precheck(const T*, const uint8_t*, size_t, std::string&) {
  return true;
}

}  // namespace

template <class T>
size_t max_message_bytes() {
  if constexpr (std::is_same_v<T, depth_frame_t>) return depth_frame_t::MAX_MESSAGE_BYTES;
  else if constexpr (std::is_same_v<T, stair_observation_t>) return stair_observation_t::MAX_MESSAGE_BYTES;
  else if constexpr (std::is_same_v<T, stair_model_t>) return stair_model_t::MAX_MESSAGE_BYTES;
  else return 1 << 20;
}

template <class T>
bool decode_message(const void* data, size_t size, T& msg, std::string& error) {
  if (size > max_message_bytes<T>()) {
    error = std::string(typeid(T).name()) + " of " + std::to_string(size) + " bytes exceeds the cap of " +
            std::to_string(max_message_bytes<T>());
    return false;
  }
  if (size >= 8) {
    int64_t hash = 0;
    for (int i = 0; i < 8; ++i) hash = (hash << 8) | static_cast<const uint8_t*>(data)[i];
    if (hash != T::getHash()) {
      error = "wrong message type on the channel (fingerprint mismatch)";
      return false;
    }
  }
  if (!precheck(static_cast<const T*>(nullptr), static_cast<const uint8_t*>(data), size, error)) return false;
  try {
    if (msg.decode(data, 0, static_cast<int>(size)) < 0) {
      error = "truncated or corrupt encoding";
      return false;
    }
  } catch (const std::exception& e) {
    error = std::string("corrupt encoding: ") + e.what();
    return false;
  }
  return true;
}

#define STAIRS_INSTANTIATE(T)                                                         \
  template bool decode_message<T>(const void*, size_t, T&, std::string&);           \
  template size_t max_message_bytes<T>();
STAIRS_INSTANTIATE(depth_frame_t)
STAIRS_INSTANTIATE(stair_observation_t)
STAIRS_INSTANTIATE(stair_model_t)
STAIRS_INSTANTIATE(ground_truth_t)
STAIRS_INSTANTIATE(daemon_status_t)
STAIRS_INSTANTIATE(pose_t)
STAIRS_INSTANTIATE(imu_t)
STAIRS_INSTANTIATE(tracker_command_t)
#undef STAIRS_INSTANTIATE

// --- odometry -----------------------------------------------------------------

pose_t to_lcm(const OdometrySample& o) {
  pose_t m{};
  m.utime = o.utime;
  put_pose(o.position_m, o.orientation, m.pos, m.orientation);
  return m;
}

bool from_lcm(const pose_t& m, OdometrySample& o, std::string& error) {
  bool finite = true;
  for (double v : m.pos) finite = finite && std::isfinite(v);
  for (double v : m.orientation) finite = finite && std::isfinite(v);
  if (!finite) return error = "odometry pose with NaN/inf", false;
  const Eigen::Quaterniond q = quaternion_of(m.orientation);
  if (std::abs(q.norm() - 1.0) > 1e-3)
    return error = "odometry orientation is no unit quaternion (norm " + std::to_string(q.norm()) + ")", false;
  o.utime = m.utime;
  o.position_m = position_of(m.pos);
  o.orientation = q.normalized();
  return true;
}

// --- inertial -----------------------------------------------------------------

imu_t to_lcm(const ImuSample& s) {
  imu_t m{};
  m.utime = s.utime;
  for (int i = 0; i < 3; ++i) {
    m.specific_force_mps2[i] = s.specific_force_mps2[i];
    m.angular_rate_radps[i] = s.angular_rate_radps[i];
  }
  return m;
}

bool from_lcm(const imu_t& m, ImuSample& s, std::string& error) {
  bool finite = true;
  for (int i = 0; i < 3; ++i) finite = finite && std::isfinite(m.specific_force_mps2[i]) && std::isfinite(m.angular_rate_radps[i]);
  if (!finite) return error = "IMU sample with NaN/inf", false;
  s.utime = m.utime;
  s.specific_force_mps2 = Eigen::Vector3d(m.specific_force_mps2[0], m.specific_force_mps2[1], m.specific_force_mps2[2]);
  s.angular_rate_radps = Eigen::Vector3d(m.angular_rate_radps[0], m.angular_rate_radps[1], m.angular_rate_radps[2]);
  return true;
}

// --- depth --------------------------------------------------------------------

depth_frame_t to_lcm(const DepthImage& img, int zlib_level, const std::string& frame_id) {
  depth_frame_t m{};
  m.utime = img.utime;
  m.device_timestamp_us = 0;
  m.seq = img.seq;
  m.width = img.K.width;
  m.height = img.K.height;
  m.fx = static_cast<float>(img.K.fx);
  m.fy = static_cast<float>(img.K.fy);
  m.cx = static_cast<float>(img.K.cx);
  m.cy = static_cast<float>(img.K.cy);
  m.depth_scale = static_cast<float>(img.depth_scale);
  m.uncompressed_size = static_cast<int32_t>(img.depth.size() * 2);
  // Little-endian on the wire; this code targets little-endian hosts (x86, ARM).
  const auto* raw = reinterpret_cast<const uint8_t*>(img.depth.data());
  if (zlib_level > 0) {
    m.encoding = depth_frame_t::ENCODING_ZLIB_U16LE;
    m.data = zlib_compress(raw, img.depth.size() * 2, zlib_level);
  } else {
    m.encoding = depth_frame_t::ENCODING_RAW_U16LE;
    m.data.assign(raw, raw + img.depth.size() * 2);
  }
  m.data_size = static_cast<int32_t>(m.data.size());
  m.color_encoding = depth_frame_t::COLOR_NONE;
  m.frame_id = frame_id;
  return m;
}

bool from_lcm(const depth_frame_t& m, DepthImage& img, std::string& error) {
  if (m.width <= 0 || m.height <= 0 || m.width > depth_frame_t::MAX_WIDTH || m.height > depth_frame_t::MAX_HEIGHT) {
    error = "width/height " + std::to_string(m.width) + "x" + std::to_string(m.height) + " out of range";
    return false;
  }
  const float intr[] = {m.fx, m.fy, m.cx, m.cy, m.depth_scale};
  if (!finite_all(intr, 5) || m.fx <= 0 || m.fy <= 0 || m.depth_scale <= 0) {
    error = "intrinsics or depth_scale not finite and positive";
    return false;
  }
  const size_t expected = static_cast<size_t>(m.width) * m.height * 2;
  if (m.uncompressed_size < 0 || static_cast<size_t>(m.uncompressed_size) != expected) {
    error = "uncompressed_size " + std::to_string(m.uncompressed_size) + " != width*height*2 = " +
            std::to_string(expected);
    return false;
  }
  if (static_cast<size_t>(m.data_size) != m.data.size()) {
    error = "data_size disagrees with data";
    return false;
  }
  img.K = {m.width, m.height, m.fx, m.fy, m.cx, m.cy};
  img.depth_scale = m.depth_scale;
  img.utime = m.utime;
  img.seq = m.seq;
  img.depth.resize(expected / 2);
  if (m.encoding == depth_frame_t::ENCODING_RAW_U16LE) {
    if (m.data.size() != expected) {
      error = "raw depth of " + std::to_string(m.data.size()) + " bytes, expected " + std::to_string(expected);
      return false;
    }
    std::memcpy(img.depth.data(), m.data.data(), expected);
  } else if (m.encoding == depth_frame_t::ENCODING_ZLIB_U16LE) {
    // Little-endian bytes straight into the image (the raw case's memcpy assumes the same host order).
    if (!zlib_decompress(m.data.data(), m.data.size(), reinterpret_cast<uint8_t*>(img.depth.data()), expected, error))
      return false;
  } else {
    error = "unknown depth encoding " + std::to_string(m.encoding);
    return false;
  }
  if (std::all_of(img.depth.begin(), img.depth.end(), [](uint16_t d) { return d == 0; })) {
    error = "depth is zero everywhere";
    return false;
  }
  return true;
}

// --- planes, steps --------------------------------------------------------------

plane_t to_lcm(const Plane& p) {
  plane_t m{};
  m.kind = static_cast<int8_t>(p.kind);
  m.source = static_cast<int8_t>(p.source);
  for (int i = 0; i < 3; ++i) {
    m.normal[i] = p.normal[i];
    m.centroid_m[i] = p.centroid[i];
    for (int c = 0; c < 4; ++c) m.corners_m[c][i] = p.corners[c][i];
  }
  m.length_m = p.length_m;
  m.extent_m = p.extent_m;
  m.support = p.support;
  const size_t n = std::min<size_t>(p.points.size(), plane_t::MAX_POINTS);
  // Keep an even spread when the sample exceeds the cap.
  const double stride = p.points.empty() ? 1.0 : static_cast<double>(p.points.size()) / std::max<size_t>(n, 1);
  m.num_points = static_cast<int16_t>(n);
  m.points_x_m.resize(n);
  m.points_y_m.resize(n);
  m.points_z_m.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f& q = p.points[static_cast<size_t>(i * stride)];
    m.points_x_m[i] = q.x();
    m.points_y_m[i] = q.y();
    m.points_z_m[i] = q.z();
  }
  return m;
}

Plane from_lcm(const plane_t& m) {
  Plane p;
  p.kind = static_cast<PlaneKind>(m.kind);
  p.source = static_cast<PlaneSource>(m.source);
  for (int i = 0; i < 3; ++i) {
    p.normal[i] = m.normal[i];
    p.centroid[i] = m.centroid_m[i];
    for (int c = 0; c < 4; ++c) p.corners[c][i] = m.corners_m[c][i];
  }
  p.length_m = m.length_m;
  p.extent_m = m.extent_m;
  p.support = m.support;
  p.points.resize(static_cast<size_t>(std::max<int16_t>(m.num_points, 0)));
  for (size_t i = 0; i < p.points.size(); ++i) p.points[i] = {m.points_x_m[i], m.points_y_m[i], m.points_z_m[i]};
  return p;
}

step_t to_lcm(const Step& s) {
  step_t m{};
  m.riser_plane = static_cast<int16_t>(s.riser_plane);
  m.tread_plane = static_cast<int16_t>(s.tread_plane);
  m.landing = s.landing;
  m.riser_valid = s.riser_height_m.has_value();
  m.riser_height_m = static_cast<float>(s.riser_height_m.value_or(0.0));
  m.tread_valid = s.tread_depth_m.has_value();
  m.tread_depth_m = static_cast<float>(s.tread_depth_m.value_or(0.0));
  m.width_m = static_cast<float>(s.width_m);
  for (int i = 0; i < 3; ++i) m.nosing_m[i] = static_cast<float>(s.nosing_m[i]);
  m.confirmations = s.confirmations;
  return m;
}

Step from_lcm(const step_t& m) {
  Step s;
  s.riser_plane = m.riser_plane;
  s.tread_plane = m.tread_plane;
  s.landing = m.landing;
  if (m.riser_valid) s.riser_height_m = m.riser_height_m;
  if (m.tread_valid) s.tread_depth_m = m.tread_depth_m;
  s.width_m = m.width_m;
  s.nosing_m = {m.nosing_m[0], m.nosing_m[1], m.nosing_m[2]};
  s.confirmations = m.confirmations;
  return s;
}

namespace {

bool valid_step(const step_t& s, int num_planes, std::string& error) {
  const float v[] = {s.riser_height_m, s.tread_depth_m, s.width_m, s.nosing_m[0], s.nosing_m[1], s.nosing_m[2]};
  if (!finite_all(v, 6)) {
    error = "step with NaN/inf";
    return false;
  }
  if (s.riser_plane < -1 || s.riser_plane >= num_planes || s.tread_plane < -1 || s.tread_plane >= num_planes) {
    error = "step refers to a plane that does not exist";
    return false;
  }
  return true;
}

bool valid_plane(const plane_t& p, std::string& error) {
  if (p.num_points < 0 || p.num_points > plane_t::MAX_POINTS) {
    error = "plane sample of " + std::to_string(p.num_points) + " points exceeds the cap";
    return false;
  }
  if (!finite_all(p.normal, 3) || !finite_all(p.centroid_m, 3) || !finite_all(&p.corners_m[0][0], 12) ||
      !std::isfinite(p.length_m) || !std::isfinite(p.extent_m) || !finite_all(p.points_x_m.data(), p.num_points) ||
      !finite_all(p.points_y_m.data(), p.num_points) || !finite_all(p.points_z_m.data(), p.num_points)) {
    error = "plane with NaN/inf";
    return false;
  }
  return true;
}

CameraPose from_lcm(const camera_pose_t& m) {
  CameraPose c;
  c.valid = m.valid;
  c.pitch_deg = m.pitch_deg;
  c.roll_deg = m.roll_deg;
  if (m.height_valid) c.height_m = m.height_m;
  if (m.distance_valid) c.distance_m = m.distance_m;
  c.gravity_rotation = Eigen::Quaterniond(m.gravity_rotation_wxyz[0], m.gravity_rotation_wxyz[1],
                                          m.gravity_rotation_wxyz[2], m.gravity_rotation_wxyz[3]);
  return c;
}

camera_pose_t to_lcm(const CameraPose& c) {
  camera_pose_t m{};
  m.valid = c.valid;
  m.pitch_deg = static_cast<float>(c.pitch_deg);
  m.roll_deg = static_cast<float>(c.roll_deg);
  m.height_valid = c.height_m.has_value();
  m.height_m = static_cast<float>(c.height_m.value_or(0.0));
  m.distance_valid = c.distance_m.has_value();
  m.distance_m = static_cast<float>(c.distance_m.value_or(0.0));
  const Eigen::Quaterniond& q = c.gravity_rotation;
  m.gravity_rotation_wxyz[0] = q.w();
  m.gravity_rotation_wxyz[1] = q.x();
  m.gravity_rotation_wxyz[2] = q.y();
  m.gravity_rotation_wxyz[3] = q.z();
  return m;
}

bool valid_camera(const camera_pose_t& c, std::string& error) {
  const float v[] = {c.pitch_deg, c.roll_deg, c.height_m, c.distance_m};
  bool ok = finite_all(v, 4);
  for (double q : c.gravity_rotation_wxyz) ok = ok && std::isfinite(q);
  if (!ok) error = "camera pose with NaN/inf";
  return ok;
}

}  // namespace

// --- observation ---------------------------------------------------------------

stair_observation_t to_lcm(const Observation& o, int64_t utime) {
  stair_observation_t m{};
  m.utime = utime;
  m.source_utime = o.source_utime;
  m.source_seq = o.source_seq;
  m.camera = to_lcm(o.camera);
  m.direction = static_cast<int8_t>(o.direction);
  m.num_steps = count16(o.steps, stair_observation_t::MAX_STEPS);
  for (int i = 0; i < m.num_steps; ++i) {
    m.steps.push_back(to_lcm(o.steps[i]));
    m.step_inferred.push_back(static_cast<int8_t>(o.steps[i].inferred));
  }
  m.num_planes = count16(o.planes, stair_observation_t::MAX_PLANES);
  for (int i = 0; i < m.num_planes; ++i) m.planes.push_back(to_lcm(o.planes[i]));
  for (step_t& s : m.steps) {  // indices past the cap would dangle
    if (s.riser_plane >= m.num_planes) s.riser_plane = -1;
    if (s.tread_plane >= m.num_planes) s.tread_plane = -1;
  }
  m.num_edges = count16(o.edges, stair_observation_t::MAX_EDGES);
  for (int i = 0; i < m.num_edges; ++i) {
    const Edge& e = o.edges[i];
    edge_t em{};
    em.type = static_cast<int8_t>(e.type);
    em.source = static_cast<int8_t>(e.source);
    for (int k = 0; k < 3; ++k) {
      em.start_m[k] = e.start[k];
      em.end_m[k] = e.end[k];
    }
    for (int k = 0; k < 2; ++k) {
      em.start_px[k] = e.start_px[k];
      em.end_px[k] = e.end_px[k];
    }
    em.support = e.support;
    m.edges.push_back(em);
  }
  m.num_stages = count16(o.stages, stair_observation_t::MAX_STAGES);
  for (int i = 0; i < m.num_stages; ++i) {
    m.stage_names.push_back(o.stages[i].name);
    m.stage_latency_ms.push_back(static_cast<float>(o.stages[i].ms));
  }
  m.latency_ms = static_cast<float>(o.latency_ms);
  m.status = o.status;
  return m;
}

bool from_lcm(const stair_observation_t& m, Observation& o, std::string& error) {
  if (m.num_steps < 0 || m.num_steps > stair_observation_t::MAX_STEPS || m.num_planes < 0 ||
      m.num_planes > stair_observation_t::MAX_PLANES || m.num_edges < 0 ||
      m.num_edges > stair_observation_t::MAX_EDGES || m.num_stages < 0 ||
      m.num_stages > stair_observation_t::MAX_STAGES) {
    error = "observation array length beyond its documented cap";
    return false;
  }
  if (m.direction < 0 || m.direction > 2) {
    error = "unknown direction " + std::to_string(m.direction);
    return false;
  }
  if (!valid_camera(m.camera, error)) return false;
  for (const plane_t& p : m.planes)
    if (!valid_plane(p, error)) return false;
  for (const step_t& s : m.steps)
    if (!valid_step(s, m.num_planes, error)) return false;
  for (const edge_t& e : m.edges)
    if (!finite_all(e.start_m, 3) || !finite_all(e.end_m, 3)) {
      error = "edge with NaN/inf";
      return false;
    }
  o = Observation{};
  o.source_utime = m.source_utime;
  o.source_seq = m.source_seq;
  o.camera = from_lcm(m.camera);
  o.direction = static_cast<Direction>(m.direction);
  for (size_t i = 0; i < m.steps.size(); ++i) {
    o.steps.push_back(from_lcm(m.steps[i]));
    if (i < m.step_inferred.size()) o.steps.back().inferred = static_cast<uint8_t>(m.step_inferred[i]);
  }
  for (const plane_t& p : m.planes) o.planes.push_back(from_lcm(p));
  for (const edge_t& em : m.edges) {
    Edge e;
    e.type = static_cast<EdgeType>(em.type);
    e.source = static_cast<EdgeSource>(em.source);
    e.start = {em.start_m[0], em.start_m[1], em.start_m[2]};
    e.end = {em.end_m[0], em.end_m[1], em.end_m[2]};
    e.start_px = {em.start_px[0], em.start_px[1]};
    e.end_px = {em.end_px[0], em.end_px[1]};
    e.support = em.support;
    o.edges.push_back(e);
  }
  for (int i = 0; i < m.num_stages; ++i) o.stages.push_back({m.stage_names[i], m.stage_latency_ms[i]});
  o.latency_ms = m.latency_ms;
  o.status = m.status;
  return true;
}

// --- model -----------------------------------------------------------------------

namespace {

flight_t to_lcm(const Flight& f) {
  flight_t m{};
  m.width_m = static_cast<float>(f.width_m);
  m.num_steps = count16(f.steps, flight_t::MAX_STEPS);
  for (int i = 0; i < m.num_steps; ++i) m.steps.push_back(to_lcm(f.steps[i]));
  return m;
}

bool from_lcm(const flight_t& m, int num_planes, Flight& f, std::string& error) {
  if (m.num_steps < 0 || m.num_steps > flight_t::MAX_STEPS) {
    error = "flight with " + std::to_string(m.num_steps) + " steps beyond the cap";
    return false;
  }
  if (!std::isfinite(m.width_m)) {
    error = "flight width NaN/inf";
    return false;
  }
  f.width_m = m.width_m;
  f.steps.clear();
  for (const step_t& s : m.steps) {
    if (!valid_step(s, num_planes, error)) return false;
    f.steps.push_back(from_lcm(s));
  }
  return true;
}

}  // namespace

stair_model_t to_lcm(const StairModel& model, int64_t utime, int64_t source_utime, int32_t source_seq) {
  stair_model_t m{};
  m.utime = utime;
  m.source_utime = source_utime;
  m.source_seq = source_seq;
  m.tracking_state = static_cast<int8_t>(model.state);
  m.direction = static_cast<int8_t>(model.direction);
  m.num_flights = count16(model.flights, stair_model_t::MAX_FLIGHTS);
  for (int i = 0; i < m.num_flights; ++i) m.flights.push_back(to_lcm(model.flights[i]));
  m.camera_valid = model.camera_valid;
  put_pose(model.camera_position_m, model.camera_orientation, m.camera_position_m, m.camera_quaternion_wxyz);
  m.camera_height_m = static_cast<float>(model.camera_height_m);
  m.camera_step_index = static_cast<int16_t>(model.camera_step_index);
  m.observations_fused = model.observations_fused;
  m.registration_rmse_m = static_cast<float>(model.registration_rmse_m);
  m.registration_inlier_ratio = static_cast<float>(model.registration_inlier_ratio);
  m.update_latency_ms = static_cast<float>(model.update_latency_ms);
  m.num_planes = count16(model.planes, stair_model_t::MAX_PLANES);
  for (int i = 0; i < m.num_planes; ++i) m.planes.push_back(to_lcm(model.planes[i]));
  for (flight_t& f : m.flights)
    for (step_t& s : f.steps) {
      if (s.riser_plane >= m.num_planes) s.riser_plane = -1;
      if (s.tread_plane >= m.num_planes) s.tread_plane = -1;
    }
  m.status = model.status;
  m.confirmed = model.confirmed;
  m.camera_beneath_known = model.camera_beneath_known;
  m.base_valid = model.base_valid;
  put_pose(model.base_position_m, model.base_orientation, m.base_position_m, m.base_quaternion_wxyz);
  m.base_height_m = static_cast<float>(model.base_height_m);
  m.base_step_index = static_cast<int16_t>(model.base_step_index);
  m.base_beneath_known = model.base_beneath_known;
  m.camera_height_known = model.camera_height_known;
  m.base_height_known = model.base_height_known;
  m.camera_position_uncertainty_m = static_cast<float>(model.camera_position_uncertainty_m);
  return m;
}

stair_model_t steps_only(stair_model_t model) {
  model.num_planes = 0;
  model.planes.clear();
  for (flight_t& f : model.flights)
    for (step_t& s : f.steps) s.riser_plane = s.tread_plane = -1;
  return model;
}

bool from_lcm(const stair_model_t& m, StairModel& model, std::string& error) {
  if (m.num_flights < 0 || m.num_flights > stair_model_t::MAX_FLIGHTS || m.num_planes < 0 ||
      m.num_planes > stair_model_t::MAX_PLANES) {
    error = "model array length beyond its documented cap";
    return false;
  }
  if (m.tracking_state < 0 || m.tracking_state > 3 || m.direction < 0 || m.direction > 2) {
    error = "unknown tracking state or direction";
    return false;
  }
  StairModel out;
  out.state = static_cast<TrackingState>(m.tracking_state);
  out.direction = static_cast<Direction>(m.direction);
  for (const flight_t& fm : m.flights) {
    Flight f;
    if (!from_lcm(fm, m.num_planes, f, error)) return false;
    out.flights.push_back(std::move(f));
  }
  for (const plane_t& p : m.planes) {
    if (!valid_plane(p, error)) return false;
    out.planes.push_back(from_lcm(p));
  }
  out.camera_valid = m.camera_valid;
  out.camera_position_m = position_of(m.camera_position_m);
  out.camera_orientation = quaternion_of(m.camera_quaternion_wxyz);
  if (!out.camera_position_m.allFinite() || !out.camera_orientation.coeffs().allFinite() ||
      !std::isfinite(m.camera_height_m) || !std::isfinite(m.camera_position_uncertainty_m)) {
    error = "model camera pose with NaN/inf";
    return false;
  }
  out.base_position_m = position_of(m.base_position_m);
  out.base_orientation = quaternion_of(m.base_quaternion_wxyz);
  if (!out.base_position_m.allFinite() || !out.base_orientation.coeffs().allFinite() || !std::isfinite(m.base_height_m)) {
    error = "model base pose with NaN/inf";
    return false;
  }
  out.camera_height_m = m.camera_height_m;
  out.camera_step_index = m.camera_step_index;
  out.base_valid = m.base_valid;
  out.base_height_m = m.base_height_m;
  out.base_step_index = m.base_step_index;
  out.base_beneath_known = m.base_beneath_known;
  out.camera_height_known = m.camera_height_known;
  out.base_height_known = m.base_height_known;
  out.observations_fused = m.observations_fused;
  out.registration_rmse_m = m.registration_rmse_m;
  out.registration_inlier_ratio = m.registration_inlier_ratio;
  out.update_latency_ms = m.update_latency_ms;
  out.status = m.status;
  out.confirmed = m.confirmed;
  out.camera_beneath_known = m.camera_beneath_known;
  out.camera_position_uncertainty_m = m.camera_position_uncertainty_m;
  model = std::move(out);
  return true;
}

// --- ground truth ------------------------------------------------------------------

ground_truth_t to_lcm(const GroundTruth& gt, const GroundTruthFrame& fr, int64_t utime, int32_t seq) {
  ground_truth_t m{};
  m.utime = utime;
  m.seq = seq;
  m.scene = gt.scene;
  m.num_flights = count16(gt.flights, stair_model_t::MAX_FLIGHTS);
  for (int i = 0; i < m.num_flights; ++i) m.flights.push_back(to_lcm(gt.flights[i]));
  m.pitch_deg = static_cast<float>(fr.pitch_deg);
  m.roll_deg = static_cast<float>(fr.roll_deg);
  m.height_m = static_cast<float>(fr.height_m);
  m.distance_valid = fr.distance_m.has_value();
  m.distance_m = static_cast<float>(fr.distance_m.value_or(0.0));
  put_pose(fr.position_m, fr.orientation, m.position_m, m.quaternion_wxyz);
  m.num_visible = count16(fr.visible_steps, ground_truth_t::MAX_VISIBLE);
  for (int i = 0; i < m.num_visible; ++i) m.visible_steps.push_back(static_cast<int16_t>(fr.visible_steps[i]));
  return m;
}

bool from_lcm(const ground_truth_t& m, GroundTruth& gt, GroundTruthFrame& fr, std::string& error) {
  if (m.num_flights < 0 || m.num_flights > stair_model_t::MAX_FLIGHTS || m.num_visible < 0 ||
      m.num_visible > ground_truth_t::MAX_VISIBLE) {
    error = "ground truth array length beyond its documented cap";
    return false;
  }
  gt.scene = m.scene;
  gt.flights.clear();
  for (const flight_t& fm : m.flights) {
    Flight f;
    if (!from_lcm(fm, 0, f, error)) return false;
    gt.flights.push_back(std::move(f));
  }
  fr = GroundTruthFrame{};
  fr.timestamp = m.utime * 1e-6;
  fr.pitch_deg = m.pitch_deg;
  fr.roll_deg = m.roll_deg;
  fr.height_m = m.height_m;
  if (m.distance_valid) fr.distance_m = m.distance_m;
  fr.position_m = position_of(m.position_m);
  fr.orientation = quaternion_of(m.quaternion_wxyz);
  fr.visible_steps.assign(m.visible_steps.begin(), m.visible_steps.end());
  return true;
}

}  // namespace stairs
