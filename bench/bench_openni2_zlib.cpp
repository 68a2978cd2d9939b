// Size and CPU cost of the depth_frame_t zlib levels on simulated Kinect v1
// frames (every sensor effect on), to choose stairs-openni2's --zlib default.
// Reports bytes/frame (counter) and time per frame, levels 0, 1, 3, 6; and the
// receiving side's decode per frame, raw and level 1.
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

// What the perception daemon spends on a frame before perception: the LCM message decoded and
// inflated into an image, both reused from frame to frame as the daemon keeps them.
void BM_DepthFrameDecode(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  std::vector<std::vector<uint8_t>> encoded;
  for (const stairs::DepthImage& img : frames()) {
    const stairs::depth_frame_t m = stairs::to_lcm(img, level);
    encoded.emplace_back(static_cast<size_t>(m.getEncodedSize()));
    m.encode(encoded.back().data(), 0, static_cast<int>(encoded.back().size()));
  }
  stairs::depth_frame_t msg;
  stairs::DepthImage img;
  std::string error;
  size_t i = 0;
  for (auto _ : state) {
    const std::vector<uint8_t>& buf = encoded[i++ % encoded.size()];
    if (!stairs::decode_message(buf.data(), buf.size(), msg, error) || !stairs::from_lcm(msg, img, error))
      state.SkipWithError(error.c_str());
    benchmark::DoNotOptimize(img.depth.data());
  }
}
BENCHMARK(BM_DepthFrameDecode)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

}  // namespace

BENCHMARK_MAIN();
