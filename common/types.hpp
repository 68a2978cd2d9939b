// Core value types shared by perception, tracker, eval and viewer. No LCM here:
// common/lcm_bridge.hpp converts to and from the messages of lcmtypes/.
//
// Frames (DESIGN.md): camera optical frame x right, y down, z forward;
// gravity-aligned camera frame x forward, y left, z up; stair frame x along the
// ascending direction, y left, z up, origin on the floor at the first riser.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace stairs {

struct Intrinsics {
  int width = 0;    // px
  int height = 0;   // px
  double fx = 0.0;  // px
  double fy = 0.0;  // px
  double cx = 0.0;  // px
  double cy = 0.0;  // px
};

// One depth image, row-major, 0 = no measurement.
struct DepthImage {
  Intrinsics K;
  double depth_scale = 0.001;  // metres per unit
  std::vector<uint16_t> depth;
  int64_t utime = 0;  // us since the epoch (or since the start of a sequence)
  int32_t seq = 0;

  float metres(int u, int v) const {
    return static_cast<float>(depth[static_cast<size_t>(v) * K.width + u] * depth_scale);
  }
};

struct CameraPose {
  bool valid = false;
  double pitch_deg = 0.0;  // optical axis below (negative) / above the horizon
  double roll_deg = 0.0;   // positive = camera's right side down
  std::optional<double> height_m;    // above the horizontal surface beneath
  std::optional<double> distance_m;  // horizontal, to the first step edge ahead
  // Camera optical frame -> gravity-aligned camera frame.
  Eigen::Quaterniond gravity_rotation = Eigen::Quaterniond::Identity();
};

enum class PlaneKind : int8_t { Other = 0, Tread = 1, Riser = 2, Landing = 3 };
enum class PlaneSource : int8_t { Segmented = 0, Edges = 1, Reconstructed = 2 };

struct Plane {
  PlaneKind kind = PlaneKind::Other;
  PlaneSource source = PlaneSource::Segmented;
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();  // m
  // Bounding box (thesis Algorithm 5): top-left, top-right, bottom-left,
  // bottom-right. Left = +y. Top = far edge of a tread, upper edge of a riser.
  enum Corner { kTopLeft = 0, kTopRight = 1, kBottomLeft = 2, kBottomRight = 3 };
  std::array<Eigen::Vector3f, 4> corners{};
  float length_m = 0.0f;  // extent along y
  float extent_m = 0.0f;  // tread depth or riser height
  int support = 0;        // depth pixels in the segment
  std::vector<Eigen::Vector3f> points;  // downsampled sample, m
};

enum class EdgeType : int8_t { Unknown = 0, Convex = 1, Concave = 2 };
enum class EdgeSource : int8_t { NormalImage = 0, DepthJump = 1 };

struct Edge {
  EdgeType type = EdgeType::Unknown;
  EdgeSource source = EdgeSource::NormalImage;
  Eigen::Vector3f start = Eigen::Vector3f::Zero();  // m
  Eigen::Vector3f end = Eigen::Vector3f::Zero();    // m
  Eigen::Vector2f start_px = Eigen::Vector2f::Zero();
  Eigen::Vector2f end_px = Eigen::Vector2f::Zero();
  int support = 0;
};

// One riser and the tread above it.
struct Step {
  int riser_plane = -1;  // index into the owner's planes, -1 = none
  int tread_plane = -1;
  bool landing = false;
  std::optional<double> riser_height_m;
  std::optional<double> tread_depth_m;
  double width_m = 0.0;
  // Nosing (riser top meets tread front), x forward, y left, z up, m.
  Eigen::Vector3d nosing_m = Eigen::Vector3d::Zero();
  int confirmations = 1;
  // What of this step was not seen but inferred (an observation's steps only;
  // kStep* bits): a value flagged here is a prior, not a measurement.
  uint8_t inferred = 0;
};

// Step::inferred bits (stair_observation_t.step_inferred).
constexpr uint8_t kStepRiserInferred = 1;   // riser height not measured: the chain's median rise,
                                            // or a level from a riser's top (a nosing may hide it)
constexpr uint8_t kStepNosingInferred = 2;  // nosing height from the median rise (riser top out of view)
constexpr uint8_t kStepWidthPartial = 4;    // width is what was seen: the tread is cut by the view
constexpr uint8_t kStepTreadPartial = 8;    // tread depth is the visible part only (no next nosing)

