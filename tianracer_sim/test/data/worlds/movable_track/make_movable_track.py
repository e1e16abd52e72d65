#!/usr/bin/env python3
"""Writes the movable track of test_sim_world_models.cpp (run by hand; its output is committed).

The case of issue 24 ("a movable floor throws the car"): a non-static track model whose floor and
walls are two links with no joint between them, mesh collisions, 1,665 kg each, saved by Gazebo
while it was still settling (its <state> has the floor 0.4 mm sunk and a hair tilted, the walls
1.3 mm above the ground).

- floor.stl (binary): a 5.6 m x 5.6 m slab, 2 cm thick (z 0..0.02 in its link), its top and
  bottom split into 0.4 m squares. (The issue's floor is COLLADA; how a DAE is placed is the mesh
  loader's business, the physics takes its triangles as they come.)
- walls.stl (ASCII): a square ring around the floor on the ground, outer 6 m, inner 5.6 m,
  0.3 m high. Its convex hull would be a 6 x 6 x 0.3 m block around the car.
- movable_track.world: the model, with the inertias of the slab and the ring.
The two links of one model do not collide with each other (SDF <self_collide> is false).
"""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
SIZE, THICK, CELLS = 5.6, 0.02, 14
OUTER = 6.0
INNER, HEIGHT = SIZE, 0.3
MASS = 1665.0


def floor_mesh():
    verts, tris = [], []
    h = SIZE / 2
    step = SIZE / CELLS
    index = {}

    def v(x, y, z):
        key = (round(x, 6), round(y, 6), round(z, 6))
        if key not in index:
            index[key] = len(verts)
            verts.append(key)
        return index[key]

    for i in range(CELLS):
        for j in range(CELLS):
            x0, x1 = -h + i * step, -h + (i + 1) * step
            y0, y1 = -h + j * step, -h + (j + 1) * step
            a, b, c, d = v(x0, y0, THICK), v(x1, y0, THICK), v(x1, y1, THICK), v(x0, y1, THICK)
            tris += [(a, b, c), (a, c, d)]  # top, normal +z
            a, b, c, d = v(x0, y0, 0), v(x1, y0, 0), v(x1, y1, 0), v(x0, y1, 0)
            tris += [(a, c, b), (a, d, c)]  # bottom, normal -z
    for k in range(CELLS):
        s0, s1 = -h + k * step, -h + (k + 1) * step
        # sides at y = -h, x = +h, y = +h, x = -h, normals outwards
        for (p0, p1) in [((s0, -h), (s1, -h)), ((h, s0), (h, s1)), ((s1, h), (s0, h)), ((-h, s1), (-h, s0))]:
            a, b = v(p0[0], p0[1], 0), v(p1[0], p1[1], 0)
            c, d = v(p1[0], p1[1], THICK), v(p0[0], p0[1], THICK)
            tris += [(a, b, c), (a, c, d)]
    return verts, tris


def ring_mesh():
    ho, hi = OUTER / 2, INNER / 2
    outer = [(-ho, -ho), (ho, -ho), (ho, ho), (-ho, ho)]
    inner = [(-hi, -hi), (hi, -hi), (hi, hi), (-hi, hi)]
    tris = []
    for k in range(4):
        o0, o1 = outer[k], outer[(k + 1) % 4]
        i0, i1 = inner[k], inner[(k + 1) % 4]
        P = lambda p, z: (p[0], p[1], z)
        # outer wall (normal out), inner wall (normal in, towards the centre)
        tris += [(P(o0, 0), P(o1, 0), P(o1, HEIGHT)), (P(o0, 0), P(o1, HEIGHT), P(o0, HEIGHT))]
        tris += [(P(i1, 0), P(i0, 0), P(i0, HEIGHT)), (P(i1, 0), P(i0, HEIGHT), P(i1, HEIGHT))]
        # top (normal +z) and bottom (normal -z)
        tris += [(P(o0, HEIGHT), P(o1, HEIGHT), P(i1, HEIGHT)), (P(o0, HEIGHT), P(i1, HEIGHT), P(i0, HEIGHT))]
        tris += [(P(o0, 0), P(i1, 0), P(o1, 0)), (P(o0, 0), P(i0, 0), P(i1, 0))]
    return tris


