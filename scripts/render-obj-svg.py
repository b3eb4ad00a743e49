#!/usr/bin/env python3
"""Draws OBJ surfaces (faces, and polylines 'l') side by side as flat-shaded SVG, painter's algorithm,
orthographic, seen from the side and a little from below (docs/three-d.md's shell pictures):

    python3 scripts/render-obj-svg.py OUT.svg A.obj "label A" B.obj "label B" ...
"""
import math
import sys


def read_obj(path):
    vertices, faces, lines = [], [], []
    for row in open(path):
        w = row.split()
        if not w:
            continue
        if w[0] == 'v':
            vertices.append(tuple(float(c) for c in w[1:4]))
        elif w[0] == 'f':
            faces.append([int(c.split('/')[0]) - 1 for c in w[1:]])
        elif w[0] == 'l':
            lines.append([int(c) - 1 for c in w[1:]])
    return vertices, faces, lines


def view(p, elevation=-0.35, azimuth=0.6):
    """Screen x, y (up) and depth (toward the viewer) of a point."""
    x, y, z = p
    ca, sa = math.cos(azimuth), math.sin(azimuth)
    x, z = ca * x + sa * z, -sa * x + ca * z
    ce, se = math.cos(elevation), math.sin(elevation)
    y, z = ce * y - se * z, se * y + ce * z
    return x, y, z


def panel(vertices, faces, lines, ox, scale, size):
    light = (0.3, 0.8, 0.5)
    out = []
    items = []
    for f in faces:
        q = [view(vertices[i]) for i in f]
        a = [q[1][k] - q[0][k] for k in range(3)]
        b = [q[2][k] - q[0][k] for k in range(3)]
        n = (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
        ln = math.sqrt(sum(c * c for c in n)) or 1.0
        shade = abs(sum(n[k] * light[k] for k in range(3)) / ln)
        depth = sum(p[2] for p in q) / 3
        items.append((depth, q, shade))
    for strand in lines:  # tentacle segments, sorted with the faces
        for i, j in zip(strand, strand[1:]):
            q = [view(vertices[i]), view(vertices[j])]
            items.append(((q[0][2] + q[1][2]) / 2, q, None))
    items.sort(key=lambda it: it[0])
    cx, cy = ox + size / 2, size * 0.62
    for _, q, shade in items:
        pts = ' '.join(f'{cx + scale * p[0]:.2f},{cy - scale * p[1]:.2f}' for p in q)
        if shade is None:
            out.append(f'<polyline points="{pts}" fill="none" stroke="rgb(200,120,60)" stroke-width="1.5"/>')
            continue
        g = int(90 + 150 * shade)
        out.append(f'<polygon points="{pts}" fill="rgb({g // 2},{g // 2 + 20},{g})" stroke="rgb(40,40,60)" stroke-width="0.4"/>')
    return out


def main():
    out_path, args = sys.argv[1], sys.argv[2:]
    size, scale = 360, 6000.0
    body = []
    for k in range(0, len(args), 2):
        v, f, l = read_obj(args[k])
        body += panel(v, f, l, size * (k // 2), scale, size)
        body.append(f'<text x="{size * (k // 2) + 10}" y="{size - 12}" font-family="sans-serif" font-size="15">{args[k + 1]}</text>')
    width = size * (len(args) // 2)
    with open(out_path, 'w') as fh:
        fh.write(f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{size}">'
                 f'<rect width="100%" height="100%" fill="white"/>' + ''.join(body) + '</svg>\n')


main()
