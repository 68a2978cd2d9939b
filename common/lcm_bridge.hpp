// Conversion between the core types (common/types.hpp) and the LCM messages,
// with validation. Every daemon decodes through decode_message(), which
// enforces the size caps documented in lcmtypes/*.lcm before any allocation.
#pragma once

#include "common/types.hpp"

#include <stairs/daemon_status_t.hpp>
#include <stairs/depth_frame_t.hpp>
#include <stairs/ground_truth_t.hpp>
#include <stairs/imu_t.hpp>
#include <stairs/pose_t.hpp>
#include <stairs/stair_model_t.hpp>
#include <stairs/stair_observation_t.hpp>
#include <stairs/tracker_command_t.hpp>

#include <string>

namespace stairs {

// Decodes a message of type T from a received buffer. Rejects a buffer larger
// than the type's cap, a wrong type (fingerprint), a truncated or corrupt
// encoding, and (for depth frames) declared array sizes larger than the buffer.
// Never throws; returns false with a one-line reason.
template <class T>
bool decode_message(const void* data, size_t size, T& msg, std::string& error);

// decode_message, then from_lcm: the message and its checked core value, or
// false with the reason (what every receiver does with a buffer).
template <class Msg, class Value>
bool decode_and_convert(const void* data, size_t size, Msg& msg, Value& value, std::string& error);

// Largest encoded size accepted for a type, bytes.
template <class T>
size_t max_message_bytes();

// --- depth frames ---------------------------------------------------------
// zlib_level 0 = raw, 1..9 = zlib.
depth_frame_t to_lcm(const DepthImage& img, int zlib_level, const std::string& frame_id = "camera");
// Validates sizes, caps, encoding, intrinsics, NaN/inf, zlib; rejects a frame
// whose depth is zero everywhere.
bool from_lcm(const depth_frame_t& msg, DepthImage& img, std::string& error);

// --- observations and models ----------------------------------------------
stair_observation_t to_lcm(const Observation& obs, int64_t utime);
bool from_lcm(const stair_observation_t& msg, Observation& obs, std::string& error);

stair_model_t to_lcm(const StairModel& model, int64_t utime, int64_t source_utime, int32_t source_seq);
// The model without its planes (point samples): steps, flights and camera only,
// about 1 KB instead of 20 for a robot that sends the model over Wi-Fi. Steps'
// plane indices become -1, as they would point into planes no longer there.
stair_model_t steps_only(stair_model_t model);
bool from_lcm(const stair_model_t& msg, StairModel& model, std::string& error);

// --- ground truth -----------------------------------------------------------
ground_truth_t to_lcm(const GroundTruth& gt, const GroundTruthFrame& frame, int64_t utime, int32_t seq);
// Fills gt.scene, gt.flights and frame.
bool from_lcm(const ground_truth_t& msg, GroundTruth& gt, GroundTruthFrame& frame, std::string& error);

// Step and flight conversions used by the above (and by tools that build messages).
// --- odometry ------------------------------------------------------------------
pose_t to_lcm(const OdometrySample& o);
// Rejects non-finite values and an orientation whose norm is off 1 by more than 1e-3.
bool from_lcm(const pose_t& msg, OdometrySample& o, std::string& error);

// --- inertial -------------------------------------------------------------------
imu_t to_lcm(const ImuSample& s);
// Rejects non-finite values.
bool from_lcm(const imu_t& msg, ImuSample& s, std::string& error);

step_t to_lcm(const Step& s);
Step from_lcm(const step_t& s);
plane_t to_lcm(const Plane& p);
Plane from_lcm(const plane_t& p);

template <class Msg, class Value>
bool decode_and_convert(const void* data, size_t size, Msg& msg, Value& value, std::string& error) {
  return decode_message(data, size, msg, error) && from_lcm(msg, value, error);
}

}  // namespace stairs
