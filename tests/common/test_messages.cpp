// Round trip of every message type through LCM encoding and the core types.
#include "common/lcm_bridge.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace stairs;

namespace {

template <class T>
std::vector<uint8_t> encode(const T& msg) {
  std::vector<uint8_t> buf(msg.getEncodedSize());
  EXPECT_EQ(msg.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  return buf;
}

template <class T>
T round_trip(const T& msg) {
  const std::vector<uint8_t> buf = encode(msg);
  T out;
  std::string error;
  EXPECT_TRUE(decode_message(buf.data(), buf.size(), out, error)) << error;
  return out;
}

Plane sample_plane(PlaneKind kind, int n_points) {
  Plane p;
  p.kind = kind;
  p.source = PlaneSource::Edges;
  p.normal = {0, 0, 1};
  p.centroid = {1.0f, 0.1f, -0.8f};
  for (int c = 0; c < 4; ++c) p.corners[c] = {1.0f + c, 0.5f - c, -0.8f};
  p.length_m = 1.1f;
  p.extent_m = 0.27f;
  p.support = 1234;
  for (int i = 0; i < n_points; ++i) p.points.push_back({0.01f * i, -0.02f * i, 0.5f});
  return p;
}

Observation sample_observation() {
  Observation o;
  o.source_utime = 1234567;
  o.source_seq = 42;
  o.camera.valid = true;
  o.camera.pitch_deg = -35.5;
  o.camera.roll_deg = 1.25;
  o.camera.height_m = 1.02;
  o.camera.gravity_rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()));
  o.direction = Direction::Up;
  o.planes = {sample_plane(PlaneKind::Tread, 10), sample_plane(PlaneKind::Riser, 0)};
  Step s;
  s.riser_plane = 1;
  s.tread_plane = 0;
  s.riser_height_m = 0.18;
  s.width_m = 1.0;
  s.nosing_m = {1.5, -0.2, -0.7};
  o.steps = {s, s};
  o.steps[1].riser_height_m.reset();
  o.steps[1].tread_depth_m = 0.3;
  Edge e;
  e.type = EdgeType::Concave;
  e.source = EdgeSource::DepthJump;
  e.start = {1, 2, 3};
  e.end = {4, 5, 6};
  e.start_px = {10, 20};
  e.end_px = {30, 40};
  e.support = 77;
  o.edges = {e};
  o.stages = {{"normals", 1.5}, {"region_growing", 2.25}};
  o.latency_ms = 4.0;
  o.status = "2 steps";
  return o;
}

}  // namespace

TEST(Messages, ObservationRoundTrip) {
  const Observation o = sample_observation();
  const stair_observation_t m = round_trip(to_lcm(o, 99));
  Observation back;
  std::string error;
  ASSERT_TRUE(from_lcm(m, back, error)) << error;
  EXPECT_EQ(m.utime, 99);
  EXPECT_EQ(back.source_seq, 42);
  EXPECT_EQ(back.direction, Direction::Up);
  EXPECT_TRUE(back.camera.valid);
  EXPECT_NEAR(back.camera.pitch_deg, -35.5, 1e-5);
  EXPECT_NEAR(*back.camera.height_m, 1.02, 1e-6);
  EXPECT_FALSE(back.camera.distance_m.has_value());
  EXPECT_NEAR(back.camera.gravity_rotation.angularDistance(o.camera.gravity_rotation), 0.0, 1e-9);
  ASSERT_EQ(back.steps.size(), 2u);
  EXPECT_NEAR(*back.steps[0].riser_height_m, 0.18, 1e-6);
  EXPECT_FALSE(back.steps[0].tread_depth_m.has_value());
  EXPECT_FALSE(back.steps[1].riser_height_m.has_value());
  EXPECT_EQ(back.steps[0].riser_plane, 1);
  EXPECT_NEAR(back.steps[0].nosing_m.y(), -0.2, 1e-6);
  ASSERT_EQ(back.planes.size(), 2u);
  EXPECT_EQ(back.planes[0].kind, PlaneKind::Tread);
  EXPECT_EQ(back.planes[0].source, PlaneSource::Edges);
  ASSERT_EQ(back.planes[0].points.size(), 10u);
  EXPECT_FLOAT_EQ(back.planes[0].points[9].y(), -0.18f);
  EXPECT_FLOAT_EQ(back.planes[0].corners[Plane::kBottomRight].x(), 4.0f);
  ASSERT_EQ(back.edges.size(), 1u);
  EXPECT_EQ(back.edges[0].type, EdgeType::Concave);
  EXPECT_EQ(back.edges[0].source, EdgeSource::DepthJump);
  EXPECT_FLOAT_EQ(back.edges[0].end_px.y(), 40.0f);
  ASSERT_EQ(back.stages.size(), 2u);
  EXPECT_EQ(back.stages[1].name, "region_growing");
  EXPECT_EQ(back.status, "2 steps");
}

