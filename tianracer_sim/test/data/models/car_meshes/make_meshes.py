#!/usr/bin/env python3
"""Writes the meshes of test model (c) (car_meshes.urdf) as ASCII STL, as CAD exports name them:
meshes/chassis.STL (a 0.36 x 0.16 x 0.06 m box centred on its origin) and meshes/wheel.STL (a
cylinder of radius 0.05 m and width 0.035 m about the y axis, 32 sides).
Run from this folder: ./make_meshes.py"""
import math


def facet(out, a, b, c):
    out.append('  facet normal 0 0 0\n    outer loop\n')
    for v in (a, b, c):
        out.append('      vertex %.6f %.6f %.6f\n' % v)
    out.append('    endloop\n  endfacet\n')


def box(sx, sy, sz):
    out = []
    h = (sx / 2, sy / 2, sz / 2)
    for axis in range(3):
        for sign in (-1, 1):
            u, v = [a for a in range(3) if a != axis]
            corners = []
            for cu, cv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis], p[u], p[v] = sign * h[axis], cu * h[u], cv * h[v]
                corners.append(tuple(p))
            if sign < 0:
                corners.reverse()
            facet(out, corners[0], corners[1], corners[2])
            facet(out, corners[0], corners[2], corners[3])
    return out


def cylinder_y(r, w, n):
    out = []
    ring = [(r * math.cos(2 * math.pi * i / n), r * math.sin(2 * math.pi * i / n)) for i in range(n)]
    for i in range(n):
        (x0, z0), (x1, z1) = ring[i], ring[(i + 1) % n]
        a, b = (x0, w / 2, z0), (x1, w / 2, z1)
        c, d = (x0, -w / 2, z0), (x1, -w / 2, z1)
        facet(out, a, c, d)
        facet(out, a, d, b)
        facet(out, (0.0, w / 2, 0.0), b, a)
        facet(out, (0.0, -w / 2, 0.0), c, d)
    return out


def write(path, name, facets):
    with open(path, 'w') as f:
        f.write('solid %s\n' % name)
        f.writelines(facets)
        f.write('endsolid %s\n' % name)


if __name__ == '__main__':
    write('meshes/chassis.STL', 'chassis', box(0.36, 0.16, 0.06))
    write('meshes/wheel.STL', 'wheel', cylinder_y(0.05, 0.035, 32))
