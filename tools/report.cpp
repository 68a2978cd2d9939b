#include "tools/report.hpp"

#include <cstdio>
#include <string>

namespace stairs::eval {
namespace {

template <typename... A>
std::string fmt(const char* f, A... a) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a...);
  return buf;
}

std::string num(const std::optional<double>& v, const char* f = "%.2f") { return v ? fmt(f, *v) : "n/a"; }

void print_error_row(std::ostream& out, const char* name, const ErrorStats& e) {
  out << fmt("  %-26s %12s %10s %5d\n", name, num(e.mean_signed).c_str(), num(e.mean_abs).c_str(), e.n);
}

void print_score(std::ostream& out, const Score& s) {
  out << "Table 6.1  per-frame step detection: "
      << (s.frame_step_detection ? fmt("%.1f %%", 100.0 * *s.frame_step_detection) : std::string("n/a"))
      << fmt("  (%d of %d visible steps, %d frames)\n", s.frame_steps_matched, s.visible_steps, s.frames_scored);
  if (s.frame_step_detection_nosing_in_view)
    out << fmt("  of the visible steps whose nosing is in the image: %.1f %%  (%d of %d)\n",
               100.0 * *s.frame_step_detection_nosing_in_view, s.frame_steps_matched_nosing_in_view,
               s.visible_steps_nosing_in_view);
  if (s.frame_step_detection_tracked)
    out << fmt("  tracked (the model's steps from its camera): %.1f %%  (%d of %d), %d false\n",
               100.0 * *s.frame_step_detection_tracked, s.tracked_steps_matched, s.visible_steps,
               s.tracked_false_steps);
  if (s.model_scored) {
    out << "Tables 6.2/6.3  final model error (cm)  mean signed  mean abs     n\n";
    print_error_row(out, "riser", s.riser_error_cm);
    print_error_row(out, "tread (landing excluded)", s.tread_error_cm);
    out << fmt("Table 6.4  model steps detected/real: %d/%d  (model origin on real step %d)\n",
               s.model_steps_detected, s.model_steps_real, s.model_step_offset);
  } else {
    out << "Tables 6.2-6.4: no model (tracker not run)\n";
  }
  out << fmt("False steps: %d in %d of %d frames", s.frame_false_steps, s.frames_with_false_steps, s.frames_scored)
      << (s.model_scored ? fmt("; %d in the model\n", s.model_false_steps) : std::string("\n"));
  out << fmt("Camera pose error, mean abs over %d valid of %d frames: pitch %s deg, roll %s deg, height %s cm\n",
             s.pose_frames_valid, s.frames_scored, num(s.pitch_error_deg.mean_abs).c_str(),
             num(s.roll_error_deg.mean_abs).c_str(), num(s.height_error_cm.mean_abs).c_str());
  out << fmt("  height where the surface beneath is in view: %s cm over %d frames\n",
             num(s.height_error_beneath_visible_cm.mean_abs).c_str(), s.height_error_beneath_visible_cm.n);
  if (s.tracked_camera_coverage)
    out << fmt("Tracked camera over %d frames (%.1f %% of frames since the first): height %s cm, "
               "step beneath right %s %%, position along the stair %s cm\n",
               s.tracked_camera_frames, 100.0 * *s.tracked_camera_coverage,
               num(s.tracked_height_error_cm.mean_abs).c_str(),
               s.tracked_step_index_accuracy ? fmt("%.1f", 100.0 * *s.tracked_step_index_accuracy).c_str() : "n/a",
               num(s.tracked_position_error_cm.mean_abs).c_str());
  if (s.tracked_base_frames > 0)
    out << fmt("Tracked robot base (mount) over %d frames: height %s cm, step beneath right %s %%\n",
               s.tracked_base_frames, num(s.tracked_base_height_error_cm.mean_abs).c_str(),
               s.tracked_base_step_index_accuracy ? fmt("%.1f", 100.0 * *s.tracked_base_step_index_accuracy).c_str()
                                                  : "n/a");
}

void print_model(std::ostream& out, const StairModel& m) {
  out << "Final model: " << direction_name(m.direction) << ", " << m.flights.size() << " flight(s), "
      << m.observations_fused << " observations fused\n";
  for (size_t f = 0; f < m.flights.size(); ++f) {
    out << fmt("  flight %zu, width %.2f m\n", f + 1, m.flights[f].width_m);
    out << "     #   riser cm   tread cm   nosing x m   nosing z m\n";
    const auto& steps = m.flights[f].steps;
    for (size_t i = 0; i < steps.size(); ++i) {
      const Step& s = steps[i];
      const std::optional<double> riser = s.riser_height_m ? std::optional<double>(100 * *s.riser_height_m) : std::nullopt;
      const std::optional<double> tread = s.tread_depth_m ? std::optional<double>(100 * *s.tread_depth_m) : std::nullopt;
      out << fmt("  %4zu %10s %10s %12.3f %12.3f%s\n", i + 1, num(riser).c_str(), num(tread).c_str(),
                 s.nosing_m.x(), s.nosing_m.z(), s.landing ? "   landing" : "");
    }
  }
}

}  // namespace

void print_report(std::ostream& out, const RunResult& r) {
  out << "stairs-eval: " << r.input << "\n"
      << fmt("frames: %d processed of %d (%d invalid skipped)\n\n", r.frames_processed, r.frames_total,
             r.frames_invalid);
  if (r.recorded)
    out << fmt("recorded live run, scored as it ran: %d observations, %d models (%d rejected); "
               "%d frames without an observation (missed), %d without a model\n\n",
               r.recorded->observations, r.recorded->models, r.recorded->rejected_messages,
               r.recorded->frames_without_observation, r.recorded->frames_without_model);
  if (r.score)
    print_score(out, *r.score);
  else
    out << "No ground truth: no scores.\n";
  out << "\n";
  if (r.model) print_model(out, *r.model);
  out << "\nLatency (ms)                       median       p95      n\n";
  for (const auto& [name, l] : latency_by_stage(r.frames))
    out << fmt("  %-30s %9.2f %9.2f %6d\n", name.c_str(), l.median_ms, l.p95_ms, l.n);
}

}  // namespace stairs::eval
