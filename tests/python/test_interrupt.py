"""Ctrl-C during a run from Python: the step under way ends, the run stops and
weavelab.Interrupted carries the frames so far, as the command line keeps its record."""
import os
import signal
import subprocess
import sys
import time
import unittest

SCRIPT = """
import sys, weavelab, support
scene = support.small_scene(weavelab, size=9, duration=100.0)
print("running", flush=True)
try:
    weavelab.run(scene)
except weavelab.Interrupted as e:
    print("interrupted", e.run.outcome, len(e.run.times) >= 1, e.run.end_time > 0, flush=True)
    sys.exit(5)
print("finished")
"""


STEPPING = """
import sys, weavelab, support
sim = weavelab.Simulation(support.small_scene(weavelab, size=9, duration=100.0))
print("running", flush=True)
try:
    sim.advance_to(100.0)
except weavelab.Interrupted:
    print("interrupted", 0 < sim.t < 100.0, sim.stats()["steps"] > 0, flush=True)
    sys.exit(5)
print("finished")
"""


SAYS = """
import sys, weavelab, support
sim = weavelab.Simulation(support.small_scene(weavelab, size=9, duration=100.0))
print("running", flush=True)
try:
    sim.advance_to(100.0)
except weavelab.Interrupted as e:
    print(e, flush=True)
    sys.exit(5)
"""


# Calibrate ends its fit at a Ceres iteration and raises with its record; a run
# on another thread afterwards (which takes no handlers) does not see the old signal.
CALIBRATE = """
import sys, tempfile, threading, weavelab, support
scene = support.small_scene(weavelab, size=5, duration=0.01)
print("running", flush=True)
try:
    weavelab.calibrate(scene, tempfile.mkdtemp(), tests=["shear"], starts=4000)
except weavelab.Interrupted as e:
    later = []
    worker = threading.Thread(target=lambda: later.append(weavelab.run(scene).outcome))
    worker.start()
    worker.join()
    print(e, e.run["outcome"], e.run["interrupted_in"], later, flush=True)
    sys.exit(5)
"""


# Fit ends its simulation at a step and raises with fit.json's dict; the message
# names the signal, as run's and calibrate's do, and the record names the stage.
FIT = """
import os, sys, tempfile, weavelab, support
truth = support.small_scene(weavelab, size=9, duration=0.5)
tmp = tempfile.mkdtemp()
weavelab.run(truth, out=os.path.join(tmp, "target"))
start = truth.copy()
start["contact.shear_modulus_Pa"] = 1500.0
print("running", flush=True)
try:
    weavelab.fit(start, os.path.join(tmp, "target"), ["contact.shear_modulus_Pa"], os.path.join(tmp, "fit"))
except weavelab.Interrupted as e:
    print(e, e.run["outcome"], e.run["interrupted_in"].startswith("stage 1 of the fit"), flush=True)
    sys.exit(5)
"""


class Interrupt(unittest.TestCase):
    def interrupt(self, script, sig=signal.SIGINT, after=2.0):
        p = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True,
                             cwd=os.path.dirname(os.path.abspath(__file__)))
        self.assertEqual(p.stdout.readline().strip(), "running")
        time.sleep(after)  # well inside the run (its set-up takes milliseconds)
        p.send_signal(sig)
        out, _ = p.communicate(timeout=120)
        self.assertEqual(p.returncode, 5, out)
        return out.strip()

    def test_sigint_ends_the_run_with_its_record(self):
        self.assertEqual(self.interrupt(SCRIPT), "interrupted interrupted True True")

    def test_sigint_ends_manual_stepping_after_a_step(self):
        self.assertEqual(self.interrupt(STEPPING), "interrupted True True")

    def test_the_message_names_the_signal(self):
        self.assertEqual(self.interrupt(SAYS), "interrupted by SIGINT")
        self.assertEqual(self.interrupt(SAYS, signal.SIGTERM), "interrupted by SIGTERM")

    def test_sigterm_ends_calibrate_with_its_record(self):
        self.assertEqual(self.interrupt(CALIBRATE, signal.SIGTERM, after=0.5),
                         "interrupted by SIGTERM interrupted the fit ['ok']")


    def test_sigterm_ends_fit_and_names_the_signal(self):
        self.assertEqual(self.interrupt(FIT, signal.SIGTERM, after=0.5), "interrupted by SIGTERM interrupted True")


if __name__ == "__main__":
    unittest.main()
