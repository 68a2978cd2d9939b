// stairs-eval --recorded (issue 18 item 4): a recording of what the daemons
// published is scored as it ran. The recording is made here the way a live
// chain makes it: the input log's messages, and after each depth frame the
// observation and model that perception and the tracker published for it,
// except for the frames the "live chain" dropped.
#include "common/lcm_bridge.hpp"
#include "common/lcm_log.hpp"
#include "chain/offline_chain.hpp"
#include "tools/recorded.hpp"
#include "tools/replay.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace stairs::eval {
namespace {

const std::string kLog = std::string(STAIRS_SOURCE_DIR) + "/logs/up_handheld.lcmlog";
constexpr int kFrames = 30;

bool dropped(int frame) { return frame % 5 == 3; }

// Copies kLog's first kFrames depth frames (with everything logged between them)
// to `path`, each followed by its observation and model unless dropped(frame).
StairModel record(const std::string& path) {
  LogReader in(kLog);
  LogWriter out(path);
  OfflineChain chain;
  LogEvent ev;
  std::string error;
  int frame = 0;
  while (in.next(ev)) {
    if (ev.channel == "STAIRS_DEPTH" && frame == kFrames) break;  // the last frame's truth is in
    out.write(ev.channel, ev.timestamp_us, ev.data.data(), ev.data.size());
    if (ev.channel != "STAIRS_DEPTH") continue;
    depth_frame_t msg;
    DepthImage image;
    if (!decode_message(ev.data.data(), ev.data.size(), msg, error) || !from_lcm(msg, image, error))
      throw std::runtime_error(error);
    if (!dropped(frame)) {
      const ChainStep step = chain.process(image);
      const Observation& obs = step.observation;
      out.write_message("STAIRS_OBSERVATION", ev.timestamp_us + 3000, to_lcm(obs, ev.timestamp_us + 3000));
      out.write_message("STAIRS_MODEL", ev.timestamp_us + 4000,
                        to_lcm(*step.model, ev.timestamp_us + 4000, obs.source_utime, obs.source_seq));
    }
    ++frame;
  }
  out.close();
  return chain.model();
}

TEST(EvalRecorded, ScoresWhatWasPublishedAndCountsDroppedFramesAsMissed) {
  const std::string path = (std::filesystem::temp_directory_path() / "stairs_recorded_test.lcmlog").string();
  const StairModel live_model = record(path);
  const RunResult recorded = score_recorded(path, RecordedOptions{});
  ReplayOptions replay_options;
  replay_options.max_frames = kFrames;
  const RunResult replayed = replay(kLog, replay_options);
  std::filesystem::remove(path);

  ASSERT_TRUE(recorded.recorded && recorded.score && replayed.score);
  EXPECT_EQ(recorded.frames_processed, kFrames);
  EXPECT_EQ(recorded.recorded->frames_without_observation, kFrames / 5);
  EXPECT_EQ(recorded.recorded->observations, kFrames - kFrames / 5);
  EXPECT_EQ(recorded.recorded->models, kFrames - kFrames / 5);
  EXPECT_EQ(recorded.recorded->frames_without_model, 0);
  const auto real_matches = [](const std::vector<int>& m) {
    return std::count_if(m.begin(), m.end(), [](int k) { return k >= 0; });
  };
  long missed_visible = 0;
  for (int i = 0; i < kFrames; ++i) {
    const auto& rec = recorded.score->frames.at(i);
    const auto& rep = replayed.score->frames.at(i);
    ASSERT_TRUE(rec && rep) << "frame " << i;
    EXPECT_EQ(rec->visible, rep->visible) << "frame " << i;
    if (dropped(i)) {
      // What the robot did not get counts against the run: nothing matched, nothing tracked.
      EXPECT_EQ(real_matches(rec->matched), 0) << "frame " << i;
      EXPECT_NE(recorded.frames[i].status.find("no observation recorded"), std::string::npos);
      EXPECT_FALSE(recorded.frames[i].tracked_camera->valid);
      missed_visible += real_matches(rep->matched);
    } else {
      // Perception is per frame: what it published is what the replay computes.
      EXPECT_EQ(rec->matched, rep->matched) << "frame " << i;
      EXPECT_EQ(recorded.frames[i].steps.size(), replayed.frames[i].steps.size()) << "frame " << i;
    }
  }
  EXPECT_GT(missed_visible, 0) << "the dropped frames had steps to miss";
  EXPECT_EQ(recorded.score->frame_steps_matched, replayed.score->frame_steps_matched - missed_visible);
  // The final model is the last one published.
  ASSERT_TRUE(recorded.model);
  ASSERT_EQ(recorded.model->flights.size(), live_model.flights.size());
  for (size_t k = 0; k < live_model.flights.size(); ++k)
    EXPECT_EQ(recorded.model->flights[k].steps.size(), live_model.flights[k].steps.size());
}

TEST(EvalRecorded, ALogWithoutTheDaemonsOutputIsAnErrorNamingTheChannel) {
  try {
    score_recorded(kLog, RecordedOptions{});
    FAIL() << "a log with only depth frames was scored as a recorded run";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(kLog), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("STAIRS_OBSERVATION"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stairs::eval