def normal(t):
    a, b, c = t
    u = [b[i] - a[i] for i in range(3)]
    w = [c[i] - a[i] for i in range(3)]
    n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
    l = sum(x * x for x in n) ** 0.5
    return [x / l for x in n]


def write_binary_stl(path, tris):
    with open(path, "wb") as f:
        f.write(b"movable track floor".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", *normal(t)))
            for p in t:
                f.write(struct.pack("<3f", *p))
            f.write(struct.pack("<H", 0))


def write_ascii_stl(path, tris):
    with open(path, "w") as f:
        f.write("solid walls\n")
        for t in tris:
            f.write("  facet normal %g %g %g\n    outer loop\n" % tuple(normal(t)))
            for p in t:
                f.write("      vertex %g %g %g\n" % p)
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid walls\n")


def slab_inertia(m, a, b, c):
    return (m / 12 * (b * b + c * c), m / 12 * (a * a + c * c), m / 12 * (a * a + b * b))


def ring_inertia(m):
    """Four wall boxes of equal density: two along x (full length), two along y (between)."""
    t = (OUTER - INNER) / 2
    boxes = [(OUTER, t, HEIGHT, 0, (OUTER - t) / 2), (OUTER, t, HEIGHT, 0, -(OUTER - t) / 2),
             (t, INNER, HEIGHT, (OUTER - t) / 2, 0), (t, INNER, HEIGHT, -(OUTER - t) / 2, 0)]
    vol = sum(a * b * c for a, b, c, _, _ in boxes)
    ixx = iyy = izz = 0.0
    for a, b, c, x, y in boxes:
        mb = m * a * b * c / vol
        i = slab_inertia(mb, a, b, c)
        ixx += i[0] + mb * y * y
        iyy += i[1] + mb * x * x
        izz += i[2] + mb * (x * x + y * y)
    return ixx, iyy, izz


def mesh_link(name, com_z, inertia, pose=False):
    """A link of MASS whose collision and visual are the mesh <name>.stl."""
    return ('      <link name="%s">\n' % name +
            ('        <pose>0 0 0 0 0 0</pose>\n' if pose else '') + """        <inertial>
          <pose>0 0 %g 0 0 0</pose>
          <mass>%g</mass>
          <inertia><ixx>%.6g</ixx><iyy>%.6g</iyy><izz>%.6g</izz></inertia>
        </inertial>
        <collision name="collision">
          <geometry><mesh><uri>%s.stl</uri></mesh></geometry>
        </collision>
        <visual name="visual">
          <geometry><mesh><uri>%s.stl</uri></mesh></geometry>
        </visual>
      </link>
""" % ((com_z, MASS) + tuple(inertia) + (name, name)))


def model(name, static):
    return """    <model name="%s">
      <static>%s</static>
      <pose>0 0 0 0 0 0</pose>
%s%s    </model>
""" % (name, "true" if static else "false",
       mesh_link("floor", THICK / 2, slab_inertia(MASS, SIZE, SIZE, THICK)),
       mesh_link("walls", HEIGHT / 2, ring_inertia(MASS), pose=True))


def world():
    # Saved while settling: the floor 0.4 mm sunk into the ground and tilted by 2e-5 rad, the
    # walls 1.3 mm above it.
    state = """    <state world_name="movable_track">
      <sim_time>3 120000000</sim_time>
      <model name="track">
        <pose>0 0 0 0 0 0</pose>
        <link name="floor"><pose>0 0 -0.0004 2e-05 0 0</pose></link>
        <link name="walls"><pose>0 0 0.0013 0 0 0</pose></link>
      </model>
    </state>
"""
    return """<?xml version="1.0"?>
<!-- Written by make_movable_track.py. -->
<sdf version="1.6">
  <world name="movable_track">
    <include><uri>model://ground_plane</uri></include>
%s%s  </world>
</sdf>
""" % (model("track", False), state)


verts, tris = floor_mesh()
write_binary_stl(os.path.join(HERE, "floor.stl"), [tuple(verts[i] for i in t) for t in tris])
write_ascii_stl(os.path.join(HERE, "walls.stl"), ring_mesh())
with open(os.path.join(HERE, "movable_track.world"), "w") as f:
    f.write(world())
print("floor: %d vertices, %d triangles; walls: %d triangles" % (len(verts), len(tris), len(ring_mesh())))
