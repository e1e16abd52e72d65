#!/usr/bin/env python3
"""The shipped rviz config in the real viewer (see rviz_view.test).

rviz reports transform trouble only in its Displays panel; with its `ros.rviz` loggers at DEBUG
it also logs it: "Error transforming from frame ..." for the model's links, and for a topic
whose frame has no transform its messages wait until the display's queue overflows ("Removed
oldest message because buffer is full") and none is ever "ready". Those, and any WARN/ERROR/FATAL
rviz logs while the car drives (after a second of start-up), fail the test. (A few overflows
among many ready messages are a busy machine's rviz falling behind, not an error.) A second rviz with the fixed frame misspelt shows
that the check catches what it is meant to catch."""
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import unittest

import rosgraph
import rospkg
import rospy
import rostest
import yaml
from geometry_msgs.msg import Twist
from PIL import Image
from tianracer_sim.sim_time import drive_twist, node_connected, wait_for

RVIZ_DIR = os.path.join(rospkg.RosPack().get_path("tianracer_bringup"), "rviz")
SCREEN = (1400, 900)
SHOT_DIR = os.environ.get("ROS_LOG_DIR", tempfile.gettempdir())
TROUBLE = re.compile(r"^(WARN|ERROR|FATAL) |Error transforming|No transform|does not exist|Fixed Frame|"
                     r"Discarding message")
READY = re.compile(r"Message ready in frame (\S+)")
DROPPED = re.compile(r"Removed oldest message because buffer is full.*\(frame_id=([^,]+),")
ROSCONSOLE_CONFIG = "log4j.logger.ros=INFO\nlog4j.logger.ros.rviz=DEBUG\n"
SCAN_RGB = (255, 40, 40)   # the Scan display's flat colour in the shipped config


def displays(config):
    """(name, topic) of every enabled display that subscribes to a topic."""
    out = []
    for d in yaml.safe_load(open(config))["Visualization Manager"]["Displays"]:
        topic = d.get("Topic") or d.get("Image Topic")
        if d.get("Enabled") and topic:
            out.append((d["Name"], topic))
    return out


def trouble(log_text):
    """rviz's log lines (ESC colour codes removed) that report a transform or topic problem."""
    lines = [re.sub(r"\x1b\[[0-9;]*m", "", l).strip() for l in log_text.splitlines()]
    found = [l for l in lines if TROUBLE.search(l)]
    ready = {m.group(1) for m in map(READY.search, lines) if m}
    dropped = {}
    for m in filter(None, map(DROPPED.search, lines)):
        dropped[m.group(1)] = dropped.get(m.group(1), 0) + 1
    found += ["no message in frame %s reached the fixed frame (%d dropped waiting for a transform)" % (f, n)
              for f, n in sorted(dropped.items()) if f not in ready]
    return found


class Viewer(object):
    """rviz with `config` on its own Xvfb screen (xvfb-run -a), its console in a file."""

    def __init__(self, config, tmp):
        self.tmp = tmp
        self.log = os.path.join(tmp, "rviz.log")
        rc = os.path.join(tmp, "rosconsole.config")
        with open(rc, "w") as f:
            f.write(ROSCONSOLE_CONFIG)
        env = dict(os.environ, ROSCONSOLE_CONFIG_FILE=rc, ROSCONSOLE_FORMAT="${severity} ${logger}: ${message}",
                   XDG_RUNTIME_DIR=tmp)
        self.display_file = os.path.join(tmp, "display")
        script = 'echo "$DISPLAY" > "%s"; exec rviz -d "%s" __name:=rviz_view_check' % (self.display_file, config)
        self.proc = subprocess.Popen(
            ["xvfb-run", "-a", "-f", os.path.join(tmp, "Xauthority"),
             "-s", "-screen 0 %dx%dx24" % SCREEN, "sh", "-c", script],
            stdout=open(self.log, "w"), stderr=subprocess.STDOUT, env=env, start_new_session=True)

    def screenshot(self, path):
        display = open(self.display_file).read().strip()
        env = dict(os.environ, XAUTHORITY=os.path.join(self.tmp, "Xauthority"))
        subprocess.check_call(["import", "-display", display, "-window", "root", path], env=env)
        return path

    def console(self):
        return open(self.log, errors="replace").read()

    def close(self):
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGTERM)
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait()


class RvizViewTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_rviz_view")
        # ~config: which shipped config (tianracer.rviz with tianracer.launch, two_cars.rviz
        # with two_cars.launch); ~negative: also run the misspelt-fixed-frame check.
        cls.config = os.path.join(RVIZ_DIR, rospy.get_param("~config", "tianracer.rviz"))
        cls.negative = rospy.get_param("~negative", True)
        cls.shot = os.path.join(SHOT_DIR, os.path.basename(cls.config).replace(".rviz", "_view.png"))
        cls.missing = [t for t in ("xvfb-run", "rviz", "import") if not shutil.which(t)]
        cls.cmd = rospy.Publisher("/cmd_vel", Twist, queue_size=1)

    def setUp(self):
        if self.missing:
            self.skipTest("needs %s (apt-get install xvfb rviz imagemagick; scripts/setup.sh installs them)"
                          % ", ".join(self.missing))
        self.tmp = tempfile.mkdtemp(prefix="rviz_view_")

    def tearDown(self):
        shutil.rmtree(getattr(self, "tmp", ""), ignore_errors=True)

    def subscribed(self, node, topics):
        """`node` subscribes to every topic of `topics`, each is published, and every
        subscription of the node is connected to every publisher (not only registered)."""
        pubs, subs, _ = rosgraph.Master(rospy.get_name()).getSystemState()
        published = {t for t, nodes in pubs if nodes}
        mine = {t for t, nodes in subs if node in nodes}
        return all(t in mine and t in published for t in topics) and node_connected(node)

    def view(self, config, sim_seconds, until=None):
        """Start rviz on config, wait until it receives every topic, drive, screenshot. With
        `until`, drive on (up to 30 s of sim time more) until until(console since the start)."""
        viewer = Viewer(config, self.tmp)
        try:
            topics = [t for _, t in displays(config)]
            try:
                wait_for(lambda: viewer.proc.poll() is None and self.subscribed("/rviz_view_check", topics),
                         "rviz connected to every topic of %s (%s)" % (config, topics), 90)
            except AssertionError as e:
                self.fail("%s; its console:\n%s" % (e, viewer.console()[-3000:]))
            # The first second is rviz's start-up (its TF listener catching up with /tf_static,
            # as for any user): what it logs from then on, while the car drives, is checked.
            drive_twist(self.cmd, 1.0, 0.6)
            start = len(viewer.console())
            drive_twist(self.cmd, sim_seconds, 0.6)
            extra = 0.0
            while until and not until(viewer.console()[start:]) and extra < 30.0:
                drive_twist(self.cmd, 0.5, 0.6)  # rviz on a loaded machine reads late
                extra += 0.5
            shot = viewer.screenshot(os.path.join(self.tmp, "shot.png"))
            drive_twist(self.cmd, 0.5, 0.0)
            return viewer.console()[start:], shot
        finally:
            viewer.close()

    def test_shipped_config_clean_and_drawn(self):
        console, shot = self.view(self.config, 4.0)
        shutil.copy(shot, self.shot)
        self.assertEqual(trouble(console), [], "rviz reported problems (screenshot %s)" % self.shot)
        img = Image.open(shot).convert("RGB")
        self.assertEqual(img.size, SCREEN)
        # Not blank: many colours, and the scan's colour in the 3D view (right of the panels).
        colours = img.getcolors(maxcolors=1 << 20)
        self.assertGreater(len(colours), 200, "screenshot %s has %d colours" % (self.shot, len(colours)))
        view = img.crop((360, 70, SCREEN[0], SCREEN[1] - 40))
        scan = sum(n for n, c in view.getcolors(maxcolors=1 << 20)
                   if all(abs(a - b) <= 30 for a, b in zip(c, SCAN_RGB)))
        self.assertGreater(scan, 200, "the scan is not drawn in %s (%d pixels of its colour)" % (self.shot, scan))
        # The camera panel (top left) shows the camera image, not an empty panel.
        panel = img.crop((30, 90, 300, 350)).getcolors(maxcolors=1 << 20)
        self.assertGreater(len(panel), 20, "the camera panel of %s looks empty" % self.shot)

    def test_the_check_catches_a_wrong_fixed_frame(self):
        if not self.negative:
            self.skipTest("~negative is false: checked with tianracer.rviz")
        bad = os.path.join(self.tmp, "bad.rviz")
        with open(bad, "w") as f:
            f.write(open(self.config).read().replace("Fixed Frame: world", "Fixed Frame: no_such_frame"))
        def caught(console):
            found = trouble(console)
            return (any("no_such_frame" in l for l in found) and
                    any(l.startswith("no message in frame") for l in found))

        # A display's queue overflows (messages waiting for a transform) after rviz has read
        # enough of them: a busy rviz takes longer than a second of sim time.
        console, _ = self.view(bad, 1.0, until=caught)
        found = trouble(console)
        self.assertTrue(any("no_such_frame" in l for l in found), "not caught; console:\n%s" % console[-3000:])
        self.assertTrue(any(l.startswith("no message in frame") for l in found),
                        "the topics' displays were not caught: %s" % found[-5:])


if __name__ == "__main__":
    rostest.rosrun("tianracer_bringup", "test_rviz_view", RvizViewTest, sys.argv)
