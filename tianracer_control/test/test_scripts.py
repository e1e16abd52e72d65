"""The scripts' pure parts: manoeuvre plans and key handling (no ROS needed)."""
import math
import os
import unittest
from importlib.machinery import SourceFileLoader
from importlib.util import module_from_spec, spec_from_loader

SCRIPTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts")


def load(name):
    loader = SourceFileLoader(name, os.path.join(SCRIPTS, name))
    module = module_from_spec(spec_from_loader(name, loader))
    loader.exec_module(module)
    return module


driver = load("scripted_driver")
teleop = load("teleop_keyboard")


class TestPlans(unittest.TestCase):
    def test_straight(self):
        (s,) = driver.plan("straight", 0.5, distance=2.0)
        self.assertAlmostEqual(s.duration, 4.0)
        self.assertEqual((s.v, s.w), (0.5, 0.0))

    def test_circle_yaw_rate_is_v_over_r(self):
        (s,) = driver.plan("circle", 0.5, radius=1.0, laps=2)
        self.assertAlmostEqual(s.duration, 2 * 2 * math.pi * 1.0 / 0.5)
        self.assertAlmostEqual(s.w, 0.5)
        (r,) = driver.plan("circle", 0.5, radius=1.0, direction="right")
        self.assertAlmostEqual(r.w, -0.5)

    def test_figure_eight_is_two_opposite_laps(self):
        a, b = driver.plan("figure_eight", 1.0, radius=0.8)
        self.assertAlmostEqual(a.duration, 2 * math.pi * 0.8)
        self.assertAlmostEqual(a.duration, b.duration)
        self.assertAlmostEqual(a.w, -b.w)
        self.assertGreater(a.w, 0)

    def test_command_at(self):
        segs = driver.plan("figure_eight", 1.0, radius=1.0)
        self.assertEqual(driver.command_at(segs, 0.0), (1.0, 1.0))
        self.assertEqual(driver.command_at(segs, 2 * math.pi + 0.1), (1.0, -1.0))
        self.assertIsNone(driver.command_at(segs, 4 * math.pi + 0.1))

    def test_steering_angle_mode(self):
        self.assertAlmostEqual(driver.to_angular_z(0.5, 0.5, True, 0.25), math.atan(0.25))
        self.assertEqual(driver.to_angular_z(0.5, 0.5, False, 0.25), 0.5)
        self.assertEqual(driver.to_angular_z(0.0, 0.5, True, 0.25), 0.0)

    def test_bad_arguments(self):
        for args, kwargs in [(("loop", 0.5), {}), (("straight", 0.0), {}),
                             (("straight", float("nan")), {}), (("circle", 0.5), {"radius": 0}),
                             (("circle", 0.5), {"direction": "up"})]:
            with self.assertRaises(ValueError):
                driver.plan(*args, **kwargs)


class TestTeleop(unittest.TestCase):
    def test_keys(self):
        self.assertEqual(teleop.split_keys("wa\x1b[A\x1b[D k"), ["w", "a", "up", "left", " ", "k"])
        self.assertEqual(teleop.actions_for("W\x1b[Bq?"), ["faster", "slower", "quit"])

    def test_state(self):
        s = teleop.TeleopState(speed_step=0.1, turn_step=0.2, max_speed=0.25, max_turn=0.3)
        for a in ["faster", "faster", "faster", "left", "left"]:
            self.assertTrue(s.apply(a))
        self.assertAlmostEqual(s.speed, 0.25)
        self.assertAlmostEqual(s.turn, 0.3)
        self.assertIn("speed +0.25 m/s", s.describe())
        s.apply("stop")
        self.assertEqual((s.speed, s.turn), (0.0, 0.0))
        s.apply("slower")
        self.assertAlmostEqual(s.speed, -0.1)
        self.assertFalse(s.apply("quit"))
        self.assertEqual(s.speed, 0.0)


if __name__ == "__main__":
    unittest.main()