enum class Direction : int8_t { None = 0, Up = 1, Down = 2 };

struct StageLatency {
  std::string name;
  double ms = 0.0;
};

// Perception's result for one frame; positions in the gravity-aligned camera
// frame relative to the camera centre.
struct Observation {
  int64_t source_utime = 0;
  int32_t source_seq = 0;
  CameraPose camera;
  Direction direction = Direction::None;
  std::vector<Step> steps;  // nearest first
  std::vector<Plane> planes;
  std::vector<Edge> edges;
  std::vector<StageLatency> stages;
  double latency_ms = 0.0;
  std::string status;
};

struct Flight {
  double width_m = 0.0;
  std::vector<Step> steps;  // bottom to top, stair frame
};

enum class TrackingState : int8_t { None = 0, Ok = 1, Lost = 2, Relocalised = 3 };

// The tracker's incremental model; positions in the stair frame.
struct StairModel {
  TrackingState state = TrackingState::None;
  Direction direction = Direction::None;
  std::vector<Flight> flights;
  bool camera_valid = false;
  Eigen::Vector3d camera_position_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond camera_orientation = Eigen::Quaterniond::Identity();  // optical -> stair
  double camera_height_m = 0.0;
  int camera_step_index = -1;  // -1 = floor before the first step
  // camera_height_m and camera_step_index hold: the camera is over a part of
  // the stair the model has seen (false beyond its far end).
  bool camera_beneath_known = false;
  // camera_height_m holds (camera_beneath_known, and the height was measured, or carried along the
  // stair's mean slope without crossing a flight's end, or its mount or odometry gives the carrier).
  bool camera_height_known = false;
  // How far off camera_position_m may be along the stair (m): the registration's uncertainty, plus
  // what the motion prior may have drifted since; the base's position is as uncertain. -1 without
  // a camera.
  double camera_position_uncertainty_m = -1.0;
  // The carrier's base frame (common/mount.hpp camera_in_base: x forward, y left, z up, origin on the
  // ground beneath the camera), from the camera and the config's "mount"; valid only with both.
  bool base_valid = false;
  Eigen::Vector3d base_position_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond base_orientation = Eigen::Quaterniond::Identity();  // base -> stair
  double base_height_m = 0.0;  // base origin above the surface beneath
  int base_step_index = -1;    // step beneath the base origin, -1 = floor before the first step
  bool base_beneath_known = false;  // as camera_beneath_known, for the base origin
  bool base_height_known = false;   // as camera_height_known, for the base origin
  int observations_fused = 0;
  bool confirmed = false;  // enough observations agree on the same steps (flights are empty until then)
  double registration_rmse_m = -1.0;
  double registration_inlier_ratio = 0.0;
  double update_latency_ms = 0.0;
  std::vector<Plane> planes;
  std::string status;
};

// The camera optical frame's pose in a drifting odometry frame (z up):
// DESIGN.md odometry.txt, channel STAIRS_ODOMETRY (stairs.pose_t).
struct OdometrySample {
  int64_t utime = 0;  // us
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // optical -> odometry
};

// One inertial sample (DESIGN.md imu.txt, channel STAIRS_IMU), in the camera
// optical frame once perception has applied its imu_to_camera rotation.
struct ImuSample {
  int64_t utime = 0;                                        // us
  Eigen::Vector3d specific_force_mps2 = Eigen::Vector3d::Zero();  // at rest +9.81 along up
  Eigen::Vector3d angular_rate_radps = Eigen::Vector3d::Zero();
};

// Ground truth of one frame (groundtruth.json "frames" / ground_truth_t).
struct GroundTruthFrame {
  double timestamp = 0.0;  // s
  double pitch_deg = 0.0;
  double roll_deg = 0.0;
  double height_m = 0.0;
  std::optional<double> distance_m;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // optical -> stair
  std::vector<int> visible_steps;
};

struct GroundTruth {
  std::string scene;
  std::vector<Flight> flights;  // steps carry riser, tread, landing and nosing (x, 0, z)
  std::vector<GroundTruthFrame> frames;
};

}  // namespace stairs
