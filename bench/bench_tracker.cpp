// Tracker::update latency on one core over whole walks of hand-built
// observations (drivers/sim/synthetic_observations.hpp) with perception's cap of 1024
// points per tread/riser. Counters: median and p95 of a single update, ms of
// thread CPU time.
#include "drivers/sim/synthetic_observations.hpp"
#include "tracker/tracker.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <ctime>

namespace {

using namespace stairs;

std::vector<Observation> sequence(bool ascending, int points, int fps_divisor) {
  const auto g = synthetic::make_stair(12, 0.17, 0.28, 1.5, 5, 1.2);
  synthetic::ObservationMaker maker(g, 42, points);
  const auto cams = synthetic::walk(g, ascending, 0.6, 30.0);
  std::vector<Observation> out;
  for (size_t k = 0; k < cams.size(); k += fps_divisor)
    out.push_back(maker.make(cams[k], static_cast<int64_t>(k) * 33333));
  return out;
}

// Thread CPU time: the machine is shared, wall time would measure the neighbours.
double cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * v.size()))];
}

// One iteration = one update; the tracker restarts at the end of the walk.
void BM_TrackerUpdate(benchmark::State& state) {
  const auto obs = sequence(state.range(0) != 0, 1024, static_cast<int>(state.range(1)));
  Tracker tracker;
  std::vector<double> ms;
  size_t i = 0;
  for (auto _ : state) {
    const double t0 = cpu_ms();
    benchmark::DoNotOptimize(tracker.update(obs[i]));
    ms.push_back(cpu_ms() - t0);
    if (++i == obs.size()) {
      state.PauseTiming();
      tracker.reset();
      i = 0;
      state.ResumeTiming();
    }
  }
  state.counters["median_ms"] = percentile(ms, 0.5);
  state.counters["p95_ms"] = percentile(ms, 0.95);
  state.counters["observations"] = static_cast<double>(obs.size());
}

}  // namespace

// Args: ascending (1) / descending (0), frame divisor (1 = 30 fps, 2 = 15 fps).
BENCHMARK(BM_TrackerUpdate)->Args({1, 1})->Args({0, 1})->Args({1, 2})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
