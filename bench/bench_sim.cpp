// Frames per second of the simulator on one core: render, and render + ground
// truth (what stairs-sim does per frame), over a hand-held walk up the stair.
#include "drivers/sim/render.hpp"
#include "drivers/sim/trajectory.hpp"

#include "common/cloud.hpp"

#include <benchmark/benchmark.h>

using namespace stairs;
using namespace stairs::sim;

namespace {

void run(benchmark::State& state, bool with_truth) {
  const int width = static_cast<int>(state.range(0));
  const bool perfect = state.range(1) != 0;
  const Scene scene = make_preset("cluttered");
  const Intrinsics K = scale_intrinsics({640, 480, 525.0, 525.0, 319.5, 239.5}, width, width * 3 / 4);
  SensorModel sensor;
  sensor.perfect = perfect;
  Renderer r(scene, K, sensor, 1);
  const Trajectory traj(scene, trajectory_defaults(Carrier::HandHeld));
  int f = 0;
  for (auto _ : state) {
    const Eigen::Isometry3d T = traj.pose(f % traj.frames());
    DepthImage img = r.render(T, 0, f);
    if (with_truth) benchmark::DoNotOptimize(r.truth(T, 0.0, img));
    benchmark::DoNotOptimize(img.depth.data());
    ++f;
  }
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_Render(benchmark::State& s) { run(s, false); }
void BM_RenderAndTruth(benchmark::State& s) { run(s, true); }

}  // namespace

// Args: width (height = 3/4 width), perfect (0 = full Kinect model, 1 = noiseless).
BENCHMARK(BM_Render)->Args({640, 0})->Args({640, 1})->Args({320, 0})->Args({160, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RenderAndTruth)->Args({640, 0})->Args({320, 0})->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