TEST(Messages, PlaneSampleIsCappedAndSpread) {
  Observation o;
  o.planes = {sample_plane(PlaneKind::Tread, 5000)};
  const stair_observation_t m = to_lcm(o, 0);
  ASSERT_EQ(m.planes[0].num_points, +plane_t::MAX_POINTS);
  // The sample spans the whole plane, not its first 1024 points.
  EXPECT_GT(m.planes[0].points_x_m.back(), 0.01f * 4000);
}

TEST(Messages, ModelRoundTrip) {
  StairModel model;
  model.state = TrackingState::Relocalised;
  model.direction = Direction::Down;
  Flight f;
  f.width_m = 1.2;
  Step s;
  s.riser_height_m = 0.17;
  s.tread_depth_m = 0.29;
  s.nosing_m = {0.0, 0.0, 0.17};
  s.confirmations = 12;
  f.steps = {s, s};
  f.steps[1].landing = true;
  model.flights = {f, f};
  model.camera_valid = true;
  model.camera_position_m = {-1.0, 0.1, 1.2};
  model.camera_step_index = 3;
  model.observations_fused = 57;
  model.registration_rmse_m = 0.004;
  model.base_valid = true;
  model.base_position_m = {-0.9, 0.1, 0.02};
  model.base_orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()));
  model.base_height_m = 0.02;
  model.base_step_index = 2;
  model.base_beneath_known = true;
  model.camera_beneath_known = true;
  model.camera_height_known = false;  // the step beneath holds, the height does not
  model.base_height_known = true;
  model.camera_position_uncertainty_m = 0.035;
  model.planes = {sample_plane(PlaneKind::Landing, 3)};
  const stair_model_t m = round_trip(to_lcm(model, 5, 4, 3));
  StairModel back;
  std::string error;
  ASSERT_TRUE(from_lcm(m, back, error)) << error;
  EXPECT_EQ(back.state, TrackingState::Relocalised);
  EXPECT_EQ(back.direction, Direction::Down);
  ASSERT_EQ(back.flights.size(), 2u);
  EXPECT_TRUE(back.flights[1].steps[1].landing);
  EXPECT_EQ(back.flights[0].steps[0].confirmations, 12);
  EXPECT_NEAR(*back.flights[0].steps[0].tread_depth_m, 0.29, 1e-6);
  EXPECT_EQ(back.camera_step_index, 3);
  EXPECT_EQ(back.observations_fused, 57);
  EXPECT_NEAR(back.camera_position_m.z(), 1.2, 1e-12);
  EXPECT_TRUE(back.base_valid && back.base_beneath_known);
  EXPECT_TRUE(back.camera_beneath_known);
  EXPECT_FALSE(back.camera_height_known);
  EXPECT_TRUE(back.base_height_known);
  EXPECT_EQ(back.base_step_index, 2);
  EXPECT_NEAR(back.base_height_m, 0.02, 1e-6);
  EXPECT_NEAR(back.base_position_m.x(), -0.9, 1e-12);
  EXPECT_NEAR(back.camera_position_uncertainty_m, 0.035, 1e-6);
  EXPECT_NEAR(back.base_orientation.angularDistance(model.base_orientation), 0.0, 1e-9);
  ASSERT_EQ(back.planes.size(), 1u);
  EXPECT_EQ(back.planes[0].kind, PlaneKind::Landing);
}

