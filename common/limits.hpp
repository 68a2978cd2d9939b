// The message caps (lcmtypes/*.lcm) that the algorithms and their configs must
// respect, in one place: the libraries know nothing of LCM, so they read these;
// common/limits_check.cpp static_asserts each against the lcm-gen constant.
#pragma once

namespace stairs::limits {

constexpr int kObservationSteps = 64;    // stair_observation_t.MAX_STEPS
constexpr int kObservationPlanes = 256;  // stair_observation_t.MAX_PLANES
constexpr int kObservationEdges = 256;   // stair_observation_t.MAX_EDGES
constexpr int kPlanePoints = 1024;       // plane_t.MAX_POINTS: a plane's point sample
constexpr int kModelFlights = 16;        // stair_model_t.MAX_FLIGHTS
constexpr int kFlightSteps = 128;        // flight_t.MAX_STEPS
constexpr int kModelPlanes = 1024;       // stair_model_t.MAX_PLANES

}  // namespace stairs::limits
