#!/usr/bin/env python3
"""render_bench --cost-table (docs/performance.md, Cameras without a GPU): the sections and rows
the docs quote are printed, with the renderer's own counts, and every LP_NUM_THREADS child ran.
No timing is asserted: figures are for the benchmark, not for tests."""
import os
import re
import subprocess
import unittest


def find_bench():
    for prefix in os.environ.get('CMAKE_PREFIX_PATH', '').split(os.pathsep):
        path = os.path.join(prefix, 'lib', 'tianracer_sim', 'render_bench')
        if prefix and os.access(path, os.X_OK):
            return path
    return None


def rows(text):
    """{first cell: [cells]} of the markdown table rows."""
    out = {}
    for line in text.splitlines():
        if line.startswith('| ') and not line.startswith('|---'):
            cells = [c.strip() for c in line.strip().strip('|').split('|')]
            out[cells[0]] = cells[1:]
    return out


class CostTableTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        bench = find_bench()
        if bench is None:
            raise AssertionError('render_bench not found under CMAKE_PREFIX_PATH: build the target '
                                 'render_bench and source devel/setup.bash')
        p = subprocess.run([bench, '--cost-table', '--frames', '1'], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, universal_newlines=True, timeout=300)
        cls.code, cls.out, cls.err = p.returncode, p.stdout, p.stderr
        cls.rows = rows(p.stdout)

    def test_exits_cleanly_with_every_section(self):
        self.assertEqual(self.code, 0, self.err)
        for title in ('### Per frame and per triangle', '### Per pixel', '### Shading and textures',
                      "### llvmpipe's rasteriser threads"):
            self.assertIn(title, self.out)

    def test_counts_come_from_the_renderer(self):
        empty = self.rows['camera1 800x800 colour, empty scene (clear, set-up, read-back)']
        self.assertEqual(empty[:2], ['0', '0'])  # triangles, draw calls
        seed = self.rows['camera1 800x800 colour, seed scene']
        boxes = self.rows['camera1 800x800 colour, seed scene, meshes as their bounding boxes']
        self.assertGreater(int(seed[0]), 1000)
        self.assertGreater(int(seed[1]), 10)
        self.assertLess(int(boxes[0]), int(seed[0]))  # the meshes were replaced
        self.assertEqual(boxes[1], seed[1])  # one draw per item either way
        self.assertEqual(self.rows['camera1 800x800 colour, ground plane only'][:2], ['2', '1'])

    def test_every_size_and_thread_count_has_figures(self):
        for side in (200, 400, 800, 1131, 1600):
            cells = self.rows['%dx%d' % (side, side)]
            self.assertEqual(cells[0], str(side * side))
            self.assertGreater(float(cells[1]), 0.0)
        for threads in '01234':
            cells = self.rows[threads]
            self.assertEqual(len(cells), 4, cells)
            for c in cells:
                self.assertRegex(c, r'^\d+\.\d\d$')


if __name__ == '__main__':
    unittest.main()
