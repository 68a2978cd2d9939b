"""stairs-model-csv and stairs_lcmlog on a real recording: a log played
through the live chain (scripts/run-live: lcm-logplayer, stairs-perception,
stairs-tracker, lcm-logger over UDP multicast on loopback). Exit 77 = skipped."""

import csv
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest

SRC = os.environ["STAIRS_SOURCE_DIR"]
BUILD = os.environ["BUILD_DIR"]
SCRIPT = os.path.join(SRC, "python", "stairs-model-csv")
LOG = os.path.join(SRC, "logs", "up_handheld.lcmlog")
URL = "udpm://239.255.76.67:7685?ttl=0&recv_buf_size=4194304"
sys.path[:0] = [os.path.join(SRC, "python"), os.path.join(BUILD, "lcmtypes", "gen", "python")]
import stairs_lcmlog  # noqa: E402
from stairs import ground_truth_t  # noqa: E402


def run(*args):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, env=dict(os.environ))


class ModelCsv(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="stairs_python_test_")
        cls.rec = os.path.join(cls.tmp, "live.lcmlog")
        if os.geteuid() == 0:  # multicast on loopback needs a route where there is no default one
            subprocess.run(["ip", "route", "add", "224.0.0.0/4", "dev", "lo"], capture_output=True)
        r = run(os.path.join(SRC, "scripts", "run-live"), "--log", LOG, "--lcm-url", URL, "--record", cls.rec)
        if r.returncode != 0:
            raise RuntimeError(f"run-live failed: {r.stderr}")
        cls.channels = {}
        for ev in stairs_lcmlog.read_events(cls.rec):
            cls.channels.setdefault(ev.channel, []).append(ev)
        if "STAIRS_MODEL" not in cls.channels and os.geteuid() != 0:
            print("skipped: no multicast on loopback here (run as root to add the route)")
            sys.exit(77)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_one_row_per_model_and_the_final_models_steps(self):
        frames_csv = os.path.join(self.tmp, "frames.csv")
        steps_csv = os.path.join(self.tmp, "steps.csv")
        plot = os.path.join(self.tmp, "plot.png")
        r = run(SCRIPT, self.rec, "--csv", frames_csv, "--steps-csv", steps_csv, "--plot", plot)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(frames_csv) as f:
            frames = list(csv.DictReader(f))
        # One model per depth frame went through the chain, and one row per model.
        self.assertEqual(len(self.channels["STAIRS_DEPTH"]), 90)
        self.assertEqual(len(frames), len(self.channels["STAIRS_MODEL"]))
        self.assertEqual(len(frames), 90)
        # The camera height per frame is the tracker's, against the truth of that frame.
        truths = [ground_truth_t.decode(ev.data) for ev in self.channels["STAIRS_GROUND_TRUTH"]]
        true_height = {g.utime: g.height_m for g in truths}
        errors = [abs(float(r["camera_height_m"]) - true_height[int(r["source_utime"])])
                  for r in frames if r["camera_height_m"]]
        self.assertGreater(len(errors), 45)
        self.assertLess(sum(errors) / len(errors), 0.02)
        truth = truths[-1]
        # The final model holds the stair's steps: as many as the ground truth has.
        with open(steps_csv) as f:
            steps = list(csv.DictReader(f))
        real_steps = sum(fl.num_steps for fl in truth.flights)
        self.assertEqual(len(steps), real_steps)
        rises = [float(s["riser_height_m"]) for s in steps if s["riser_height_m"]]
        real_rise = truth.flights[0].steps[0].riser_height_m
        self.assertTrue(all(abs(x - real_rise) < 0.01 for x in rises), rises)
        with open(plot, "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        self.assertGreater(os.path.getsize(plot), 10_000)

    def test_steps_only_channel_is_read_when_the_full_model_is_absent(self):
        steps_only = os.path.join(self.tmp, "steps_only.lcmlog")
        # The recording without STAIRS_MODEL, written event by event in LCM's log format.
        with open(steps_only, "wb") as dst:
            for ev in stairs_lcmlog.read_events(self.rec):
                if ev.channel == "STAIRS_MODEL":
                    continue
                ch = ev.channel.encode()
                dst.write(struct.pack(">IqqII", 0xEDA1DA01, ev.event_number, ev.utime, len(ch), len(ev.data)))
                dst.write(ch + ev.data)
        frames_csv = os.path.join(self.tmp, "steps_only.csv")
        r = run(SCRIPT, steps_only, "--csv", frames_csv, "--steps-csv", os.path.join(self.tmp, "s.csv"))
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(frames_csv) as f:
            self.assertEqual(len(list(csv.DictReader(f))), len(self.channels["STAIRS_MODEL_STEPS"]))

    def test_a_truncated_log_is_one_line_naming_the_file(self):
        cut = os.path.join(self.tmp, "cut.lcmlog")
        with open(self.rec, "rb") as src, open(cut, "wb") as dst:
            dst.write(src.read(os.path.getsize(self.rec) // 2))
        r = run(SCRIPT, cut)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn(cut, r.stderr)
        self.assertIn("truncated", r.stderr)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)

    def test_a_log_without_models_is_an_error_naming_the_channel(self):
        r = run(SCRIPT, LOG, "--csv", os.path.join(self.tmp, "x.csv"))
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("STAIRS_MODEL", r.stderr)


if __name__ == "__main__":
    unittest.main()
