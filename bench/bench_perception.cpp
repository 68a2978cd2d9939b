// Full-pipeline and per-stage latency on stairs-sim frames (Kinect v1 sensor
// model on), one core. Counters are medians over the iterations, ms.
#include "drivers/sim/render.hpp"
#include "drivers/sim/trajectory.hpp"
#include "perception/pipeline.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>

namespace {

std::vector<stairs::DepthImage> frames(int w, int h, bool descending) {
  const stairs::sim::Scene scene = stairs::sim::make_preset(descending ? "straight_down" : "straight_up");
  const stairs::Intrinsics K{w, h, 525.0 * w / 640, 525.0 * w / 640, (w - 1) / 2.0, (h - 1) / 2.0};
  stairs::sim::Renderer renderer(scene, K, stairs::sim::SensorModel{}, 11);
  stairs::sim::TrajectoryConfig tc = stairs::sim::trajectory_defaults(stairs::sim::Carrier::HandHeld);
  tc.descending = descending;
  const stairs::sim::Trajectory traj(scene, tc);
  std::vector<stairs::DepthImage> out;
  for (int i = 0; i < traj.frames(); i += std::max(1, traj.frames() / 16))
    out.push_back(renderer.render(traj.pose(i), i, i));
  return out;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

void BM_Pipeline(benchmark::State& state) {
  const int w = static_cast<int>(state.range(0)), h = w * 3 / 4;
  const auto imgs = frames(w, h, state.range(1) != 0);
  stairs::Pipeline pipeline;
  std::map<std::string, std::vector<double>> stages;
  std::vector<double> total;
  size_t i = 0;
  for (auto _ : state) {
    const stairs::Observation o = pipeline.process(imgs[i++ % imgs.size()]);
    benchmark::DoNotOptimize(o.steps.data());
    total.push_back(o.latency_ms);
    for (const auto& s : o.stages) stages[s.name].push_back(s.ms);
  }
  state.counters["median_ms"] = median(total);
  std::vector<double> sorted = total;
  std::sort(sorted.begin(), sorted.end());
  state.counters["p95_ms"] = sorted[static_cast<size_t>(0.95 * (sorted.size() - 1))];
  for (const auto& [name, v] : stages) state.counters[name] = median(v);
}

BENCHMARK(BM_Pipeline)->Args({640, 0})->Args({640, 1})->Args({320, 0})->Args({320, 1})->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
