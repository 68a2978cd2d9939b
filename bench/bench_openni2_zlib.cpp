// Size and CPU cost of the depth_frame_t zlib levels on simulated Kinect v1
// frames (every sensor effect on), to choose stairs-openni2's --zlib default.
// Reports bytes/frame (counter) and time per frame, levels 0, 1, 3, 6.
#include "common/lcm_bridge.hpp"
#include "drivers/sim/render.hpp"
#include "drivers/sim/scene.hpp"
#include "drivers/sim/trajectory.hpp"

#include <benchmark/benchmark.h>

#include <cmath>

namespace {

const std::vector<stairs::DepthImage>& frames() {
  static const std::vector<stairs::DepthImage> f = [] {
    using namespace stairs::sim;
    const Scene scene = make_preset("straight_up");
    const stairs::Intrinsics K{640, 480, 320.0 / std::tan(0.5 * 1.0144686), 240.0 / std::tan(0.5 * 0.7898094), 319.5,
                               239.5};
    Renderer r(scene, K, SensorModel{}, 1);
    const Trajectory traj(scene, trajectory_defaults(Carrier::HandHeld));
    std::vector<stairs::DepthImage> out;
    for (int i = 0; i < 30; ++i) out.push_back(r.render(traj.pose(i * traj.frames() / 30), i * 33'333, i));
    return out;
  }();
  return f;
}

void BM_DepthFrameZlib(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  const auto& f = frames();
  size_t i = 0, bytes = 0, n = 0;
  for (auto _ : state) {
    const stairs::depth_frame_t m = stairs::to_lcm(f[i++ % f.size()], level);
    benchmark::DoNotOptimize(m.data.data());
    bytes += m.data.size();
    ++n;
  }
  state.counters["bytes_per_frame"] = static_cast<double>(bytes) / n;
  state.counters["ratio"] = static_cast<double>(bytes) / n / (640.0 * 480 * 2);
}
BENCHMARK(BM_DepthFrameZlib)->Arg(0)->Arg(1)->Arg(3)->Arg(6)->Unit(benchmark::kMillisecond)->Repetitions(5)
    ->ReportAggregatesOnly(true);

}  // namespace

BENCHMARK_MAIN();