// STAIRS_ODOMETRY: stairs.pose_t has bot_core.pose_t's members, so its
// fingerprint is bot_core.pose_t's (lcm-gen hashes members, not the package).
TEST(Messages, OdometryRoundTripAndValidation) {
  OdometrySample o;
  o.utime = 123456;
  o.position_m = {1.0, -2.0, 0.5};
  o.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  pose_t m = round_trip(to_lcm(o));
  OdometrySample back;
  std::string error;
  ASSERT_TRUE(from_lcm(m, back, error)) << error;
  EXPECT_EQ(back.utime, 123456);
  EXPECT_NEAR((back.position_m - o.position_m).norm(), 0.0, 1e-12);
  EXPECT_NEAR(back.orientation.angularDistance(o.orientation), 0.0, 1e-9);
  m.pos[1] = std::nan("");
  EXPECT_FALSE(from_lcm(m, back, error));
  EXPECT_NE(error.find("NaN"), std::string::npos);
  m = to_lcm(o);
  m.orientation[0] = 2.0;
  EXPECT_FALSE(from_lcm(m, back, error));
  EXPECT_NE(error.find("unit quaternion"), std::string::npos);
}

TEST(Messages, GroundTruthRoundTrip) {
  GroundTruth gt;
  gt.scene = "straight_up";
  Flight f;
  Step s;
  s.riser_height_m = 0.18;
  s.tread_depth_m = 0.25;
  s.nosing_m = {0.0, 0.0, 0.18};
  f.steps = {s};
  gt.flights = {f};
  GroundTruthFrame fr;
  fr.pitch_deg = -33;
  fr.roll_deg = 0.5;
  fr.height_m = 1.01;
  fr.distance_m = 1.4;
  fr.position_m = {-1.4, 0, 1.01};
  fr.visible_steps = {0, 1, 2};
  const ground_truth_t m = round_trip(to_lcm(gt, fr, 1000000, 7));
  GroundTruth gt2;
  GroundTruthFrame fr2;
  std::string error;
  ASSERT_TRUE(from_lcm(m, gt2, fr2, error)) << error;
  EXPECT_EQ(m.seq, 7);
  EXPECT_EQ(gt2.scene, "straight_up");
  EXPECT_NEAR(*gt2.flights[0].steps[0].riser_height_m, 0.18, 1e-6);
  EXPECT_NEAR(*fr2.distance_m, 1.4, 1e-6);
  EXPECT_EQ(fr2.visible_steps, (std::vector<int>{0, 1, 2}));
  EXPECT_NEAR(fr2.timestamp, 1.0, 1e-9);
}

TEST(Messages, DaemonStatusRoundTrip) {
  daemon_status_t s{};
  s.name = "stairs-perception";
  s.received = 10;
  s.dropped = 2;
  s.last_error = "queue full";
  const daemon_status_t back = round_trip(s);
  EXPECT_EQ(back.name, s.name);
  EXPECT_EQ(back.dropped, 2);
  EXPECT_EQ(back.last_error, "queue full");
}

TEST(Messages, WrongTypeOnChannelIsRejected) {
  const std::vector<uint8_t> buf = encode(to_lcm(sample_observation(), 1));
  depth_frame_t frame;
  std::string error;
  EXPECT_FALSE(decode_message(buf.data(), buf.size(), frame, error));
  EXPECT_NE(error.find("wrong message type"), std::string::npos) << error;
}

