#!/usr/bin/env python3
"""Generate the standard component models (Wavefront OBJ) for the Pailou and
Toukung grammars of Cai et al., "Interactive Iconized Grammar-based Pailou
Modeling".

    python3 scripts/make_components.py [OUT_DIR]

OUT_DIR defaults to grammar/std/components/ beside this script's project.
Standard library only. The output is deterministic: running the script again
rewrites the same bytes.

Conventions (those of the loader, src/mesh/components.rs):

* every model fills the box [-0.5, 0.5]^3 exactly (touches all six faces);
* x = width, y = height, z = depth; the front faces -z;
* the turtle puts y along its heading H, x along its left L and the front
  (-z) toward its up U, with the middle of the bottom face (0, -0.5, 0) at
  the turtle. Long parts (arms, Ang, nose, pillar, post) therefore have
  their LENGTH along +y; the lintel, the flower board, the Queti and the
  Yundan span along x (they are placed upright, heading up).
* Toukung parts that lie horizontally (MAO, MAL, MAn, MNo) have their TOP
  (where the small blocks sit, the side the Ang's beak slopes away from)
  toward -z, i.e. toward the turtle's U. Change ARM_TOP below to move it.
* faces are triangles, counter-clockwise seen from outside, `f v//vn`;
  flat normals on flat parts, smooth normals on round ones;
* every model is a union of closed, consistently oriented shells (each edge
  of a shell is shared by exactly two triangles, in opposite directions);
  small parts (the blocks on an arm, the cushion of a pillar base) are
  separate shells sunk slightly into the part they sit on.

Each file starts with a comment giving the model's natural proportions
(before it was stretched to the unit box) so a grammar can scale it back,
e.g. `~MP(ω*αPW, ω, ω*αPW)`.

Units inside the builders are free (the Toukung parts use the Song-dynasty
"fen" module of the Yingzao Fashi); normalise() maps every model to the
unit box at the end.
"""

import math
import os
import sys

# Which side of a horizontal Toukung part is its top: "-z" (toward the
# turtle's U, the default), "+z", "+x" or "-x".
ARM_TOP = "-z"

# ---------------------------------------------------------------------------
# small vector helpers


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def mul(a, k):
    return (a[0] * k, a[1] * k, a[2] * k)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def length(a):
    return math.sqrt(dot(a, a))


def normalize(a):
    n = length(a)
    return (0.0, 0.0, 0.0) if n == 0 else (a[0] / n, a[1] / n, a[2] / n)


_uid = [0]
# Segments per curve are multiplied by D: 1 for the preview set
# (`--detail 0`), 3 for the default set (see main).
D = 1


def new_group(label=""):
    """A fresh smoothing-group id: faces sharing it get averaged normals."""
    _uid[0] += 1
    return (_uid[0], label)


# ---------------------------------------------------------------------------
# 2D polygon triangulation (ear clipping, handles concave outlines)


def area2(pts):
    """Twice the signed area of a 2D polygon (positive = counter-clockwise)."""
    s = 0.0
    for i in range(len(pts)):
        x0, y0 = pts[i - 1]
        x1, y1 = pts[i]
        s += x0 * y1 - x1 * y0
    return s


def _cross2(a, b, c):
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def _in_tri(p, a, b, c, eps):
    # inclusive: a point on an edge counts as inside (it would make a T-junction)
    d1 = _cross2(a, b, p)
    d2 = _cross2(b, c, p)
    d3 = _cross2(c, a, p)
    return d1 >= -eps and d2 >= -eps and d3 >= -eps


def earclip(pts):
    """Triangulate a simple counter-clockwise polygon given as 2D points.
    Returns index triples (counter-clockwise). Collinear vertices are kept
    (they are shared with neighbouring faces) and never become slivers
    unless the polygon leaves no other choice."""
    n = len(pts)
    if n < 3:
        return []
    scale = max(max(abs(p[0]) for p in pts), max(abs(p[1]) for p in pts), 1e-12)
    eps = 1e-12 * scale * scale
    idx = list(range(n))
    tris = []
    while len(idx) > 3:
        m = len(idx)
        best = None
        best_q = -1.0
        for k in range(m):
            i0, i1, i2 = idx[k - 1], idx[k], idx[(k + 1) % m]
            a, b, c = pts[i0], pts[i1], pts[i2]
            cr = _cross2(a, b, c)
            if cr <= eps:
                continue
            ok = True
            for j in idx:
                if j in (i0, i1, i2):
                    continue
                p = pts[j]
                if p == a or p == b or p == c:
                    continue
                if _in_tri(p, a, b, c, eps):
                    ok = False
                    break
            if not ok:
                continue
            # prefer well-shaped ears (largest smallest-angle proxy)
            la = math.dist(a, b)
            lb = math.dist(b, c)
            lc = math.dist(c, a)
            q = cr / max(la * la + lb * lb + lc * lc, 1e-30)
            if q > best_q:
                best_q = q
                best = k
        if best is None:
            # degenerate remainder (only collinear vertices left): drop a
            # collinear vertex with a zero-area triangle to stay watertight
            best = 0
            for k in range(m):
                a, b, c = pts[idx[k - 1]], pts[idx[k]], pts[idx[(k + 1) % m]]
                if abs(_cross2(a, b, c)) <= eps:
                    best = k
                    break
        k = best
        tris.append((idx[k - 1], idx[k], idx[(k + 1) % m]))
        idx.pop(k)
    tris.append((idx[0], idx[1], idx[2]))
    return tris


# ---------------------------------------------------------------------------
# the mesh


class Mesh:
    def __init__(self):
        self.v = []  # positions
        self.f = []  # (i, j, k, group or None)

    def vert(self, p):
        self.v.append((float(p[0]), float(p[1]), float(p[2])))
        return len(self.v) - 1

    def tri(self, a, b, c, g=None):
        if a == b or b == c or c == a:
            return
        self.f.append((a, b, c, g))

    def quad(self, a, b, c, d, g=None):
        """Two triangles; splits along the shorter diagonal."""
        if a == b:
            self.tri(a, c, d, g)
            return
        if c == d:
            self.tri(a, b, c, g)
            return
        if b == c:
            self.tri(a, b, d, g)
            return
        if d == a:
            self.tri(a, b, c, g)
            return
        P = self.v
        if math.dist(P[a], P[c]) <= math.dist(P[b], P[d]):
            self.tri(a, b, c, g)
            self.tri(a, c, d, g)
        else:
            self.tri(a, b, d, g)
            self.tri(b, c, d, g)

    def polygon(self, ids, g=None):
        """Fill a planar polygon (vertex ids in order; its winding gives the
        face's side) by ear clipping in its own plane."""
        pts = [self.v[i] for i in ids]
        nrm = (0.0, 0.0, 0.0)
        for i in range(len(pts)):
            a, b = pts[i], pts[(i + 1) % len(pts)]
            nrm = add(nrm, ((a[1] - b[1]) * (a[2] + b[2]), (a[2] - b[2]) * (a[0] + b[0]),
                            (a[0] - b[0]) * (a[1] + b[1])))
        nrm = normalize(nrm)
        helper = (1.0, 0.0, 0.0) if abs(nrm[0]) < 0.9 else (0.0, 1.0, 0.0)
        e1 = normalize(cross(helper, nrm))
        e2 = cross(nrm, e1)
        p2 = [(dot(p, e1), dot(p, e2)) for p in pts]
        for (i, j, k) in earclip(p2):
            self.tri(ids[i], ids[j], ids[k], g)

    def merge(self, other):
        off = len(self.v)
        self.v.extend(other.v)
        self.f.extend((a + off, b + off, c + off, g) for (a, b, c, g) in other.f)
        return self

    def signed_volume(self):
        s = 0.0
        for (a, b, c, _) in self.f:
            s += dot(self.v[a], cross(self.v[b], self.v[c]))
        return s / 6.0

    def orient_outward(self):
        """Reverse a (single, closed) shell that came out inside-out."""
        if self.signed_volume() < 0:
            self.f = [(a, c, b, g) for (a, b, c, g) in self.f]
        return self

    def transform(self, m, t=(0.0, 0.0, 0.0)):
        """p -> M p + t, M a 3x3 row-major matrix; mirror images keep their
        faces outward."""
        self.v = [(dot(m[0], p) + t[0], dot(m[1], p) + t[1], dot(m[2], p) + t[2]) for p in self.v]
        det = dot(m[0], cross(m[1], m[2]))
        if det < 0:
            self.f = [(a, c, b, g) for (a, b, c, g) in self.f]
        return self

    def translate(self, t):
        return self.transform(((1, 0, 0), (0, 1, 0), (0, 0, 1)), t)

    def scale(self, s):
        return self.transform(((s[0], 0, 0), (0, s[1], 0), (0, 0, s[2])))

    def bounds(self):
        lo = tuple(min(p[i] for p in self.v) for i in range(3))
        hi = tuple(max(p[i] for p in self.v) for i in range(3))
        return lo, hi


