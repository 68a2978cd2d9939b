// stairs-sim's command line: scene (preset or scenario file, with overrides),
// camera, sensor and trajectory, all from Options.
#pragma once

#include "drivers/sim/sensor.hpp"
#include "drivers/sim/trajectory.hpp"

#include "common/daemon.hpp"

#include <nlohmann/json.hpp>

namespace stairs::sim {

struct SimSetup {
  Scene scene;
  Intrinsics K;
  SensorModel sensor;
  TrajectoryConfig trajectory;
  uint64_t seed = 1;
};

void add_setup_options(Options& o);
// Throws std::runtime_error naming the option or file on bad values.
SimSetup setup_from_options(const Options& o);
// For the "extra keys" of groundtruth.json.
nlohmann::json setup_to_json(const SimSetup& s);

}  // namespace stairs::sim
