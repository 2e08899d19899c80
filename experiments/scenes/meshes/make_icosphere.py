#!/usr/bin/python3
"""Writes icosphere.obj: the unit sphere as an icosahedron subdivided 3 times
(642 vertices, 1280 faces, every vertex on the sphere, faces counter-clockwise
seen from outside). A scene scales it to its radius (`scale`, metres per unit).

    /usr/bin/python3 experiments/scenes/meshes/make_icosphere.py [LEVEL] > icosphere.obj
"""
import math
import sys


def icosphere(level):
    t = (1 + math.sqrt(5)) / 2
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
             (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    verts = [tuple(c / math.sqrt(sum(x * x for x in v)) for c in v) for v in verts]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        mid = {}

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                m = [(p + q) / 2 for p, q in zip(verts[a], verts[b])]
                n = math.sqrt(sum(x * x for x in m))
                verts.append(tuple(x / n for x in m))
                mid[key] = len(verts) - 1
            return mid[key]

        new = []
        for a, b, c in faces:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            new += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = new
    return verts, faces


def main():
    level = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    verts, faces = icosphere(level)
    print(f"# unit icosphere, level {level}: {len(verts)} vertices, {len(faces)} faces "
          "(experiments/scenes/meshes/make_icosphere.py)")
    for v in verts:
        print("v %.15g %.15g %.15g" % v)
    for f in faces:
        print("f %d %d %d" % tuple(i + 1 for i in f))


if __name__ == "__main__":
    main()