# ---------------------------------------------------------------------------
# builders; each returns one closed, outward-oriented shell


def loft(rings, seg_groups=None, around=False, cap0=True, cap1=True, per=None):
    """Skin a sequence of rings (lists of 3D points, all the same length n,
    or a single point for an apex). Ring k is joined to ring k+1 with quads;
    the first and last rings are closed with flat caps. seg_groups[k] is a
    label (or None for flat shading) for the band between rings k and k+1:
    bands with the same label are smoothed together along the sweep; with
    around=True they are also smooth around the ring (round sections),
    otherwise each ring edge keeps its own crease; with per=k, runs of k
    ring edges (the petals of a lobed ring) are smooth, creased between."""
    m = Mesh()
    ids = [[m.vert(p) for p in ring] for ring in rings]
    n = max(len(r) for r in rings)
    groups = {}

    def grp(k, j):
        lab = seg_groups[k] if seg_groups else None
        if lab is None:
            return None
        key = (lab,) if around else ((lab, j // per) if per else (lab, j))
        if key not in groups:
            groups[key] = new_group(str(key))
        return groups[key]

    for k in range(len(rings) - 1):
        a, b = ids[k], ids[k + 1]
        for j in range(n):
            j1 = (j + 1) % n
            a0 = a[0] if len(a) == 1 else a[j]
            a1 = a[0] if len(a) == 1 else a[j1]
            b0 = b[0] if len(b) == 1 else b[j]
            b1 = b[0] if len(b) == 1 else b[j1]
            m.quad(a0, a1, b1, b0, grp(k, j))
    if cap0 and len(ids[0]) > 2:
        m.polygon(list(reversed(ids[0])))
    if cap1 and len(ids[-1]) > 2:
        m.polygon(list(ids[-1]))
    return m.orient_outward()


def lathe(profile, n=24, seg_groups=None, phase=0.0):
    """Revolve a profile of (r, y) points about the y axis. Points with r == 0
    become poles. Open ends (r > 0 at the first/last point) get flat caps."""
    rings = []
    for (r, y) in profile:
        if r == 0:
            rings.append([(0.0, y, 0.0)])
        else:
            rings.append([(r * math.cos(phase + 2 * math.pi * i / n), y,
                           -r * math.sin(phase + 2 * math.pi * i / n)) for i in range(n)])
    return loft(rings, seg_groups, around=True)


# Right-handed axis frames for extrusions: profile (u, v), extrusion axis w.
FRAMES = {
    "xy": lambda u, v, w: (u, v, w),  # profile in x-y, extruded along z
    "yz": lambda u, v, w: (w, u, v),  # profile in y-z, extruded along x
    "zx": lambda u, v, w: (v, w, u),  # profile in z-x, extruded along y
}


def extrude(profile, w0, w1, frame="xy", edge_groups=None):
    """Extrude a simple 2D polygon (any winding, concave allowed) along the
    frame's third axis from w0 to w1. edge_groups[i] labels the side face of
    profile edge i -> i+1; consecutive edges with the same label are shaded
    smooth. Caps are ear-clipped."""
    pts = list(profile)
    groups = list(edge_groups) if edge_groups else [None] * len(pts)
    if area2(pts) < 0:
        pts.reverse()
        # edge i (p_i -> p_i+1) becomes edge n-2-i after reversal
        n = len(pts)
        groups = [groups[(n - 2 - i) % n] for i in range(n)]
    emb = FRAMES[frame]
    m = Mesh()
    bot = [m.vert(emb(u, v, w0)) for (u, v) in pts]
    top = [m.vert(emb(u, v, w1)) for (u, v) in pts]
    made = {}
    n = len(pts)
    for i in range(n):
        j = (i + 1) % n
        lab = groups[i]
        g = None
        if lab is not None:
            if lab not in made:
                made[lab] = new_group(str(lab))
            g = made[lab]
        m.quad(bot[i], bot[j], top[j], top[i], g)
    for (a, b, c) in earclip(pts):
        m.tri(top[a], top[b], top[c])
        m.tri(bot[a], bot[c], bot[b])
    return m.orient_outward()


def box(x0, x1, y0, y1, z0, z1):
    return extrude([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], z0, z1, "xy")


def stepped(ub, vb, heights, base):
    """A 2.5D stepped block: a grid of cells (breaks ub along x, vb along y),
    cell (i, j) rising from z = base to z = heights[i][j]. One closed shell
    with the walls split wherever neighbouring cells step, so it stays
    watertight. (Rotate it into place with Mesh.transform.)"""
    nu, nv = len(ub) - 1, len(vb) - 1

    def h(i, j):
        if 0 <= i < nu and 0 <= j < nv:
            return heights[i][j]
        return base

    m = Mesh()
    vid = {}

    def V(i, j, z):
        key = (i, j, z)
        if key not in vid:
            vid[key] = m.vert((ub[i], vb[j], z))
        return vid[key]

    def breaks(i, j):
        s = {base}
        for di in (-1, 0):
            for dj in (-1, 0):
                s.add(h(i + di, j + dj))
        return sorted(s)

    for i in range(nu):
        for j in range(nv):
            z = heights[i][j]
            m.quad(V(i, j, z), V(i + 1, j, z), V(i + 1, j + 1, z), V(i, j + 1, z))
            m.quad(V(i, j, base), V(i, j + 1, base), V(i + 1, j + 1, base), V(i + 1, j, base))

    def wall(p, q, lo, hi, outward):
        # polygon p_lo -> q_lo -> (q breaks up) -> q_hi -> p_hi -> (p breaks down)
        pb = [z for z in breaks(*p) if lo <= z <= hi]
        qb = [z for z in breaks(*q) if lo <= z <= hi]
        ring = [V(p[0], p[1], lo)] + [V(q[0], q[1], z) for z in qb] + \
               [V(p[0], p[1], z) for z in reversed(pb) if z != lo]
        # orientation: Newell normal must point along `outward`
        pts = [m.v[i] for i in ring]
        nrm = (0.0, 0.0, 0.0)
        for k in range(len(pts)):
            a, b = pts[k], pts[(k + 1) % len(pts)]
            nrm = add(nrm, ((a[1] - b[1]) * (a[2] + b[2]), (a[2] - b[2]) * (a[0] + b[0]),
                            (a[0] - b[0]) * (a[1] + b[1])))
        if dot(nrm, outward) < 0:
            ring.reverse()
        m.polygon(ring)

    # walls on lines of constant y (between cells (i, j-1) and (i, j))
    for j in range(nv + 1):
        for i in range(nu):
            ha, hb = h(i, j - 1), h(i, j)
            if ha != hb:
                out = (0, 1, 0) if ha > hb else (0, -1, 0)
                wall((i, j), (i + 1, j), min(ha, hb), max(ha, hb), out)
    # walls on lines of constant x
    for i in range(nu + 1):
        for j in range(nv):
            ha, hb = h(i - 1, j), h(i, j)
            if ha != hb:
                out = (1, 0, 0) if ha > hb else (-1, 0, 0)
                wall((i, j), (i, j + 1), min(ha, hb), max(ha, hb), out)
    return m.orient_outward()


def ring_rect(hx, hz, y, cx=0.0, cz=0.0, chamfer=0.0):
    """A horizontal rectangle (optionally with chamfered corners) at height y."""
    if chamfer <= 0:
        return [(cx - hx, y, cz - hz), (cx + hx, y, cz - hz), (cx + hx, y, cz + hz), (cx - hx, y, cz + hz)]
    c = chamfer
    return [(cx - hx + c, y, cz - hz), (cx + hx - c, y, cz - hz), (cx + hx, y, cz - hz + c),
            (cx + hx, y, cz + hz - c), (cx + hx - c, y, cz + hz), (cx - hx + c, y, cz + hz),
            (cx - hx, y, cz + hz - c), (cx - hx, y, cz - hz + c)]


# rotations used to put parts into place
ROT_X180 = ((1, 0, 0), (0, -1, 0), (0, 0, -1))
ROT_Y180 = ((-1, 0, 0), (0, 1, 0), (0, 0, -1))
# arm local frame (x across, y along, z up) -> component frame with the top on ARM_TOP
ARM_FRAMES = {
    "-z": ROT_Y180,                        # (x, y, z) -> (-x, y, -z)
    "+z": ((1, 0, 0), (0, 1, 0), (0, 0, 1)),
    "+x": ((0, 0, 1), (0, 1, 0), (-1, 0, 0)),   # up -> +x
    "-x": ((0, 0, -1), (0, 1, 0), (1, 0, 0)),   # up -> -x
}


# ---------------------------------------------------------------------------
# Toukung parts. Local frame for the horizontal ones: x across, y along the
# part (length), z up; units: fen (Yingzao Fashi module).


def dou(w_along, w_across, height, slot, taper=0.75, hollow=0.06, slot_along=True):
    """A bearing block (dou / sheng): tapered, slightly hollowed lower 2/5
    (qi), straight 1/5 (ping), top 2/5 (ear) cut by a slot of width `slot`
    running along y (slot_along) or a cross of slots (slot_along=None).
    Bottom centre at the origin, z up. Returns a list of shells."""
    qi, ping = 0.4 * height, 0.2 * height
    ha, hc = w_across / 2, w_along / 2
    rings = []
    steps = 6 * D
    for s in range(steps + 1):
        t = s / steps
        k = taper + (1 - taper) * t - hollow * math.sin(math.pi * t)
        z = qi * t
        rings.append([(-ha * k, -hc * k, z), (ha * k, -hc * k, z), (ha * k, hc * k, z), (-ha * k, hc * k, z)])
    # one more ring, just inside the upper block, so the two shells overlap
    z = qi + 0.05 * height
    k = 0.995
    rings.append([(-ha * k, -hc * k, z), (ha * k, -hc * k, z), (ha * k, hc * k, z), (-ha * k, hc * k, z)])
    groups = ["qi"] * steps + [None]
    lower = loft(rings, groups)
    s2 = slot / 2
    top = height
    low = qi + ping
    if slot_along is None:
        ub = [-ha, -s2, s2, ha]
        vb = [-hc, -s2, s2, hc]
        hs = [[top, low, top], [low, low, low], [top, low, top]]
    else:
        ub = [-ha, -s2, s2, ha]
        vb = [-hc, hc]
        hs = [[top], [low], [top]]
    upper = stepped(ub, vb, hs, qi)
    return [lower, upper]


def sheng_row(mesh, ys, ztop, w_along=16.0, w_across=14.0, height=10.0):
    for y in ys:
        for shell in dou(w_along, w_across, height, slot=6.0):
            shell.translate((0.0, y, ztop - 0.5))
            mesh.merge(shell)


def gong_profile(length, height, end_h, roll_len, segs=None):
    """Side view (y, z) of a bracket arm: flat top, vertical end faces down to
    end_h, then the rounded 'juansha' underside rising to the ends."""
    segs = segs or 8 * D
    L2 = length / 2
    pts = [(-L2 + roll_len, 0.0), (L2 - roll_len, 0.0)]
    groups = [None]
    # right end: quarter ellipse from bottom (L2-roll_len, 0) up to (L2, end_h)
    for s in range(1, segs + 1):
        a = (math.pi / 2) * s / segs
        pts.append((L2 - roll_len + roll_len * math.sin(a), end_h - end_h * math.cos(a)))
        groups.append("roll_r")
    pts.append((L2, height))
    groups.append(None)
    pts.append((-L2, height))
    groups.append(None)
    pts.append((-L2, end_h))
    groups.append(None)
    for s in range(1, segs):
        a = (math.pi / 2) * (1 - s / segs)
        pts.append((-L2 + roll_len - roll_len * math.sin(a), end_h - end_h * math.cos(a)))
        groups.append("roll_l")
    groups.append("roll_l")  # last edge back to the start point
    return pts, groups


def make_arm(length, n_sheng, roll_len):
    thick, height, end_h = 10.0, 15.0, 8.0
    prof, groups = gong_profile(length, height, end_h, roll_len)
    m = Mesh()
    m.merge(extrude(prof, -thick / 2, thick / 2, "yz", groups))
    L2 = length / 2
    end = L2 - 8.0
    ys = [-end + 2 * end * i / (n_sheng - 1) for i in range(n_sheng)]
    sheng_row(m, ys, height)
    return m.transform(ARM_FRAMES[ARM_TOP])


def make_MAO():
    # guazi gong / nidao gong: 62 fen long, three blocks (ends + middle)
    return make_arm(62.0, 3, 14.0)


def make_MAL():
    # man gong: 92 fen long, four blocks spread evenly
    return make_arm(92.0, 4, 16.0)


def make_MCa():
    # ludou: 32 x 32 fen, 20 fen high, 10 fen cross slot for the arms
    m = Mesh()
    for shell in dou(32.0, 32.0, 20.0, slot=10.0, taper=0.75, hollow=0.05, slot_along=None):
        m.merge(shell)
    # dou() works with z up; the cap stands on the turtle with y up
    return m.transform(((1, 0, 0), (0, 0, 1), (0, -1, 0)))  # (x,y,z)->(x,z,-y)


def ang_section(w, zb, zt):
    """Cross-section of the Ang: flat bottom, sides, and a 'qin mian'
    (lute-face) bevelled top."""
    zm = zt - 0.3 * (zt - zb)
    return [(-w / 2, zb), (w / 2, zb), (w / 2, zm), (w / 4, zt), (-w / 4, zt), (-w / 2, zm)]


def make_MAn():
    """Ang: a long lever sloping down toward its far end (+y), tapering,
    ending in a pointed beak whose top curves down to the tip."""
    L, h0, w0, drop = 100.0, 21.0, 10.0, 12.0
    sb = 0.70           # where the beak starts
    h_tip, w_tip = 1.2, 6.0
    rings = []
    groups = []
    samples = [0.0, 0.35, sb] + [sb + (1 - sb) * k / (12 * D) for k in range(1, 12 * D + 1)]
    for s in samples:
        y = L * s
        w = w0 + (w_tip - w0) * s ** 1.5
        zb = -drop * s
        hb = h0 * (1 - 0.2 * sb)
        if s <= sb:
            hgt = h0 * (1 - 0.2 * s)
        else:
            u = (s - sb) / (1 - sb)
            zb -= 4.0 * u * u          # the beak droops
            hgt = h_tip + (hb - h_tip) * (1 - u) * (1 + 0.6 * u)
        sec = ang_section(w, zb, zb + hgt)
        rings.append([(x, y, z) for (x, z) in sec])
    for k in range(len(samples) - 1):
        groups.append("body" if samples[k + 1] <= sb else "beak")
    m = loft(rings, groups)
    return m.transform(ARM_FRAMES[ARM_TOP])


def make_MNo():
    """Nose (shuatou, 'grasshopper head'): a short beam whose end is carved
    into a pointed beak sloping down from the top, a narrow mouth slot under
    it, and a rounded cloud lobe below."""
    L, H, T = 60.0, 21.0, 10.0
    pts = [(0.0, 0.0), (40.0, 0.0)]
    groups = [None]
    # lower lobe: a round bulging forward, from the bottom up to the mouth
    c, r = (40.0, 7.0), 7.0
    segs = 10 * D
    a0, a1 = -math.pi / 2, math.radians(112)
    for s in range(1, segs + 1):
        a = a0 + (a1 - a0) * s / segs
        pts.append((c[0] + r * math.cos(a), c[1] + r * math.sin(a)))
        groups.append("lobe")
    # from the mouth corner forward along the beak's underside to the tip,
    # then the beak's top slopes back up to the top of the beam
    pts.append((L, 14.5))
    groups.append(None)
    pts.append((43.0, H))
    groups.append(None)
    pts.append((0.0, H))
    groups.append(None)
    groups.append(None)   # tail edge back to the start
    m = extrude(pts, -T / 2, T / 2, "yz", groups)
    return m.transform(ARM_FRAMES[ARM_TOP])


# ---------------------------------------------------------------------------
# Pailou parts (y up, natural units: the pillar height = 1)


def make_MP():
    """Pillar: 24-sided, slight taper with entasis, a ring moulding near the
    top."""
    r0, H = 0.0575, 1.0

    def r(y):
        return r0 * (1 - 0.08 * y + 0.03 * math.sin(math.pi * y * 0.8))

    prof = [(0.0, 0.0)]
    groups = []
    for y in (0.0, 0.2, 0.4, 0.6, 0.75, 0.9):
        prof.append((r(y), y))
    groups += [None] + ["shaft"] * 5
    ry = r(0.9)
    bump = [(ry * 1.04, 0.903), (ry * 1.10, 0.910), (ry * 1.12, 0.918),
            (ry * 1.10, 0.926), (ry * 1.04, 0.933), (r(0.936), 0.936)]
    prof += bump
    groups += ["ring"] * 6
    prof.append((r(1.0), 1.0))
    groups.append("neck")
    prof.append((0.0, 1.0))
    groups.append(None)
    return lathe(prof, 24 * min(D, 2), groups)


def make_MPB():
    """Pillar base: a square plinth with bevelled top edges and a drum-shaped
    cushion on it."""
    m = Mesh()
    rings = [ring_rect(1.0, 1.0, 0.0), ring_rect(1.0, 1.0, 0.38), ring_rect(0.9, 0.9, 0.45)]
    m.merge(loft(rings))
    prof = [(0.0, 0.40), (0.80, 0.40), (0.84, 0.47), (0.865, 0.56), (0.86, 0.65), (0.83, 0.74),
            (0.77, 0.82), (0.69, 0.88), (0.62, 0.92), (0.60, 0.93), (0.60, 0.97), (0.0, 0.97)]
    groups = [None, "drum", "drum", "drum", "drum", "drum", "drum", "drum", None, "mirror", None]
    m.merge(lathe(prof, 32 * min(D, 2), groups))
    return m


def make_ML():
    """Lintel: a long beam along x with a square, chamfered cross-section;
    the painted zones are stepped: full-size end bands (gutou) and centre
    panel (fangxin), the parts between set back slightly."""
    L, a, c, inset = 10.0, 0.5, 0.05, 0.018

    def sec(x, d):
        s = a - d
        cc = c
        return [(x, 0.5 - s + cc, -s), (x, 0.5 + s - cc, -s), (x, 0.5 + s, -s + cc), (x, 0.5 + s, s - cc),
                (x, 0.5 + s - cc, s), (x, 0.5 - s + cc, s), (x, 0.5 - s, s - cc), (x, 0.5 - s, -s + cc)]

    xs = [(-5.0, 0), (-4.55, 0), (-4.55, inset), (-4.45, inset), (-4.45, 0), (-4.35, 0), (-4.35, inset),
          (-1.7, inset), (-1.7, 0), (1.7, 0), (1.7, inset), (4.35, inset), (4.35, 0), (4.45, 0),
          (4.45, inset), (4.55, inset), (4.55, 0), (5.0, 0)]
    rings = [sec(x, d) for (x, d) in xs]
    return loft(rings)


def make_MFB():
    """Flower board: a thin panel, wide in x, with a raised frame, two
    posts dividing it into three recessed fields, and a carved eight-lobed
    rosette in each field (front = -z)."""
    W, H, T, Tf = 10.0, 1.4, 0.16, 0.09
    fr = 0.12
    ub = [-W / 2, -W / 2 + fr, -W / 6 - fr / 2, -W / 6 + fr / 2, W / 6 - fr / 2, W / 6 + fr / 2, W / 2 - fr, W / 2]
    vb = [0.0, fr, H - fr, H]
    hs = []
    for i in range(7):
        col = []
        for j in range(3):
            field = i in (1, 3, 5) and j == 1
            col.append(Tf if field else T)
        hs.append(col)
    m = Mesh()
    board = stepped(ub, vb, hs, 0.0)
    m.merge(board)
    for cx in (-W / 3, 0.0, W / 3):
        m.merge(rosette(cx, H / 2, 0.46, 8, Tf - 0.01, T - 0.015))
        m.merge(rosette(cx, H / 2, 0.16, 8, T - 0.02, T - 0.005, phase=math.pi / 8))
    # the board was built with z = thickness toward the viewer: turn it so
    # the carved face looks down -z
    return m.transform(((1, 0, 0), (0, 1, 0), (0, 0, -1)))


def rosette(cx, cy, r, lobes, z0, z1, phase=0.0):
    """A flat flower: a lobed outline (x-y) extruded from z0 to z1."""
    pts = []
    groups = []
    per = 6
    for k in range(lobes * per):
        t = k / (lobes * per)
        a = phase + 2 * math.pi * t
        rr = r * (0.72 + 0.28 * abs(math.sin(math.pi * lobes * t)))
        pts.append((cx + rr * math.cos(a), cy + rr * math.sin(a)))
        groups.append("lobe%d" % (k // per))
    return extrude(pts, z0, z1, "xy", groups)


def make_MQ():
    """Queti: a thin bracket plate under a lintel end. The pillar side is at
    -x (full height), the top edge is straight under the lintel, the lower
    edge runs in scalloped 'cicada-belly' lobes from the pillar up to a
    rounded scroll tip at +x."""
    W, H, T = 1.0, 0.55, 0.07
    rt = 0.075
    cxt, cyt = W - rt, H - rt
    tip_a0 = math.radians(-125)
    x_end = cxt + rt * math.cos(tip_a0)
    y_end = cyt + rt * math.sin(tip_a0)
    amp = 0.035
    pts = [(0.0, amp)]
    groups = []
    lobes, per = 5, 6 * D
    y_at = lambda x: amp + (y_end - amp) * (x / x_end) ** 1.9
    for k in range(lobes):
        for s in range(1, per + 1):
            t = s / per
            x = x_end * (k + t) / lobes
            y = y_at(x) - amp * math.sin(math.pi * t) * (1.0 - 0.5 * k / lobes)
            pts.append((x, y))
            groups.append("lobe%d" % k)
    # scroll tip: round nose from the lower-left of the circle up to its top
    steps = 10 * D
    for s in range(1, steps + 1):
        a = tip_a0 + (math.radians(90) - tip_a0) * s / steps
        pts.append((cxt + rt * math.cos(a), cyt + rt * math.sin(a)))
        groups.append("tip")
    pts.append((0.0, H))
    groups.append(None)   # top edge
    groups.append(None)   # pillar edge back to the start
    m = Mesh()
    m.merge(extrude(pts, -T / 2, T / 2, "xy", groups))
    # a raised scroll boss on both faces near the tip
    for zsign in (-1, 1):
        boss = lathe([(0.0, 0.0), (0.045, 0.0), (0.05, 0.006), (0.045, 0.012), (0.0, 0.014)], 16 * D,
                     [None, "b", "b", "b"])
        # lathe axis y -> face normal z
        if zsign < 0:
            boss.transform(((1, 0, 0), (0, 0, 1), (0, -1, 0)))   # y -> -z
        else:
            boss.transform(((1, 0, 0), (0, 0, -1), (0, 1, 0)))   # y -> +z
        boss.translate((cxt - 0.005, cyt - 0.005, zsign * (T / 2 - 0.004)))
        m.merge(boss)
    return m


def make_MY():
    """Yundan: a low cloud block; its outline in x-y swells out in three
    cloud lobes on each side, widening upward; extruded in z."""
    W, H, D = 1.0, 0.45, 0.4
    n = 36
    right = []
    for k in range(n + 1):
        y = H * k / n
        t = y / H
        x = 0.28 + 0.12 * t + 0.085 * abs(math.sin(3 * math.pi * t))
        right.append((x, y))
    pts = [(-right[0][0], 0.0)] + right + [(-p[0], p[1]) for p in reversed(right[1:])]
    # pts: bottom-left, up the right side, top-left, down the left side
    groups = [None]  # bottom edge
    for k in range(n):
        groups.append("r%d" % (3 * k // n))
    groups.append(None)  # top edge
    for k in range(n - 1):
        groups.append("l%d" % (2 - 3 * k // n))
    groups.append("l0")
    m = Mesh()
    m.merge(extrude(pts, -D / 2, D / 2, "xy", groups))
    # carved cloud curls on the front: two small lobed discs
    for cx in (-0.17, 0.17):
        m.merge(rosette(cx, H * 0.52, 0.11, 5, -D / 2 + 0.01, -D / 2 - 0.025))
    return m


def make_MIB():
    """Inscribed board: a vertical plaque with a two-step raised border
    around a recessed field (front = -z)."""
    W, H, T, Tm, Tf = 0.6, 1.0, 0.08, 0.066, 0.05
    ub = [-W / 2, -W / 2 + 0.045, -W / 2 + 0.075, W / 2 - 0.075, W / 2 - 0.045, W / 2]
    vb = [0.0, 0.045, 0.075, H - 0.075, H - 0.045, H]
    hs = []
    for i in range(5):
        col = []
        for j in range(5):
            ring = min(i, j, 4 - i, 4 - j)
            col.append(T if ring == 0 else (Tm if ring == 1 else Tf))
        hs.append(col)
    m = stepped(ub, vb, hs, 0.0)
    return m.transform(((1, 0, 0), (0, 1, 0), (0, 0, -1)))


def make_MBP():
    """Booklet pillar: a short square post with chamfered edges on a low
    base, topped by a wider cap with a bevelled top."""
    R = ring_rect
    rings = [R(0.125, 0.125, 0.0, chamfer=0.015), R(0.125, 0.125, 0.06, chamfer=0.015),
             R(0.1, 0.1, 0.06, chamfer=0.02), R(0.1, 0.1, 0.80, chamfer=0.02),
             R(0.125, 0.125, 0.80, chamfer=0.02), R(0.125, 0.125, 0.93, chamfer=0.02),
             R(0.1, 0.1, 1.0, chamfer=0.02)]
    return loft(rings)


# ---------------------------------------------------------------------------
# more Pailou parts (y up unless said otherwise)


def lobed_rings(profile, lobes, per, phase=0.0):
    """Rings for a lobed solid of revolution about y: profile rows (r, y,
    amp, lift) give, at each height, the radius r of the lobes' crests, how
    deep (a fraction of r) the notches between the lobes cut in, and how
    much higher than y the crests stand (petal tips). r == 0 makes a pole.
    Ring point j*per (j = 0, 1, ...) sits in a notch."""
    n = lobes * per
    rings = []
    for (r, y, amp, lift) in profile:
        if r == 0:
            rings.append([(0.0, y, 0.0)])
            continue
        ring = []
        for i in range(n):
            t = i / n
            a = phase + 2 * math.pi * t
            crest = abs(math.sin(math.pi * lobes * t))   # 0 in a notch, 1 on a crest
            rr = r * (1 - amp * (1 - crest))
            ring.append((rr * math.cos(a), y + lift * crest, -rr * math.sin(a)))
        rings.append(ring)
    return rings


def ellipsoid(c, rx, ry, rz, n, nlat, label="ell"):
    """A smooth ellipsoid centred at c: a lathe'd sphere, scaled."""
    prof = [(0.0, -1.0)] + [(math.sin(math.pi * k / nlat), -math.cos(math.pi * k / nlat))
                           for k in range(1, nlat)] + [(0.0, 1.0)]
    m = lathe(prof, n, [label] * nlat)
    m.scale((rx, ry, rz))
    return m.translate(c)


def round_ring(cx, y, cz, hx, hz, n, p=3.0):
    """A horizontal superellipse (a rounded rectangle for p > 2) at height y."""
    ring = []
    for i in range(n):
        a = 2 * math.pi * (i + 0.5) / n
        c, s = math.cos(a), math.sin(a)
        ring.append((cx + hx * math.copysign(abs(c) ** (2 / p), c), y,
                     cz - hz * math.copysign(abs(s) ** (2 / p), s)))
    return ring


def make_MPC():
    """Pillar cap ('cloud cap', yunguan) crowning a free-standing stone
    pillar that rises above the roofs: a short square collar with a
    bevelled top, a disc of twelve upturned lotus petals, a round drum with
    a lip at its foot and its head, and a flame-shaped pointed jewel."""
    m = Mesh()
    m.merge(loft([ring_rect(0.55, 0.55, 0.0), ring_rect(0.55, 0.55, 0.19),
                  ring_rect(0.49, 0.49, 0.25)]))
    # lotus disc: petals widening upward, their tips standing up
    per = 2 * min(D, 2)
    prof = [(0.46, 0.18, 0.0, 0.0), (0.57, 0.27, 0.10, 0.0), (0.68, 0.37, 0.14, 0.0),
            (0.75, 0.47, 0.16, 0.05), (0.0, 0.53, 0.0, 0.0)]
    m.merge(loft(lobed_rings(prof, 12, per, -math.pi / 12), ["petal", "petal", "petal", None], per=per))
    # drum, sunk into the lotus disc
    n = 16 * min(D, 2)
    prof = [(0.0, 0.51), (0.53, 0.51), (0.53, 0.58), (0.47, 0.61), (0.50, 0.73), (0.47, 0.87),
            (0.53, 0.90), (0.53, 0.97), (0.0, 0.97)]
    groups = [None, "lip0", None, "drum", "drum", None, "lip1", None]
    m.merge(lathe(prof, n, groups))
    # flame jewel: a short round neck, a bulb, a concave taper to the point
    prof = [(0.0, 0.95), (0.29, 0.95), (0.29, 1.03), (0.37, 1.12), (0.40, 1.24), (0.34, 1.37),
            (0.21, 1.51), (0.09, 1.66), (0.0, 1.80)]
    groups = [None, None, None] + ["bulb"] * 5
    m.merge(lathe(prof, n, groups))
    return m


def make_MCH():
    """Chuihua ('hanging flower'): the carved pendant ending a suspended
    pillar below the lintel it hangs from. From the top down: the pillar's
    square end (the neck, chamfered), a round ring moulding, and a lotus
    bud of eight petals swelling out and closing to a point at the bottom."""
    m = Mesh()
    H = 2.2
    m.merge(loft([ring_rect(0.35, 0.35, 1.76, chamfer=0.04), ring_rect(0.35, 0.35, H, chamfer=0.04)]))
    n = 16 * min(D, 2)
    prof = [(0.0, 1.80), (0.30, 1.80), (0.40, 1.77), (0.44, 1.71), (0.40, 1.65), (0.30, 1.62),
            (0.27, 1.55), (0.0, 1.55)]
    groups = [None, "ring", "ring", "ring", "ring", None, None]
    m.merge(lathe(prof, n, groups))
    # the bud: eight petals, deepest notches round its waist, a point below
    per = 2 + 2 * min(D, 2)
    k = 4 + 2 * min(D, 2)
    prof = []
    for s in range(1, k):
        u = s / k
        r = math.sin(math.pi * (0.17 + 0.83 * u)) ** 0.8 * (1 - 0.25 * u * u)
        prof.append((r, 1.56 * (1 - u), 0.13 * math.sin(math.pi * u) ** 0.5, 0.0))
    widest = max(p[0] for p in prof)
    prof = [(0.29, 1.60, 0.0, 0.0)] + [(0.5 * r / widest, y, a, l) for (r, y, a, l) in prof] + \
        [(0.0, 0.0, 0.0, 0.0)]
    rings = lobed_rings(prof, 8, per, -math.pi / 8)
    m.merge(loft(rings, ["bud"] * (len(rings) - 1), per=per))
    return m


def make_MCS():
    """Capital stone (zhudingshi): the square stone slab a pillar stands on,
    set flush in the ground, its top edges bevelled, with a very low round
    'ancient mirror' (guji) disc raised in its middle."""
    m = Mesh()
    m.merge(loft([ring_rect(1.4, 1.4, 0.0), ring_rect(1.4, 1.4, 0.28), ring_rect(1.32, 1.32, 0.35)]))
    prof = [(0.0, 0.32), (1.0, 0.32), (1.0, 0.39), (0.98, 0.42), (0.94, 0.44), (0.88, 0.45),
            (0.0, 0.45)]
    groups = [None, None, "edge", "edge", "edge", None]
    m.merge(lathe(prof, 32 * min(D, 2), groups))
    return m


def make_MLS():
    """Small lintel: a slimmer beam under the big lintel (C3), square
    chamfered section, with full-size painted end bands (gutou) and a thin
    raised band beside each, the long middle set back slightly."""
    L, a, c, inset = 10.0, 0.35, 0.04, 0.014

    def sec(x, d):
        s = a - d
        return [(x, a - s + c, -s), (x, a + s - c, -s), (x, a + s, -s + c), (x, a + s, s - c),
                (x, a + s - c, s), (x, a - s + c, s), (x, a - s, s - c), (x, a - s, -s + c)]

    xs = [(-5.0, 0), (-4.6, 0), (-4.6, inset), (-4.52, inset), (-4.52, 0), (-4.44, 0), (-4.44, inset),
          (4.44, inset), (4.44, 0), (4.52, 0), (4.52, inset), (4.6, inset), (4.6, 0), (5.0, 0)]
    return loft([sec(x, d) for (x, d) in xs])


def make_MLO():
    """Single lintel (C1): the lintel of an upper entrance, carried by
    suspended pillars. A beam along x whose section is a rectangle with
    strongly rounded (bull-nosed) top edges and a flat bottom, a raised
    bead moulding, set off by a small groove, along its lower front and
    back edges."""
    hw, rn, rb = 0.44, 0.30, 0.05     # half width of the body, nose and bead radii
    segs_n = 4 * D
    half = []        # the +z half of the section, (z, y), bottom to top
    groups = []
    # bead: from its bottom round its outer side to the groove
    cb = (0.5 - rb, rb)
    angles = [-90 + 90 * s / (2 * D) for s in range(2 * D)] + [160 * s / (3 * D) for s in range(3 * D + 1)]
    for t in angles:
        half.append((cb[0] + rb * math.cos(math.radians(t)), cb[1] + rb * math.sin(math.radians(t))))
        groups.append("bead")
    groups[-1] = None                  # groove edge up to the body
    half.append((hw, 2.4 * rb))
    groups.append(None)                # flat side
    cn = (hw - rn, 1.0 - rn)
    for s in range(segs_n + 1):
        t = (math.pi / 2) * s / segs_n
        half.append((cn[0] + rn * math.cos(t), cn[1] + rn * math.sin(t)))
        groups.append("nose")
    groups[-1] = None                  # flat top to the mirror point
    # whole section, counter-clockwise in (z, y): +z half up, -z half down
    pts = half + [(-z, y) for (z, y) in reversed(half)]
    # labels: the +z half's edges (the last one is the flat top), then
    # edge i of the mirrored half, the mirror of the +z half's edge m-2-i
    # (m points in a half), then the flat bottom back to the start.
    eg = groups + [None if g is None else g + "_b" for g in list(reversed(groups))[1:]] + [None]
    prof = [(y, z) for (z, y) in pts]      # "yz" frame: u = y, v = z, extruded along x
    return extrude(prof, -5.0, 5.0, "yz", eg)


def make_MRO():
    """Ridge-end ornament (zhengwen / chiwen), the dragon-fish that
    swallows the end of the main ridge: a flat outline extruded in z, a wide
    base, the open jaw at the bottom toward +x gripping the ridge, the body
    rising with notched fins down its back (-x) and the tail curling over
    the top toward +x into a hook; a round eye boss on both faces."""
    T = 0.26
    pts, groups = [], []

    def put(p, g=None):
        pts.append(p)
        groups.append(g)

    # base and lower jaw
    put((0.0, 0.0))
    put((1.0, 0.0))
    put((1.0, 0.07))
    put((0.93, 0.10))
    put((0.89, 0.14))                   # a tooth
    put((0.85, 0.11))
    put((0.70, 0.13))
    # mouth corner, round
    c, r = (0.63, 0.20), 0.07
    for s in range(3 * D + 1):
        t = math.radians(-90 - 120 * s / (3 * D))
        put((c[0] + r * math.cos(t), c[1] + r * math.sin(t)), "mouth")
    # upper jaw: underside out to the lip, a fang, a snout curling up
    put((0.70, 0.31))
    put((0.84, 0.35))
    put((0.88, 0.30))                   # fang
    put((0.91, 0.37))
    put((1.0, 0.39))
    put((0.995, 0.46))
    put((0.93, 0.49))
    # forehead, brow, front of the body up to the curl
    put((0.88, 0.52))
    put((0.86, 0.62))
    put((0.89, 0.66))
    put((0.80, 0.70))
    put((0.68, 0.78))
    put((0.60, 0.86))
    # the tail's curl round C: hollow (clockwise), hook tip, outer edge
    C = (0.62, 1.0)
    ri0, ri1 = 0.09, 0.10
    ang0, ang1 = -110.0, -380.0
    k = 8 * D
    for s in range(k + 1):
        a = ang0 + (ang1 - ang0) * s / k
        rr = ri0 + (ri1 - ri0) * s / k
        put((C[0] + rr * math.cos(math.radians(a)), C[1] + rr * math.sin(math.radians(a))), "hollow")
    groups[-1] = "tip"
    put((C[0] + 0.135 * math.cos(math.radians(-42)), C[1] + 0.135 * math.sin(math.radians(-42))), "tip")

    def R(a):
        return 0.175 + (0.125 / 110.0) * (a + 20.0)

    a0, a1 = -20.0, 212.0
    k = 10 * D
    for s in range(k + 1):
        a = a0 + (a1 - a0) * s / k
        put((C[0] + R(a) * math.cos(math.radians(a)), C[1] + R(a) * math.sin(math.radians(a))), "curl")
    groups[-1] = None
    # the back, down to the base, with four notched fins
    top = pts[-1]
    x_at = lambda y: 0.03 + (top[0] - 0.03) * (y / top[1]) ** 1.3
    fins = 4
    y_hi, y_lo = top[1] - 0.06, 0.12
    step = (y_hi - y_lo) / fins
    for f in range(fins):
        y0 = y_hi - f * step
        put((x_at(y0), y0))
        put((x_at(y0) - 0.085, y0 + 0.015))
    put((x_at(y_lo), y_lo))
    put((0.0, 0.05))
    m = Mesh()
    m.merge(extrude(pts, -T / 2, T / 2, "xy", groups))
    # eye bosses
    for zs in (-1, 1):
        boss = lathe([(0.0, 0.0), (0.045, 0.0), (0.05, 0.008), (0.04, 0.019), (0.0, 0.024)], 8 * D,
                     [None, "eye", "eye", "eye"])
        if zs < 0:
            boss.transform(((1, 0, 0), (0, 0, 1), (0, -1, 0)))     # y -> -z
        else:
            boss.transform(((1, 0, 0), (0, 0, -1), (0, 1, 0)))     # y -> +z
        boss.translate((0.79, 0.56, zs * (T / 2 - 0.004)))
        m.merge(boss)
    return m


def tube(path, radii, n, label):
    """A round tube swept along a path in the y-z plane (x = 0), closed by
    flat caps; radii[k] is the radius at path point k."""
    rings = []
    for k, p in enumerate(path):
        q0 = path[max(k - 1, 0)]
        q1 = path[min(k + 1, len(path) - 1)]
        t = normalize(sub(q1, q0))
        nrm = cross(t, (1.0, 0.0, 0.0))
        r = radii[k]
        rings.append([add(p, add(mul((1.0, 0.0, 0.0), r * math.cos(2 * math.pi * i / n)),
                                 mul(nrm, r * math.sin(2 * math.pi * i / n)))) for i in range(n)])
    return loft(rings, [label] * (len(rings) - 1), around=True)


def make_MSA():
    """Stone animal (zoushou), one of the small beasts sitting in a row down
    a hip ridge: a beast seated on its haunches on a thin base plate (the
    ridge tile), front legs straight, head up with its snout toward -z
    (front), two ears, a short tail curling up at the back (+z). Separate
    shells sunk into each other."""
    m = Mesh()
    m.merge(loft([ring_rect(0.25, 0.45, 0.0, chamfer=0.02), ring_rect(0.25, 0.45, 0.05, chamfer=0.02)]))
    n = 8 * min(D, 2)
    # body: haunches on the plate, the chest rising forward to the neck
    rows = [(0.03, 0.12, 0.15, 0.20), (0.13, 0.10, 0.17, 0.23), (0.27, 0.05, 0.16, 0.20),
            (0.42, -0.03, 0.13, 0.15), (0.54, -0.09, 0.10, 0.11)]
    rings = [round_ring(0.0, y, cz, hx, hz, 2 * n) for (y, cz, hx, hz) in rows]
    m.merge(loft(rings, ["body"] * (len(rings) - 1), around=True))
    # thighs
    for sx in (-1, 1):
        m.merge(ellipsoid((sx * 0.14, 0.15, 0.13), 0.06, 0.11, 0.16, n, 2 + 2 * min(D, 2), "thigh"))
    # front legs with paws
    for sx in (-1, 1):
        leg = lathe([(0.0, 0.03), (0.05, 0.03), (0.05, 0.07), (0.038, 0.10), (0.035, 0.40), (0.0, 0.40)],
                    n, [None, "paw", "paw", "leg", None])
        leg.translate((sx * 0.075, 0.0, -0.16))
        m.merge(leg)
    # head, snout, ears
    m.merge(ellipsoid((0.0, 0.63, -0.12), 0.115, 0.105, 0.115, 2 * n, 2 + 2 * min(D, 2), "head"))
    rings = []
    for (z, yc, hx, hy) in ((-0.14, 0.60, 0.08, 0.065), (-0.28, 0.59, 0.07, 0.055), (-0.34, 0.585, 0.055, 0.04)):
        rings.append([(hx * x, yc + hy * y, z) for (x, y) in
                      ((-1, -0.7), (-0.7, -1), (0.7, -1), (1, -0.7), (1, 0.7), (0.7, 1), (-0.7, 1), (-1, 0.7))])
    m.merge(loft(rings, ["snout", "snout"], around=True))
    for sx in (-1, 1):
        ear = lathe([(0.0, 0.0), (0.035, 0.0), (0.0, 0.12)], n // 2 + 2, [None, "ear"])
        ear.translate((sx * 0.065, 0.68, -0.09))
        m.merge(ear)
    # tail: from the rump up and curling forward
    k = 2 + 2 * D
    path, radii = [], []
    for s in range(k + 1):
        u = s / k
        a = math.radians(-70 + 250 * u)
        rr = 0.12 * (1 - 0.45 * u)
        path.append((0.0, 0.32 + rr * math.sin(a) + 0.02, 0.30 + rr * math.cos(a)))
        radii.append(0.05 * (1 - 0.6 * u))
    m.merge(tube(path, radii, 8, "tail"))
    return m


# ---------------------------------------------------------------------------
# normalisation, normals and output


def normalise(m):
    """Centre and stretch every axis to exactly [-0.5, 0.5]; returns the
    natural size (extent per axis) before stretching."""
    lo, hi = m.bounds()
    ext = tuple(hi[i] - lo[i] for i in range(3))
    out = []
    for p in m.v:
        q = []
        for i in range(3):
            t = (p[i] - lo[i]) / ext[i] - 0.5
            if abs(t - 0.5) < 1e-12:
                t = 0.5
            elif abs(t + 0.5) < 1e-12:
                t = -0.5
            q.append(t)
        out.append(tuple(q))
    m.v = out
    return ext


CREASE_COS = math.cos(math.radians(65))


def normals(m):
    """Per-corner normals, computed on the final (normalised) geometry:
    flat faces get their own normal; a face in a smoothing group gets, at
    each corner, the area-weighted average of the faces of its group around
    that vertex that bend less than 65 degrees from it (so a strongly
    stretched model never gets a normal pointing away from its face)."""
    fn = []
    at = {}
    for k, (a, b, c, g) in enumerate(m.f):
        n = cross(sub(m.v[b], m.v[a]), sub(m.v[c], m.v[a]))  # length = 2 * area
        fn.append(n)
        if g is not None:
            for v in (a, b, c):
                at.setdefault((g, v), []).append(k)
    unit = [normalize(n) for n in fn]
    corner = []
    for k, (a, b, c, g) in enumerate(m.f):
        if g is None:
            corner.append((unit[k],) * 3)
            continue
        ns = []
        for v in (a, b, c):
            s = (0.0, 0.0, 0.0)
            for o in at[(g, v)]:
                if dot(unit[o], unit[k]) >= CREASE_COS:
                    s = add(s, fn[o])
            ns.append(normalize(s))
        corner.append(tuple(ns))
    return corner


def fmt(x):
    s = "%.6f" % x
    if s.startswith("-") and float(s) == 0.0:
        s = s[1:]
    s = s.rstrip("0").rstrip(".") if "." in s else s
    return s if s not in ("", "-") else "0"


def write_obj(path, name, m, natural, note):
    corner = normals(m)
    vn = []
    vn_id = {}
    faces = []
    for (a, b, c, g), ns in zip(m.f, corner):
        ids = []
        for n in ns:
            key = tuple(fmt(x) for x in n)
            if key not in vn_id:
                vn.append(key)
                vn_id[key] = len(vn)
            ids.append(vn_id[key])
        faces.append(((a + 1, ids[0]), (b + 1, ids[1]), (c + 1, ids[2])))
    lines = [
        "# %s - %s" % (name, note),
        "# lsys standard component, generated by scripts/make_components.py; do not edit",
        "# unit box [-0.5,0.5]^3: x width, y height (length of long parts), z depth, front -z",
        "# natural size before normalisation (x y z): %s %s %s" % tuple(fmt(e) for e in natural),
        "# %d vertices, %d triangles" % (len(m.v), len(m.f)),
        "o %s" % name,
    ]
    lines += ["v %s %s %s" % tuple(fmt(x) for x in p) for p in m.v]
    lines += ["vn %s %s %s" % n for n in vn]
    lines += ["f %d//%d %d//%d %d//%d" % (f[0] + f[1] + f[2]) for f in faces]
    with open(path, "w", newline="\n") as fh:
        fh.write("\n".join(lines) + "\n")


ARM_NOTE = "top toward %s" % ARM_TOP
MODELS = [
    ("MCa", make_MCa, "Toukung cap (ludou): tapered lower part, cross slot on top; y up"),
    ("MAO", make_MAO, "axial-oval arm (gong): length along y, rounded ends, 3 blocks on top; " + ARM_NOTE),
    ("MAL", make_MAL, "axial-long arm (man gong): length along y, 4 blocks on top; " + ARM_NOTE),
    ("MAn", make_MAn, "Ang: sloping, tapering lever along y with a beak at +y; " + ARM_NOTE),
    ("MNo", make_MNo, "nose (shuatou): short beam along y, pointed, lobed end at +y; " + ARM_NOTE),
    ("MP", make_MP, "pillar: 24-sided round shaft along y with a ring moulding near the top"),
    ("MPB", make_MPB, "pillar base: square plinth with a drum cushion; y up"),
    ("ML", make_ML, "lintel: beam spanning x, square chamfered section, stepped painted bands"),
    ("MFB", make_MFB, "flower board: thin panel in x-y, raised frame, three fields with rosettes; front -z"),
    ("MQ", make_MQ, "Queti: bracket plate in x-y, pillar side at -x, scalloped lower edge, scroll tip at +x"),
    ("MY", make_MY, "Yundan: cloud block, lobed outline in x-y, extruded in z"),
    ("MIB", make_MIB, "inscribed board: vertical plaque in x-y with a stepped raised border; front -z"),
    ("MBP", make_MBP, "booklet pillar: short chamfered square post with a cap; y up"),
    ("MPC", make_MPC, "pillar cap: cloud cap, collar, lotus disc, drum and jewel; y up"),
    ("MCH", make_MCH, "Chuihua: hanging lotus-bud pendant, square neck at the top (+y), bud at the bottom"),
    ("MCS", make_MCS, "capital stone: square stone slab with a low round mirror on top; y up"),
    ("MLS", make_MLS, "small lintel: slim beam spanning x, square chamfered section, end bands"),
    ("MLO", make_MLO, "single lintel: beam spanning x, rounded top edges, beaded lower edges"),
    ("MRO", make_MRO, "ridge-end ornament (chiwen): jaw toward +x at the bottom, tail curling at the top; extruded in z"),
    ("MSA", make_MSA, "stone animal: small seated beast facing -z on a base plate"),
]


def main(argv):
    """make_components.py [OUT] [--detail N]: the components with every
    curve's segments multiplied by N (default 3, the set lsys builds with;
    1 is the preview set in OUT/preview)."""
    global D
    args = list(argv[1:])
    if "--detail" in args:
        i = args.index("--detail")
        D = int(args[i + 1])
        del args[i:i + 2]
    else:
        D = 3
    here = os.path.dirname(os.path.abspath(__file__))
    out = args[0] if args else os.path.join(here, "..", "grammar", "std", "components")
    if not args and D == 1:
        out = os.path.join(out, "preview")
    out = os.path.normpath(out)
    os.makedirs(out, exist_ok=True)
    for name, make, note in MODELS:
        _uid[0] = 0
        m = make()
        natural = normalise(m)
        path = os.path.join(out, name + ".obj")
        write_obj(path, name, m, natural, note)
        print("%-4s %5d triangles  natural %s  -> %s" % (
            name, len(m.f), " x ".join(fmt(e) for e in natural), os.path.relpath(path)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
