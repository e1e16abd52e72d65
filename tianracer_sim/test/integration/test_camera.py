#!/usr/bin/env python3
"""rostest: the seed's camera (800x800, 30 Hz) and RealSense depth camera (640x480, images and
cloud at 20 Hz, camera_infos at 10 Hz) in walled_room, as docs/model_and_sensors.md lists them:

- the seven topics at their rates in sim time (header stamps, +-10 % over >= 2 s), with their
  encodings, sizes, steps, cloud layout and optical frame ids; the cloud's z and colour equal
  the depth and colour images of the same render (colour in PCL's byte order, not Gazebo's);
- CameraInfo as gazebo_ros fills it (f 476.70, cx = cy = 400.5, P[3] = -33.37; real_sense f 554.60);
- no image subscriber, no rendering: renders_total in /diagnostics (the sim's status_period is
  0.5 s in camera.test) stays put without one, and with only a camera_info subscriber;
- the optical frames in TF: camera -> camera_optical_frame is rpy(-pi/2, 0, -pi/2);
- scripts/save_frames against the live sim (PNG files checked by decoding them here), its pure
  parts (PNG writer, colour map), and its exit code on a timeout.
"""
import math
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time
import unittest

import numpy as np
import rospkg
import rospy
import rostest
import tf2_ros
from diagnostic_msgs.msg import DiagnosticArray
from sensor_msgs.msg import CameraInfo, Image, PointCloud2, PointField
from tianracer_sim.rotation import quaternion_from_rpy
from tianracer_sim.script_module import load_script
from tianracer_sim.sim_time import bus_info, lossless, sim_sleep, wait_connected, wait_for

CAMERA = '/rrbot/camera1/image_raw'
CAMERA_INFO = '/rrbot/camera1/camera_info'
RS_RGB = '/real_sense/rgb/image_raw'
RS_DEPTH = '/real_sense/depth/image_raw'
RS_POINTS = '/real_sense/depth/points'
RS_RGB_INFO = '/real_sense/rgb/camera_info'
RS_DEPTH_INFO = '/real_sense/depth/camera_info'
# topic -> (type, rate in sim time, frame)
TOPICS = {
    CAMERA: (Image, 30.0, 'camera_optical_frame'),
    CAMERA_INFO: (CameraInfo, 30.0, 'camera_optical_frame'),
    RS_RGB: (Image, 20.0, 'real_sense_optical_frame'),
    RS_DEPTH: (Image, 20.0, 'real_sense_optical_frame'),
    RS_POINTS: (PointCloud2, 20.0, 'real_sense_optical_frame'),
    RS_RGB_INFO: (CameraInfo, 10.0, 'real_sense_optical_frame'),
    RS_DEPTH_INFO: (CameraInfo, 10.0, 'real_sense_optical_frame'),
}
CLOUD_DTYPE = np.dtype({'names': ['x', 'y', 'z', 'rgb'], 'formats': ['<f4', '<f4', '<f4', '<u4'],
                        'offsets': [0, 4, 8, 16], 'itemsize': 32})
SAVE_FRAMES = os.path.join(rospkg.RosPack().get_path('tianracer_sim'), 'scripts', 'save_frames')


def read_png(path):
    """(width, height, mode, pixels) of a PNG file, decoded by Pillow after it checked the
    file's structure and CRCs (verify())."""
    from PIL import Image
    with Image.open(path) as im:
        im.verify()
    with Image.open(path) as im:
        assert im.format == 'PNG', path
        return im.width, im.height, im.mode, np.asarray(im)