TEST(Messages, TruncatedAndOversizedAreRejected) {
  std::vector<uint8_t> buf = encode(to_lcm(sample_observation(), 1));
  stair_observation_t m;
  std::string error;
  for (size_t cut : {size_t{4}, size_t{20}, buf.size() / 2, buf.size() - 1})
    EXPECT_FALSE(decode_message(buf.data(), cut, m, error)) << cut;
  std::vector<uint8_t> huge(stair_observation_t::MAX_MESSAGE_BYTES + 1, 0);
  std::copy(buf.begin(), buf.end(), huge.begin());
  EXPECT_FALSE(decode_message(huge.data(), huge.size(), m, error));
  EXPECT_NE(error.find("cap"), std::string::npos) << error;
}

TEST(Messages, CorruptCountsNeverAllocateBeyondCaps) {
  // Overwrite the steps count with -1 and with 32767: decode must fail cleanly.
  Observation o = sample_observation();
  const std::vector<uint8_t> good = encode(to_lcm(o, 1));
  // num_steps follows hash(8) utime(8) source_utime(8) seq(4) camera pose(1+4+4+1+4+1+4+32) direction(1).
  const size_t off = 8 + 8 + 8 + 4 + (1 + 4 + 4 + 1 + 4 + 1 + 4 + 32) + 1;
  for (uint16_t v : {uint16_t{0xFFFF}, uint16_t{0x7FFF}}) {
    std::vector<uint8_t> bad = good;
    bad[off] = static_cast<uint8_t>(v >> 8);
    bad[off + 1] = static_cast<uint8_t>(v & 0xFF);
    stair_observation_t m;
    std::string error;
    EXPECT_FALSE(decode_message(bad.data(), bad.size(), m, error));
  }
  // A count within the int16 range but beyond the documented cap decodes but is refused.
  stair_observation_t m = to_lcm(o, 1);
  m.num_edges = stair_observation_t::MAX_EDGES + 1;
  m.edges.resize(m.num_edges);
  Observation back;
  std::string error;
  EXPECT_FALSE(from_lcm(round_trip(m), back, error));
}

// Found by fuzzing (tests/fuzz/corpus/*/string_length_int_min): lcm-gen's decoders
// let a negative string length through, and INT_MIN made a 100-byte message copy
// 2 GB (a segfault). lcmtypes/harden_strings.cmake requires every length >= 1.
TEST(Messages, ANegativeOrZeroStringLengthIsRejected) {
  tracker_command_t cmd{};
  cmd.utime = 1;
  cmd.command = tracker_command_t::COMMAND_RESET;
  cmd.reason = "ok";
  const std::vector<uint8_t> good = encode(cmd);
  const size_t at = 8 + 8 + 1;  // hash, utime, command: then the reason's int32 length
  for (uint32_t length : {0x80000000u, 0xFFFFFFFFu, 0u}) {
    std::vector<uint8_t> bad = good;
    for (int i = 0; i < 4; ++i) bad[at + i] = static_cast<uint8_t>(length >> (24 - 8 * i));
    tracker_command_t m;
    std::string error;
    EXPECT_FALSE(decode_message(bad.data(), bad.size(), m, error)) << std::hex << length;
    EXPECT_FALSE(error.empty());
  }
  tracker_command_t m;
  std::string error;
  ASSERT_TRUE(decode_message(good.data(), good.size(), m, error)) << error;
  EXPECT_EQ(m.reason, "ok");
}

TEST(Messages, NaNIsRejected) {
  Observation o = sample_observation();
  o.planes[0].points[3].x() = std::nanf("");
  Observation back;
  std::string error;
  EXPECT_FALSE(from_lcm(round_trip(to_lcm(o, 1)), back, error));
  EXPECT_NE(error.find("NaN"), std::string::npos);
  o = sample_observation();
  o.camera.pitch_deg = INFINITY;
  EXPECT_FALSE(from_lcm(round_trip(to_lcm(o, 1)), back, error));
}
