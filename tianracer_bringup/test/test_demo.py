"""The headless demo (README's run command) on a short lap: it completes, and the files it
writes are valid PNG and CSV. The demo starts its own ROS master."""
import csv
import os
import shutil
import subprocess
import tempfile
import unittest

def read_png(path):
    """(width, height, channels), after Pillow checked the file's structure and CRCs
    (verify()) and decoded every pixel (load())."""
    from PIL import Image
    with Image.open(path) as im:
        im.verify()
    with Image.open(path) as im:
        assert im.format == 'PNG', path
        im.load()
        return im.width, im.height, len(im.getbands())


class Demo(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = tempfile.mkdtemp(prefix='tianracer_demo_')
        proc = subprocess.run(
            ['rosrun', 'tianracer_bringup', 'demo', '--laps', '0.15', '--out', cls.out,
             '--timeout', '300'], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=420)
        cls.code, cls.log = proc.returncode, proc.stdout.decode(errors='replace')

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.out, ignore_errors=True)

    def test_completes_the_short_lap(self):
        self.assertEqual(self.code, 0, self.log)
        summary = open(os.path.join(self.out, 'summary.txt')).read()
        self.assertIn('laps completed     yes', summary)
        for key in ('distance', 'lap time', 'real-time factor', 'odometry error'):
            self.assertIn(key, summary)

    def test_pictures_are_valid_pngs(self):
        sizes = {name: read_png(os.path.join(self.out, name)) for name in (
            'birds_eye.png', 'camera.png', 'real_sense_rgb.png', 'real_sense_depth.png')}
        self.assertEqual(sizes['camera.png'], (800, 800, 3))
        self.assertEqual(sizes['real_sense_rgb.png'], (640, 480, 3))
        self.assertEqual(sizes['real_sense_depth.png'][:2], (640, 480))
        self.assertGreater(sizes['birds_eye.png'][0], 100)

    def test_trajectory_is_a_valid_csv(self):
        with open(os.path.join(self.out, 'trajectory.csv'), newline='') as f:
            rows = list(csv.reader(f))
        self.assertEqual(rows[0], ['t', 'x', 'y', 'yaw', 'odom_x', 'odom_y', 'odom_yaw', 'speed'])
        values = [[float(v) for v in r] for r in rows[1:]]
        self.assertGreater(len(values), 50)  # 50 Hz over the ~3 s of sim time the lap takes
        self.assertTrue(all(len(r) == 8 for r in values))
        times = [r[0] for r in values]
        self.assertEqual(times, sorted(times))
        # 0.15 of the 21.85 m lap along the start straight: x grows to about 3.3 m.
        self.assertGreater(values[-1][1], 3.0)


if __name__ == '__main__':
    unittest.main()