class Camera(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_camera')
        cls.lock = threading.Lock()
        cls.diagnostics = []  # (sim stamp, {status name: {key: value}})
        lossless(rospy.Subscriber('/diagnostics', DiagnosticArray, cls.on_diagnostics))
        cls.tf_buffer = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf_buffer)
        wait_for(lambda: rospy.get_time() > 0.0, '/clock')

    @classmethod
    def on_diagnostics(cls, msg):
        status = {s.name: {kv.key: kv.value for kv in s.values} for s in msg.status}
        with cls.lock:
            cls.diagnostics.append((msg.header.stamp.to_sec(), status))

    def diagnostics_after(self, t):
        """The first /diagnostics made at sim time >= t (status_period 0.5 s)."""
        def find():
            with self.lock:
                return next(((s, status) for s, status in self.diagnostics if s >= t), None)
        return wait_for(find, '/diagnostics made after sim time %.3f' % t)

    @staticmethod
    def sim_connections(topics):
        """The sim's connections to this process on `topics`."""
        return [c for c in bus_info('/tianracer_sim')
                if c[2] == 'o' and c[4] in topics and c[1] == rospy.get_name()]

    def renders(self, t):
        """renders_total of the camera and of the depth camera, from diagnostics after t."""
        stamp, status = self.diagnostics_after(t)
        for topic in (CAMERA, RS_RGB):
            self.assertIn('tianracer_sim: ' + topic, status)
        return (int(float(status['tianracer_sim: ' + CAMERA]['renders_total'])),
                int(float(status['tianracer_sim: ' + RS_RGB]['renders_total'])))

    @staticmethod
    def now():
        return rospy.get_rostime().to_sec()

    def wait_sim(self, seconds):
        sim_sleep(seconds)

    # --- save_frames' pure parts --------------------------------------------------------------

    def test_0_save_frames_png_and_colour_map(self):
        sf = load_script(SAVE_FRAMES)
        rgb = np.random.RandomState(1).randint(0, 256, (7, 5, 3)).astype(np.uint8)
        tmp = tempfile.mkdtemp()
        try:
            sf.save_png(os.path.join(tmp, 'rgb.png'), rgb)
            w, h, mode, px = read_png(os.path.join(tmp, 'rgb.png'))
            self.assertEqual((w, h, mode), (5, 7, 'RGB'))
            np.testing.assert_array_equal(px, rgb)
            sf.save_png(os.path.join(tmp, 'grey.png'), rgb[:, :, 0])
            w, h, mode, px = read_png(os.path.join(tmp, 'grey.png'))
            self.assertEqual((w, h, mode), (5, 7, 'L'))
            np.testing.assert_array_equal(px, rgb[:, :, 0])
            with self.assertRaises(ValueError):
                sf.save_png(os.path.join(tmp, 'bad.png'), np.zeros((2, 2, 4), np.uint8))
        finally:
            shutil.rmtree(tmp)
        depth = np.array([[1.0, 1.3, 2.0, 3.0, np.nan, np.inf, -np.inf]])
        image, near, far = sf.colorize_depth(depth)
        self.assertEqual((near, far), (1.0, 3.0))
        self.assertEqual(image.shape, (1, 7, 3))
        np.testing.assert_array_equal(image[0, 4:], 0)  # NaN and inf are black
        self.assertTrue((image[0, :4].sum(axis=1) > 50).all())  # finite ones are not
        r, g, b = [image[0, :4, k].astype(int) for k in range(3)]
        self.assertGreater(b[1], max(r[1], g[1]))  # near (x = 0.15) is blue
        self.assertGreater(g[2], max(r[2], b[2]))  # the middle is green
        self.assertGreater(r[3], max(g[3], b[3]))  # far is red
        blank, near, far = sf.colorize_depth(np.full((2, 2), np.nan))
        self.assertIsNone(near)
        self.assertFalse(blank.any())
        bgr = sf.image_pixels('bgr8', 1, 2, 6, bytes([1, 2, 3, 4, 5, 6]))
        np.testing.assert_array_equal(bgr, [[[3, 2, 1], [6, 5, 4]]])
        self.assertEqual(sf.file_name('/real_sense/rgb/image_raw'), 'real_sense_rgb_image_raw.png')

    # --- the sim -----------------------------------------------------------------------------

    def test_1_no_subscriber_no_rendering(self):
        t = self.now()
        cam0, depth0 = self.renders(t)
        # A camera_info subscriber alone must not make the camera render.
        info = rospy.Subscriber(CAMERA_INFO, CameraInfo, lambda m: None, queue_size=1)
        with self.lock:
            n_diag = len(self.diagnostics)
        w0 = time.time()
        self.wait_sim(1.5)
        cam1, depth1 = self.renders(self.now())
        with self.lock:
            n_diag = len(self.diagnostics) - n_diag
        rospy.loginfo('no image subscriber for 1.5 s sim (%.1f s wall, %d diagnostics): '
                      'renders_total camera %d -> %d, depth %d -> %d',
                      time.time() - w0, n_diag, cam0, cam1, depth0, depth1)
        self.assertGreaterEqual(n_diag, 2)  # status_period 0.5 s reached the node
        self.assertEqual(cam1, cam0)
        self.assertEqual(depth1, depth0)

        received = []
        image = rospy.Subscriber(CAMERA, Image, lambda m: received.append(m.header.stamp),
                                 queue_size=5)
        wait_connected(image)  # rendering starts with the connection, not the registration
        self.wait_sim(1.0)
        cam2, depth2 = self.renders(self.now())
        rospy.loginfo('camera subscribed for 1 s sim: renders_total camera %d -> %d (%d images '
                      'received), depth %d -> %d', cam1, cam2, len(received), depth1, depth2)
        self.assertGreaterEqual(cam2 - cam1, 20)
        # Every received image was rendered; the counter is a diagnostics snapshot, and an
        # image or two rendered after it may already be in `received`.
        self.assertGreaterEqual(cam2 - cam1, len(received) - 2)
        self.assertEqual(depth2, depth1)  # the depth camera has no subscriber yet

        points = rospy.Subscriber(RS_POINTS, PointCloud2, lambda m: None, queue_size=1)
        wait_connected(points)
        self.wait_sim(1.0)
        cam3, depth3 = self.renders(self.now())
        rospy.loginfo('cloud subscribed for 1 s sim: depth renders_total %d -> %d',
                      depth2, depth3)
        self.assertGreaterEqual(depth3 - depth2, 12)  # 20 Hz

        for sub in (info, image, points):
            sub.unregister()
        # The node sees the connections close (its getNumSubscribers is 0), then renders none.
        wait_for(lambda: not self.sim_connections((CAMERA, CAMERA_INFO, RS_POINTS)),
                 "the sim's connections to us closed")
        self.wait_sim(0.2)
        cam4, depth4 = self.renders(self.now())
        self.wait_sim(1.0)
        cam5, depth5 = self.renders(self.now())
        rospy.loginfo('unsubscribed: renders_total camera %d -> %d, depth %d -> %d',
                      cam4, cam5, depth4, depth5)
        self.assertEqual(cam5, cam4)
        self.assertEqual(depth5, depth4)

    def test_2_topics_rates_formats_and_frames(self):
        stamps = {t: [] for t in TOPICS}
        layouts = {t: set() for t in TOPICS}
        by_stamp = {RS_RGB: {}, RS_DEPTH: {}, RS_POINTS: {}}
        complete = [None]  # stamp of the last rgb, depth and cloud all received
        lock = threading.Lock()

        def callback(msg, topic):
            s = msg.header.stamp.to_sec()
            if isinstance(msg, Image):
                layout = (msg.header.frame_id, msg.encoding, msg.width, msg.height, msg.step,
                          len(msg.data), msg.is_bigendian)
            elif isinstance(msg, PointCloud2):
                layout = (msg.header.frame_id, msg.width, msg.height, msg.point_step,
                          msg.row_step, len(msg.data), msg.is_bigendian,
                          tuple((f.name, f.offset, f.datatype, f.count) for f in msg.fields))
            else:
                layout = (msg.header.frame_id, msg.width, msg.height)
            with lock:
                stamps[topic].append((msg.header.seq, s))
                layouts[topic].add(layout)
                if topic in by_stamp:
                    keep = by_stamp[topic]
                    keep[s] = msg
                    if all(s in k for k in by_stamp.values()):
                        complete[0] = s  # rgb, depth and cloud of one render
                    # The last 10 of each, and the last complete triple (a loaded machine's
                    # subscriber may miss a different frame on each topic).
                    for old in sorted(keep)[:-10]:
                        if old != complete[0]:
                            del keep[old]

        # Large receive buffers: a 9.8 MB cloud at 20 Hz into Python. On a loaded machine the
        # transport may still drop messages (the publisher queue is short); the rate is then
        # what the node published: header.seq counts its messages, the stamps give sim time.
        subs = [rospy.Subscriber(t, c, callback, callback_args=t, queue_size=10,
                                 buff_size=1 << 25, tcp_nodelay=True)
                for t, (c, _, _) in TOPICS.items()]
        w0 = time.time()

        def spans():  # every topic spans 2 s of sim time
            with lock:
                return all(len(s) >= 2 and s[-1][1] - s[0][1] >= 2.0 for s in stamps.values())

        wait_for(spans, '2 s of sim time of every camera topic', poll=0.05)
        for sub in subs:
            sub.unregister()
        rospy.loginfo('collected for %.1f s wall', time.time() - w0)

        with lock:
            for topic, (_, target, _) in TOPICS.items():
                s = stamps[topic]
                self.assertGreaterEqual(len(s), 10, topic)
                (seq0, t0), (seq1, t1) = s[0], s[-1]
                published = seq1 - seq0
                rate = published / (t1 - t0)
                gaps = np.diff([t for _, t in s])
                rospy.loginfo('%-32s %3d published over %.3f s sim: %6.2f Hz (target %g); '
                              '%d received (%.2f Hz), gaps %.4f..%.4f s', topic, published,
                              t1 - t0, rate, target, len(s), (len(s) - 1) / (t1 - t0),
                              gaps.min(), gaps.max())
                self.assertGreaterEqual(t1 - t0, 2.0, topic)
                self.assertTrue(all(g > 0 for g in gaps), topic + ': stamps not increasing')
                self.assertTrue(all(b > a for (a, _), (b, _) in zip(s, s[1:])), topic + ': seq')
                self.assertAlmostEqual(rate, target, delta=0.1 * target, msg=topic)

        with lock:
            frame = {t: f for t, (_, _, f) in TOPICS.items()}
            self.assertEqual(layouts[CAMERA], {(frame[CAMERA], 'rgb8', 800, 800, 2400,
                                                2400 * 800, 0)})
            self.assertEqual(layouts[RS_RGB], {(frame[RS_RGB], 'rgb8', 640, 480, 1920,
                                                1920 * 480, 0)})
            self.assertEqual(layouts[RS_DEPTH], {(frame[RS_DEPTH], '32FC1', 640, 480, 2560,
                                                  2560 * 480, 0)})
            fields = (('x', 0, PointField.FLOAT32, 1), ('y', 4, PointField.FLOAT32, 1),
                      ('z', 8, PointField.FLOAT32, 1), ('rgb', 16, PointField.FLOAT32, 1))
            self.assertEqual(layouts[RS_POINTS], {(frame[RS_POINTS], 640, 480, 32, 32 * 640,
                                                   32 * 640 * 480, False, fields)})
            self.assertEqual(layouts[CAMERA_INFO], {(frame[CAMERA_INFO], 800, 800)})
            for t in (RS_RGB_INFO, RS_DEPTH_INFO):
                self.assertEqual(layouts[t], {(frame[t], 640, 480)})
            common = sorted(set(by_stamp[RS_RGB]) & set(by_stamp[RS_DEPTH]) &
                            set(by_stamp[RS_POINTS]))
            self.assertTrue(common, 'no rgb, depth and cloud of the same stamp')
            rgb_msg, depth_msg, cloud_msg = [by_stamp[t][common[-1]]
                                             for t in (RS_RGB, RS_DEPTH, RS_POINTS)]

        # One render pass: the cloud's z is the depth image, its colour the rgb image.
        depth = np.frombuffer(depth_msg.data, '<f4').reshape(480, 640)
        rgb = np.frombuffer(rgb_msg.data, np.uint8).reshape(480, 640, 3)
        cloud = np.frombuffer(cloud_msg.data, CLOUD_DTYPE).reshape(480, 640)
        finite = np.isfinite(depth)
        rospy.loginfo('depth: %.1f %% finite, %.3f..%.3f m; cloud is_dense %s', 100 * finite.mean(),
                      np.nanmin(depth), np.nanmax(depth), cloud_msg.is_dense)
        self.assertTrue(finite.any())
        self.assertGreaterEqual(np.nanmin(depth), 0.4 - 1e-4)  # pointCloudCutoff
        self.assertLessEqual(np.nanmax(depth), 5.0 + 1e-4)  # pointCloudCutoffMax default
        np.testing.assert_array_equal(np.isfinite(cloud['z']), finite)
        np.testing.assert_allclose(cloud['z'][finite], depth[finite], rtol=0, atol=1e-6)
        self.assertEqual(cloud_msg.is_dense, bool(finite.all()))
        packed = cloud['rgb'][finite]  # PCL: 0x00RRGGBB in a little-endian uint32
        unpacked = np.stack([(packed >> 16) & 255, (packed >> 8) & 255, packed & 255], axis=-1)
        np.testing.assert_array_equal(unpacked, rgb[finite])

    def test_3_camera_info(self):
        def info(topic):
            return rospy.wait_for_message(topic, CameraInfo, timeout=60)

        cam = info(CAMERA_INFO)
        f = cam.K[0]
        rospy.loginfo('camera K %s P %s', cam.K, cam.P)
        self.assertAlmostEqual(f, 476.70, delta=0.01)
        self.assertEqual(list(cam.K), [f, 0, 400.5, 0, f, 400.5, 0, 0, 1])
        self.assertEqual(list(cam.R), [1, 0, 0, 0, 1, 0, 0, 0, 1])
        self.assertAlmostEqual(cam.P[3], -33.37, delta=0.01)
        self.assertAlmostEqual(cam.P[3], -f * 0.07, delta=1e-9)
        self.assertEqual([cam.P[i] for i in (0, 1, 2, 4, 5, 6, 7, 8, 9, 10, 11)],
                         [f, 0, 400.5, 0, f, 400.5, 0, 0, 0, 1, 0])
        self.assertEqual(cam.distortion_model, 'plumb_bob')
        self.assertEqual(list(cam.D), [0, 0, 0, 0, 0])
        for topic in (RS_RGB_INFO, RS_DEPTH_INFO):
            rs = info(topic)
            f = rs.K[0]
            rospy.loginfo('%s K %s', topic, rs.K)
            self.assertAlmostEqual(f, 554.60, delta=0.01)
            self.assertEqual(list(rs.K), [f, 0, 320.5, 0, f, 240.5, 0, 0, 1])
            self.assertEqual((rs.width, rs.height), (640, 480))
            self.assertEqual(rs.distortion_model, 'plumb_bob')

    def test_4_optical_frames_in_tf(self):
        expected = quaternion_from_rpy(-math.pi / 2, 0, -math.pi / 2)
        for link in ('camera', 'real_sense'):
            optical = link + '_optical_frame'
            tf = self.tf_buffer.lookup_transform(link, optical, rospy.Time(0),
                                                 rospy.Duration(10))
            q = tf.transform.rotation
            t = tf.transform.translation
            got = (q.x, q.y, q.z, q.w)
            sign = 1.0 if sum(a * b for a, b in zip(got, expected)) >= 0 else -1.0
            rospy.loginfo('%s -> %s: rotation %s, translation (%g %g %g)', link, optical, got,
                          t.x, t.y, t.z)
            for a, b in zip(got, expected):
                self.assertAlmostEqual(sign * a, b, delta=1e-6)
            self.assertAlmostEqual(math.hypot(t.x, math.hypot(t.y, t.z)), 0.0, delta=1e-9)
            # ... and the optical frame hangs off the robot's tree (robot_state_publisher).
            self.tf_buffer.lookup_transform('base_link', optical, rospy.Time(0),
                                            rospy.Duration(10))

    def test_5_save_frames(self):
        out = tempfile.mkdtemp(prefix='save_frames_')
        proc = subprocess.run([sys.executable, SAVE_FRAMES, '-o', out, '--timeout', '30'],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
        text = proc.stdout.decode() + proc.stderr.decode()
        rospy.loginfo('save_frames: exit %d\n%s', proc.returncode, text)
        self.assertEqual(proc.returncode, 0, text)
        sizes = {'rrbot_camera1_image_raw.png': (800, 800),
                 'real_sense_rgb_image_raw.png': (640, 480),
                 'real_sense_depth_image_raw.png': (640, 480)}
        for name, size in sizes.items():
            path = os.path.join(out, name)
            self.assertIn(path, proc.stdout.decode())
            w, h, mode, pixels = read_png(path)
            self.assertEqual((w, h), size, name)
            self.assertEqual(mode, 'RGB', name)
            p32 = pixels.reshape(-1, 3).astype(np.uint32)
            colours = len(np.unique((p32[:, 0] << 16) | (p32[:, 1] << 8) | p32[:, 2]))
            rospy.loginfo('%s: %dx%d, %d distinct colours', name, w, h, colours)
            self.assertGreater(colours, 20, '%s looks uniform' % name)
        self.assertIn('blue = ', proc.stdout.decode())  # the depth range is printed

        proc = subprocess.run([sys.executable, SAVE_FRAMES, '-o', out, '--timeout', '1',
                               '--camera', '/no_such_camera/image_raw'],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
        self.assertNotEqual(proc.returncode, 0)
        self.assertIn('timed out', proc.stderr.decode())
        self.assertIn('/no_such_camera/image_raw', proc.stderr.decode())


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'camera', Camera)
