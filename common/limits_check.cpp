// common/limits.hpp must agree with the message definitions it mirrors.
#include "common/limits.hpp"

#include <stairs/flight_t.hpp>
#include <stairs/plane_t.hpp>
#include <stairs/stair_model_t.hpp>
#include <stairs/stair_observation_t.hpp>

namespace stairs::limits {

static_assert(kObservationSteps == stair_observation_t::MAX_STEPS);
static_assert(kObservationPlanes == stair_observation_t::MAX_PLANES);
static_assert(kObservationEdges == stair_observation_t::MAX_EDGES);
static_assert(kPlanePoints == plane_t::MAX_POINTS);
static_assert(kModelFlights == stair_model_t::MAX_FLIGHTS);
static_assert(kFlightSteps == flight_t::MAX_STEPS);
static_assert(kModelPlanes == stair_model_t::MAX_PLANES);

}  // namespace stairs::limits
