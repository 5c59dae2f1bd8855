#!/usr/bin/env python3
"""How the NVIDIA H100 sets up and evaluates its attribute planes, from its committed probes.

Reads the random-triangle probes of `vt calibrate` (probe 11 = randomTriangles(1, 120) of
src/calibrate/raster_fit.cpp, 160 x 120, depth32f) from data/gpus/nvidia-h100/probes.tar.gz and
compares, on every pixel an unclipped triangle won, the H100's window z (the depth32f it stored)
and its texture coordinates s, t with

  (a) the exact planes through the unsnapped window positions (exact rationals from the float
      clip coordinates);
  (b) the exact planes through the window positions snapped to 1/16, 1/256 and 1/512 pixel;
  (c) float32 evaluations of the planes through the 1/256-snapped positions: origin (window,
      each vertex, the bounding box, tiles, the quad), plane equation or barycentric, with or
      without fused multiply-adds, and for s, t the perspective division done as a quotient or
      as a product with the reciprocal.

Errors are in ulps of the exact value (float32 spacing at |exact|) and, for the setups, also in
the unit of the precision model's attribute bound (2^-23 of the terms the plane evaluation sums:
reference/perturbed_triangle.h, ratioScale / depthTerms). Exact values use fractions; float32
arithmetic is numpy's (fma emulated in float64, exact for these magnitudes, then rounded once).

Usage: nice -n 10 /usr/bin/python3 scripts/h100-plane-analysis.py [--probes 11,12,13]
       [--tar data/gpus/nvidia-h100/probes.tar.gz]
"""
import argparse
import json
import math
import os
import sys
import tarfile
import tempfile
from fractions import Fraction as F

import numpy as np

f32 = np.float32
PIXEL = np.dtype([("tri", "<i4"), ("s", "<f4"), ("t", "<f4"), ("dsdx", "<f4"), ("dtdx", "<f4"),
                  ("dsdy", "<f4"), ("dtdy", "<f4"), ("depth", "<f4")])


# ----------------------------------------------------------------------------------------------
# Reading a probe


def read_probe(folder, index):
    stem = os.path.join(folder, "probe-%04d" % index)
    with open(stem + ".json") as f:
        request = json.load(f)
    if request["kind"] != "triangles":
        sys.exit("probe %d is not a triangle probe" % index)
    vertices = np.fromfile(stem + ".vertices.f32", "<f4").reshape(-1, 6)
    indices = np.fromfile(stem + ".indices.u32", "<u4")
    width, height = request["viewport"]
    result = np.fromfile(stem + ".result", PIXEL).reshape(height, width)  # bottom row first
    assert len(vertices) == request["vertex_count"] and len(indices) == request["index_count"]
    return vertices, indices, (width, height), result


# ----------------------------------------------------------------------------------------------
# Float32 helpers


def r32(x):
    """float64 (or exact) -> nearest float32, as numpy float32."""
    return f32(x)


def fma32(a, b, c):
    """fma in float32: a*b exact in float64 for float32 a, b; + c rounded in float64 then to
    float32 (double rounding only at exact float32 midpoints of a double, never seen here)."""
    a, b, c = (np.asarray(v, np.float64) for v in (a, b, c))
    return (a * b + c).astype(f32)


def ulp32(x):
    """float32 spacing at |x| (x float64 array), 2^-149 floor."""
    ax = np.abs(np.asarray(x, dtype=np.float64))
    e = np.floor(np.log2(np.where(ax > 0, ax, 1.0)))
    # log2 may land one off at exact powers of two: fix with frexp.
    m, ex = np.frexp(np.where(ax > 0, ax, 1.0))
    e = ex.astype(np.float64) - 1
    return np.where(ax > 0, np.exp2(np.maximum(e - 23, -149)), 2.0 ** -149)


def to_float(fr):
    return float(fr)


# ----------------------------------------------------------------------------------------------
# Window positions


def snap_fraction(x, bits):
    """x (Fraction) rounded half to even to the grid 2^-bits, as a Fraction."""
    scaled = x * (1 << bits)
    n = scaled.numerator // scaled.denominator
    rem = scaled - n
    if rem > F(1, 2) or (rem == F(1, 2) and n % 2 == 1):
        n += 1
    return F(n, 1 << bits)


class Vertex:
    """One vertex of a triangle: clip coordinates, attributes, window position and values."""

    def __init__(self, row, viewport):
        x, y, z, w, s, t = (float(v) for v in row)
        self.clip = (x, y, z, w)
        self.s, self.t = F(s), F(t)
        hw, hh = F(viewport[0], 2), F(viewport[1], 2)
        fw = F(w)
        # Exact window position and values.
        self.X = (F(x) / fw + 1) * hw
        self.Y = (F(y) / fw + 1) * hh
        self.Z = F(z) / fw / 2 + F(1, 2)
        self.q = 1 / fw
        # The float pipeline the oracle's fused viewport models: oow = 1/w, ndc = x * oow,
        # window = fma(ndc, half, half).
        oow = f32(1) / f32(w)
        self.oow32 = oow
        self.X32 = fma32(f32(x) * oow, f32(viewport[0] / 2), f32(viewport[0] / 2))
        self.Y32 = fma32(f32(y) * oow, f32(viewport[1] / 2), f32(viewport[1] / 2))
        self.Z32 = fma32(f32(z) * oow, f32(0.5), f32(0.5))
        self.sq32 = f32(s) * oow
        self.tq32 = f32(t) * oow


def inside(clip):
    x, y, z, w = clip
    return w > 0 and -w <= x <= w and -w <= y <= w and -w <= z <= w


# ----------------------------------------------------------------------------------------------
# Exact planes: value(cx, cy) = A cx + B cy + C through three points


def exact_plane(P, values):
    (x0, y0), (x1, y1), (x2, y2) = P
    v0, v1, v2 = values
    d = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
    if d == 0:
        return None
    A = ((v1 - v0) * (y2 - y0) - (v2 - v0) * (y1 - y0)) / d
    B = ((v2 - v0) * (x1 - x0) - (v1 - v0) * (x2 - x0)) / d
    C = v0 - A * x0 - B * y0
    return (A, B, C)


def at(plane, cx, cy):
    A, B, C = plane
    return A * cx + B * cy + C


# ----------------------------------------------------------------------------------------------
# Statistics


def summary(err, matched=None):
    """err: float64 array of signed errors in some unit; matched: how many values are bit for
    bit what the candidate gives (for exact references: the float32 nearest the exact value)."""
    a = np.abs(err)
    if len(a) == 0:
        return dict(n=0)
    return dict(n=len(a), exact=int(matched if matched is not None else np.sum(a == 0)), p50=float(np.percentile(a, 50)),
                p90=float(np.percentile(a, 90)), p99=float(np.percentile(a, 99)),
                max=float(a.max()), mean_signed=float(np.mean(err)))


def row(name, s, unit="ulps"):
    if s["n"] == 0:
        return "| %s | 0 | | | | | | |" % name
    return "| %s | %d | %d | %.3g | %.3g | %.3g | %.4g | %+.3f |" % (
        name, s["n"], s["exact"], s["p50"], s["p90"], s["p99"], s["max"], s["mean_signed"])


HEADER = ("| candidate | values | bit for bit | p50 | p90 | p99 | max | mean (signed) |\n"
          "|---|---|---|---|---|---|---|---|")


# ----------------------------------------------------------------------------------------------
# The pixels: every pixel an unclipped triangle won


class Triangle:
    def __init__(self, probe, k, verts):
        self.probe, self.k, self.v = probe, k, verts
        self.pixels = []  # (px, py, depth, s, t) of the H100


def collect(folder, probes):
    triangles, skipped = [], 0
    for p in probes:
        vertices, indices, viewport, result = read_probe(folder, p)
        count = len(indices) // 3
        by_k = {}
        for k in range(count):
            vs = [Vertex(vertices[indices[3 * k + i]], viewport) for i in range(3)]
            if all(inside(v.clip) for v in vs):
                by_k[k] = Triangle(p, k, vs)
        height, width = result.shape
        for py in range(height):
            for px in range(width):
                r = result[py, px]
                k = int(r["tri"])
                if k < 0:
                    continue
                if k in by_k:
                    by_k[k].pixels.append((px, py, r["depth"], r["s"], r["t"]))
                else:
                    skipped += 1
        triangles += [t for t in by_k.values() if t.pixels]
    return triangles, skipped


# ----------------------------------------------------------------------------------------------
# (a), (b): exact planes through chosen positions and vertex values


def positions(tri, how):
    """The three window positions (Fractions) a setup uses."""
    if how == "exact":
        return [(v.X, v.Y) for v in tri.v]
    if how == "float":
        return [(F(float(v.X32)), F(float(v.Y32))) for v in tri.v]
    bits = int(how.split("/")[1]).bit_length() - 1  # "snap/256" -> 8
    return [(snap_fraction(F(float(v.X32)), bits), snap_fraction(F(float(v.Y32)), bits))
            for v in tri.v]


def vertex_values(tri, how):
    """z, q = 1/w, s q, t q at the vertices: exact, or as the float pipeline computes them."""
    if how == "exact":
        return ([v.Z for v in tri.v], [v.q for v in tri.v], [v.s * v.q for v in tri.v],
                [v.t * v.q for v in tri.v])
    return ([F(float(v.Z32)) for v in tri.v], [F(float(v.oow32)) for v in tri.v],
            [F(float(v.sq32)) for v in tri.v], [F(float(v.tq32)) for v in tri.v])


def plane_terms(plane, corners, cx, cy):
    """T(plane) of reference/perturbed_triangle.cpp: the largest of |a(o)| + |ax (cx - ox)| +
    |ay (cy - oy)| over the window origin and the corners (float64)."""
    A, B, C = (float(c) for c in plane)
    best = abs(C) + abs(A * cx) + abs(B * cy)
    for (ox, oy) in corners:
        ox, oy = float(ox), float(oy)
        best = max(best, abs(A * ox + B * oy + C) + abs(A * (cx - ox)) + abs(B * (cy - oy)))
    return best


def exact_values(triangles, where, values="exact"):
    """Per pixel: exact z, s, t (float64 of the exact rationals) for planes through `where`,
    and the model's term sizes for z and for s, t (ratioScale)."""
    out = {k: [] for k in ("z", "s", "t", "zterms", "sterms", "tterms")}
    for tri in triangles:
        P = positions(tri, where)
        Z, Q, SQ, TQ = vertex_values(tri, values)
        pz, pq, ps, pt = (exact_plane(P, vals) for vals in (Z, Q, SQ, TQ))
        for (px, py, _, _, _) in tri.pixels:
            cx, cy = F(2 * px + 1, 2), F(2 * py + 1, 2)
            q = at(pq, cx, cy)
            z = at(pz, cx, cy)
            s = at(ps, cx, cy) / q
            t = at(pt, cx, cy) / q
            out["z"].append(float(z))
            out["s"].append(float(s))
            out["t"].append(float(t))
            fx, fy = float(cx), float(cy)
            tq = plane_terms(pq, P, fx, fy)
            out["zterms"].append(max(1.0, plane_terms(pz, P, fx, fy)))
            for name, pl, val in (("sterms", ps, s), ("tterms", pt, t)):
                out[name].append((plane_terms(pl, P, fx, fy) + abs(float(val)) * tq) / abs(float(q)))
    return {k: np.array(v) for k, v in out.items()}


def measured(triangles):
    d = np.array([p[2] for t in triangles for p in t.pixels], dtype=np.float64)
    s = np.array([p[3] for t in triangles for p in t.pixels], dtype=np.float64)
    t = np.array([p[4] for t in triangles for p in t.pixels], dtype=np.float64)
    return d, s, t


def ulp_errors(h, exact):
    return (h - exact) / ulp32(exact)


# ----------------------------------------------------------------------------------------------
# (c) float32 evaluations of the planes through the 1/256-snapped positions


def div32(a, b):
    return (np.asarray(a, f32) / np.asarray(b, f32)).astype(f32)


def evaluate_plane(a, b, c, dx, dy, order):
    """One float32 evaluation of c + a dx + b dy (arrays of float32)."""
    if order == "(c+a*dx)+b*dy":
        return ((c + a * dx) + b * dy).astype(f32)
    if order == "(c+b*dy)+a*dx":
        return ((c + b * dy) + a * dx).astype(f32)
    if order == "c+(a*dx+b*dy)":
        return (c + (a * dx + b * dy)).astype(f32)
    if order == "fma(b,dy,fma(a,dx,c))":
        return fma32(b, dy, fma32(a, dx, c))
    if order == "fma(a,dx,fma(b,dy,c))":
        return fma32(a, dx, fma32(b, dy, c))
    if order == "c+fma(a,dx,b*dy)":
        return (c + fma32(a, dx, (b * dy).astype(f32))).astype(f32)
    if order == "rounded-once":  # the rounded coefficients, summed exactly, rounded once
        c, a, dx, b, dy = (np.asarray(v, np.float64) for v in (c, a, dx, b, dy))
        return (c + a * dx + b * dy).astype(f32)
    raise ValueError(order)


ORDERS = ["(c+a*dx)+b*dy", "(c+b*dy)+a*dx", "c+(a*dx+b*dy)", "fma(b,dy,fma(a,dx,c))",
          "fma(a,dx,fma(b,dy,c))", "c+fma(a,dx,b*dy)", "rounded-once"]
ORIGINS = ["window(0,0)", "centre(0,0)", "v0", "v1", "v2", "lowest-y", "bbox", "bbox-pixel",
           "tile8", "tile16", "tile32", "quad"]


def origin_of(name, P, px, py):
    """Origin (Fractions) of the evaluation for pixel (px, py) of a triangle at snapped P."""
    if name == "window(0,0)":
        return F(0), F(0)
    if name == "centre(0,0)":
        return F(1, 2), F(1, 2)
    if name in ("v0", "v1", "v2"):
        return P[int(name[1])]
    if name == "lowest-y":
        return min(P, key=lambda p: (p[1], p[0]))
    if name == "bbox":
        return min(p[0] for p in P), min(p[1] for p in P)
    if name == "bbox-pixel":
        return F(math.floor(min(p[0] for p in P))), F(math.floor(min(p[1] for p in P)))
    if name.startswith("tile"):
        n = int(name[4:])
        return F(px // n * n), F(py // n * n)
    if name == "quad":
        return F(px & ~1), F(py & ~1)
    raise ValueError(name)


class Planes:
    """Per triangle: the exact planes (z, q, s q, t q) through the snapped positions."""

    def __init__(self, tri, values):
        self.P = positions(tri, "snap/256")
        self.vals = vertex_values(tri, values)
        self.planes = [exact_plane(self.P, v) for v in self.vals]


def plane_candidates(triangles, values):
    """{(origin, order): (z, S, Q, T) float32 arrays over every pixel}."""
    out = {}
    per = [Planes(t, values) for t in triangles]
    for origin in ORIGINS:
        cols = {o: [[], [], [], []] for o in ORDERS}
        for tri, pl in zip(triangles, per):
            pix = tri.pixels
            O = [origin_of(origin, pl.P, px, py) for (px, py, _, _, _) in pix]
            dx = np.array([float(F(2 * px + 1, 2) - o[0]) for (px, py, *_), o in zip(pix, O)], f32)
            dy = np.array([float(F(2 * py + 1, 2) - o[1]) for (px, py, *_), o in zip(pix, O)], f32)
            for i, plane in enumerate(pl.planes):
                A, B, C = plane
                a = np.full(len(pix), f32(float(A)), f32)
                b = np.full(len(pix), f32(float(B)), f32)
                c = np.array([f32(float(at(plane, o[0], o[1]))) for o in O], f32)
                for order in ORDERS:
                    cols[order][i].append(evaluate_plane(a, b, c, dx, dy, order))
        for order in ORDERS:
            out[(origin, order)] = tuple(np.concatenate(c) for c in cols[order])
    return out


def barycentric_candidates(triangles, values):
    """Edge functions exact on the 1/256 grid, lambda = E / area in float32, then the vertex
    values combined: v0 + l1 (v1 - v0) + l2 (v2 - v0), unfused or fused, or l0 v0 + l1 v1 +
    l2 v2 with l0 = 1 - l1 - l2. Returns {name: (z, S, Q, T)} and perspective-corrected s, t."""
    names = ["bary v0+l1*d1+l2*d2", "bary fma", "bary l0v0+l1v1+l2v2", "bary ideal l, fma"]
    cols = {n: [[], [], [], []] for n in names}
    persp = {n: [[], []] for n in ("bary-persp l*q/Q", "bary-persp fma")}
    for tri in triangles:
        P = positions(tri, "snap/256")
        (x0, y0), (x1, y1), (x2, y2) = [(int(p[0] * 256), int(p[1] * 256)) for p in P]
        area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        E1, E2 = [], []
        for (px, py, *_) in tri.pixels:
            cx, cy = (2 * px + 1) * 128, (2 * py + 1) * 128
            E1.append((cx - x0) * (y2 - y0) - (x2 - x0) * (cy - y0))
            E2.append((x1 - x0) * (cy - y0) - (cx - x0) * (y1 - y0))
        l1 = np.array([float(F(e, area)) for e in E1]).astype(f32)
        l2 = np.array([float(F(e, area)) for e in E2]).astype(f32)
        r = f32(1) / f32(area)
        l1u = (np.array(E1, np.float64).astype(f32) * r).astype(f32)
        l2u = (np.array(E2, np.float64).astype(f32) * r).astype(f32)
        l0 = ((f32(1) - l1) - l2).astype(f32)
        vals = vertex_values(tri, values)
        for i, v in enumerate(vals):
            v0, v1, v2 = (f32(float(x)) for x in v)
            d1, d2 = f32(v1 - v0), f32(v2 - v0)
            cols[names[0]][i].append(((v0 + l1u * d1) + l2u * d2).astype(f32))
            cols[names[1]][i].append(fma32(l2u, d2, fma32(l1u, d1, v0)))
            cols[names[2]][i].append(((l0 * v0 + l1 * v1) + l2 * v2).astype(f32))
            cols[names[3]][i].append(fma32(l2, d2, fma32(l1, d1, v0)))
        # Perspective-corrected barycentrics: m_i = l_i q_i / Q, s = s0 + m1 (s1-s0) + m2 (s2-s0).
        q0, q1, q2 = (f32(float(x)) for x in vals[1])
        Q = fma32(l2, f32(q2 - q0), fma32(l1, f32(q1 - q0), q0))
        m1 = ((l1 * q1).astype(f32) / Q).astype(f32)
        m2 = ((l2 * q2).astype(f32) / Q).astype(f32)
        for j, attr in enumerate(("s", "t")):
            a0, a1, a2 = (f32(float(getattr(v, attr))) for v in tri.v)
            persp["bary-persp l*q/Q"][j].append(((a0 + m1 * f32(a1 - a0)) + m2 * f32(a2 - a0))
                                                .astype(f32))
            persp["bary-persp fma"][j].append(fma32(m2, f32(a2 - a0), fma32(m1, f32(a1 - a0), a0)))
    out = {n: tuple(np.concatenate(c) for c in cols[n]) for n in names}
    outp = {n: tuple(np.concatenate(c) for c in persp[n]) for n in persp}
    return out, outp


def perspective(S, Q, T, how):
    if how == "S/Q":
        return div32(S, Q), div32(T, Q)
    r = div32(np.ones_like(Q), Q)
    return (S * r).astype(f32), (T * r).astype(f32)


# ----------------------------------------------------------------------------------------------
# (d) The depth plane evaluated (nearly) exactly: a linear-programming check per triangle, and
#     float32 setups of the coefficients with the evaluation exact and rounded once


def minimax_extra(triangles, field=2, least=6):
    """Per triangle of at least `least` pixels: the least e >= 0 such that some plane P has
    |H - P| <= ulp(H)/2 + e at every pixel (an LP); e in units of 2^-24. e = 0 means the values
    are exactly some plane rounded to nearest once."""
    from scipy.optimize import linprog
    out = []
    for T in triangles:
        if len(T.pixels) < least:
            continue
        x = np.array([p[0] + 0.5 for p in T.pixels])
        y = np.array([p[1] + 0.5 for p in T.pixels])
        H = np.array([float(p[field]) for p in T.pixels])
        U = 2.0 ** -24
        X, Y, R = x - x.mean(), y - y.mean(), (H - H.mean()) / U
        half = 0.5 * ulp32(H) / U
        one = np.ones_like(X)
        A = np.vstack([np.stack([one, X, Y, -one], 1), np.stack([-one, -X, -Y, -one], 1)])
        r = linprog([0, 0, 0, 1], A_ub=A, b_ub=np.concatenate([R + half, -R + half]),
                    bounds=[(None, None)] * 3 + [(0, None)], method="highs")
        out.append((r.x[3] if r.success else float("inf"), len(H), T.probe, T.k))
    return out


SETUPS = ["scaled-first (oracle planeOf)", "products, difference, times 1/area",
          "fma numerator, times 1/area", "products, difference, / area",
          "exact numerator, times 1/area", "exact coefficients"]


def float_setup(P, vals, how):
    """dadx, dady of the plane through float32 values at snapped positions P (v0 first),
    computed in float32 as `how` says. Positions and their differences are exact in float32."""
    (x0, y0), (x1, y1), (x2, y2) = [(f32(float(p[0])), f32(float(p[1]))) for p in P]
    a0, a1, a2 = (f32(float(v)) for v in vals)
    dx01, dy01, dx20, dy20 = f32(x0 - x1), f32(y0 - y1), f32(x2 - x0), f32(y2 - y0)
    da01, da20 = f32(a0 - a1), f32(a2 - a0)
    area = f32(f32(dx01 * dy20) - f32(dy01 * dx20))
    ooa = f32(f32(1) / area)
    if how == SETUPS[0]:
        sdx01, sdy01, sdx20, sdy20 = f32(dx01 * ooa), f32(dy01 * ooa), f32(dx20 * ooa), f32(dy20 * ooa)
        return f32(f32(da01 * sdy20) - f32(da20 * sdy01)), f32(f32(da20 * sdx01) - f32(da01 * sdx20))
    if how == SETUPS[1]:
        return (f32(f32(f32(da01 * dy20) - f32(da20 * dy01)) * ooa),
                f32(f32(f32(da20 * dx01) - f32(da01 * dx20)) * ooa))
    if how == SETUPS[2]:
        nx = fma32(da01, dy20, -f32(da20 * dy01))
        ny = fma32(da20, dx01, -f32(da01 * dx20))
        return f32(nx * ooa), f32(ny * ooa)
    if how == SETUPS[3]:
        return (f32(f32(f32(da01 * dy20) - f32(da20 * dy01)) / area),
                f32(f32(f32(da20 * dx01) - f32(da01 * dx20)) / area))
    # exact numerators (and area) from the float32 values, then one rounding
    fx = [F(float(v)) for v in (x0, y0, x1, y1, x2, y2)]
    X0, Y0, X1, Y1, X2, Y2 = fx
    A0, A1, A2 = (F(float(v)) for v in (a0, a1, a2))
    ar = (X0 - X1) * (Y2 - Y0) - (Y0 - Y1) * (X2 - X0)
    nx = (A0 - A1) * (Y2 - Y0) - (A2 - A0) * (Y0 - Y1)
    ny = (A2 - A0) * (X0 - X1) - (A0 - A1) * (X2 - X0)
    if how == SETUPS[4]:
        return f32(f32(float(nx)) * ooa), f32(f32(float(ny)) * ooa)
    return f32(float(nx / ar)), f32(float(ny / ar))


def depth_setup_candidates(triangles, values):
    """{(setup, anchor): z float32} with z = round32(z_anchor + dadx (cx - x_anchor) + dady (cy -
    y_anchor)) evaluated exactly (float64, exact here), the setup from vertex `first`."""
    out = {}
    for how in SETUPS:
        for first in ("v0", "v1", "v2", "oriented v0"):
            col = []
            for tri in triangles:
                P = positions(tri, "snap/256")
                Z = vertex_values(tri, values)[0]
                order = [0, 1, 2]
                if first in ("v1", "v2"):
                    i = int(first[1])
                    order = [i, (i + 1) % 3, (i + 2) % 3]
                elif first == "oriented v0":
                    (x0, y0), (x1, y1), (x2, y2) = P
                    if (x0 - x1) * (y2 - y0) - (x2 - x0) * (y0 - y1) < 0:
                        order = [1, 0, 2]
                Po, Zo = [P[i] for i in order], [Z[i] for i in order]
                a, b = float_setup(Po, Zo, how)
                x0, y0, z0 = float(Po[0][0]), float(Po[0][1]), float(f32(float(Zo[0])))
                for (px, py, *_) in tri.pixels:
                    v = z0 + float(a) * (px + 0.5 - x0) + float(b) * (py + 0.5 - y0)
                    col.append(f32(v))
            out[(how, first)] = np.array(col, f32)
    return out


VERTEX_Z = ["exact", "fma(z*oow,.5,.5)", "z*oow*.5+.5", "(z/w)*.5+.5", "fma(z/w,.5,.5)",
            "(z*.5+w*.5)*oow", "(z+w)*.5/w", "fma(z,.5*oow,.5)"]


def vertex_z(v, how):
    """A vertex's window z as float32 pipelines compute it (oow = 1/w correctly rounded)."""
    x, y, z, w = (f32(c) for c in v.clip)
    oow = f32(1) / w
    h = f32(0.5)
    if how == "exact":
        return float(v.Z)
    if how == "fma(z*oow,.5,.5)":
        return float(v.Z32)
    if how == "z*oow*.5+.5":
        return float(f32(f32(f32(z * oow) * h) + h))
    if how == "(z/w)*.5+.5":
        return float(f32(f32(f32(z / w) * h) + h))
    if how == "fma(z/w,.5,.5)":
        return float(f32(np.float64(f32(z / w)) * 0.5 + 0.5))
    if how == "(z*.5+w*.5)*oow":
        return float(f32(f32(f32(z * h) + f32(w * h)) * oow))
    if how == "(z+w)*.5/w":
        return float(f32(f32(f32(z + w) * h) / w))
    return float(f32(np.float64(z) * np.float64(f32(h * oow)) + 0.5))  # fma(z, .5*oow, .5)


def depth_vertex_intervals(triangles, least=30):
    """For triangles of at least `least` pixels: the interval of values at each snapped vertex
    that planes P with |H - P| <= ulp(H)/2 + e (e the triangle's least, + 0.001 2^-24) take;
    returns (offsets of their middles from the exact z in 2^-24, widths in ulps of z, how many
    vertices each VERTEX_Z candidate lands inside)."""
    from scipy.optimize import linprog
    U = 2.0 ** -24
    mids, widths, inside = [], [], {k: 0 for k in VERTEX_Z}
    for T in triangles:
        if len(T.pixels) < least:
            continue
        P = positions(T, "snap/256")
        x = np.array([p[0] + 0.5 for p in T.pixels])
        y = np.array([p[1] + 0.5 for p in T.pixels])
        H = np.array([float(p[2]) for p in T.pixels])
        half = 0.5 * ulp32(H) / U
        xm, ym, Hm = x.mean(), y.mean(), H.mean()
        X, Y, R = x - xm, y - ym, (H - Hm) / U
        one = np.ones_like(X)
        A = np.vstack([np.stack([one, X, Y], 1), -np.stack([one, X, Y], 1)])
        r = linprog([0, 0, 0, 1], A_ub=np.hstack([A, -np.ones((2 * len(X), 1))]),
                    b_ub=np.concatenate([R + half, -R + half]),
                    bounds=[(None, None)] * 3 + [(0, None)], method="highs")
        e = r.x[3] + 1e-3
        b = np.concatenate([R + half + e, -R + half + e])
        for i, (vx, vy) in enumerate(P):
            g = np.array([1.0, float(vx) - xm, float(vy) - ym])
            lo = linprog(g, A_ub=A, b_ub=b, bounds=[(None, None)] * 3, method="highs").fun
            hi = -linprog(-g, A_ub=A, b_ub=b, bounds=[(None, None)] * 3, method="highs").fun
            lo, hi = lo * U + Hm, hi * U + Hm
            mids.append(((lo + hi) / 2 - float(T.v[i].Z)) / U)
            widths.append((hi - lo) / float(ulp32(np.array([float(T.v[i].Z)]))[0]))
            for k in VERTEX_Z:
                if lo - 1e-12 <= vertex_z(T.v[i], k) <= hi + 1e-12:
                    inside[k] += 1
    return np.array(mids), np.array(widths), inside


# ----------------------------------------------------------------------------------------------
# Report


def compare(name, H, cand, exact):
    """Row for a candidate's float32 values against the H100's: bit-for-bit count, and the
    H100's error against the candidate in ulps of the exact value."""
    cand = np.asarray(cand, np.float64)
    matched = int(np.sum(H == cand))
    return row(name, summary((H - cand) / ulp32(exact), matched))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--tar", default=os.path.join(os.path.dirname(__file__), "..", "data", "gpus",
                                                  "nvidia-h100", "probes.tar.gz"))
    ap.add_argument("--probes", default="11", help="comma-separated triangle probes (11,12,13)")
    ap.add_argument("--top", type=int, default=12, help="candidate rows shown per quantity")
    args = ap.parse_args()
    probes = [int(p) for p in args.probes.split(",")]
    with tempfile.TemporaryDirectory() as tmp:
        with tarfile.open(args.tar) as tar:
            tar.extractall(tmp, filter="data") if hasattr(tarfile, "data_filter") else \
                tar.extractall(tmp)
        folder = os.path.join(tmp, "probes")
        triangles, skipped = collect(folder, probes)
    d, s, t = measured(triangles)
    n = len(d)
    print("# H100 attribute planes: probes %s" % ",".join(map(str, probes)))
    print()
    print("%d unclipped triangles won %d pixels (%d pixels of clipped triangles left out)."
          % (len(triangles), n, skipped))

    # Window positions: does snapping the float window position differ from snapping the exact?
    differ = sum(1 for tri in triangles for v in tri.v
                 for xe, x32 in ((v.X, v.X32), (v.Y, v.Y32))
                 if snap_fraction(xe, 8) != snap_fraction(F(float(x32)), 8))
    print("Snapped to 1/256 from the exact window position or from fma(x * (1/w), half, half) in "
          "float32: %d of %d coordinates differ." % (differ, 6 * len(triangles)))
    print()

    print("## (a), (b) Exact planes through the positions, H100 error in ulps of the exact value")
    print()
    print("`bit for bit`: the H100's value is the float32 nearest the exact one. Vertex values "
          "exact (z/w/2 + 1/2, 1/w, s/w, t/w as rationals) or as float32 computes them "
          "(fma(z * (1/w), 0.5, 0.5), 1/w, s * (1/w)).")
    print()
    print(HEADER)
    exact_ref = {}
    for where in ("exact", "float", "snap/16", "snap/256", "snap/512"):
        for vals in ("exact", "float"):
            e = exact_values(triangles, where, vals)
            exact_ref[(where, vals)] = e
            label = "unsnapped exact" if where == "exact" else \
                "unsnapped float32" if where == "float" else where
            for q, H in (("z", d), ("s", s), ("t", t)):
                m = int(np.sum(H == e[q].astype(f32)))
                print(row("%s: %s, values %s" % (q, label, vals),
                          summary(ulp_errors(H, e[q]), m)))
    print()
    print("The same in the model's units (2^-23 of the terms the evaluation sums, "
          "reference/perturbed_triangle.h: depth at least the range, s and t ratioScale):")
    print()
    print(HEADER)
    for key, e in exact_ref.items():
        label = "%s, values %s" % key
        print(row("z: " + label, summary((d - e["z"]) / (e["zterms"] * 2.0 ** -23))))
        st = np.concatenate([(s - e["s"]) / (e["sterms"] * 2.0 ** -23),
                             (t - e["t"]) / (e["tterms"] * 2.0 ** -23)])
        print(row("s, t: " + label, summary(st)))
    print()

    for vals in ("exact", "float"):
        ref = exact_ref[("snap/256", vals)]
        print("## (c) Float32 evaluations, 1/256-snapped setup, vertex values %s" % vals)
        print()
        print("Coefficients a, b: the exact plane's rounded to float32; c: the exact value at "
              "the origin rounded to float32; dx, dy: pixel centre minus origin (exact). Errors: "
              "the H100's value minus the candidate's, in ulps of the exact value.")
        print()
        cands = plane_candidates(triangles, vals)
        bary, bary_p = barycentric_candidates(triangles, vals)
        zrows, strows = [], []
        for key, (z, Q, S, T) in list(cands.items()) + [((k, ""), v) for k, v in bary.items()]:
            name = "%s, %s" % key if key[1] else key[0]
            zrows.append((int(np.sum(d == z)), float(np.max(np.abs(d - z) / ulp32(ref["z"]))),
                          compare(name, d, z, ref["z"])))
            for how in ("S/Q", "S*(1/Q)"):
                sc, tc = perspective(S, Q, T, how)
                H = np.concatenate([s, t])
                C = np.concatenate([sc, tc])
                E = np.concatenate([ref["s"], ref["t"]])
                strows.append((int(np.sum(H == C)), float(np.max(np.abs(H - C) / ulp32(E))),
                               compare(name + ", " + how, H, C, E)))
        for name, (sc, tc) in bary_p.items():
            H, C = np.concatenate([s, t]), np.concatenate([sc, tc])
            E = np.concatenate([ref["s"], ref["t"]])
            strows.append((int(np.sum(H == C)), float(np.max(np.abs(H - C) / ulp32(E))),
                           compare(name, H, C, E)))
        for label, rows in (("depth z", zrows), ("s and t together", strows)):
            print("### %s: the %d candidates with most values bit for bit (of %d)"
                  % (label, args.top, len(rows)))
            print()
            print(HEADER)
            for r in sorted(rows, key=lambda r: (-r[0], r[1]))[:args.top]:
                print(r[2])
            print()
            print("### %s: the %d candidates with the smallest largest error" % (label, args.top))
            print()
            print(HEADER)
            for r in sorted(rows, key=lambda r: (r[1], -r[0]))[:args.top]:
                print(r[2])
            print()

    print("## (d) Depth: which plane, evaluated how")
    print()
    ex = minimax_extra(triangles)
    extra = np.array([o[0] for o in ex])
    print("Per triangle of at least 6 pixels (%d triangles), the least e such that one plane P "
          "gives |H - P| <= ulp(H)/2 + e at every pixel (linear programming): e = 0 (the "
          "values are some plane rounded to nearest once) for %d; largest e %.3f x 2^-24 "
          "(probe %d, triangle %d)." % (len(ex), int(np.sum(extra < 1e-6)), extra.max(),
                                        *max(ex)[2:]))
    print()
    mids, widths, inside = depth_vertex_intervals(triangles)
    print("Triangles of at least 30 pixels, %d vertices: the planes those allow take, at each "
          "snapped vertex, an interval of median width %.3f ulps of z; its middle lies from "
          "the exact z/w/2 + 1/2 by median |.| %.3f, 90th percentile %.3f, largest %.3f, mean "
          "%+.3f (units of 2^-24). Vertex z as float32 pipelines compute it, inside the "
          "interval:" % (len(mids), float(np.median(widths)), float(np.median(np.abs(mids))),
                         float(np.percentile(np.abs(mids), 90)), float(np.abs(mids).max()),
                         float(mids.mean())))
    print()
    print("| vertex z | vertices inside |")
    print("|---|---|")
    for k, v in inside.items():
        print("| `%s` | %d of %d |" % (k, v, len(mids)))
    print()
    for vals in ("exact", "float"):
        ref = exact_values(triangles, "snap/256", vals)
        c = depth_setup_candidates(triangles, vals)
        print("Float32 setups (vertex values %s), the plane through the first vertex's z, "
              "evaluated exactly and rounded once (correctly rounded exact plane: %d of %d bit "
              "for bit):" % (vals, int(np.sum(d == ref["z"].astype(f32))), n))
        print()
        print(HEADER)
        rows = sorted(((int(np.sum(d == z)), "%s, from %s" % k, z) for k, z in c.items()),
                      key=lambda r: -r[0])
        for m, name, z in rows[:args.top]:
            print(compare(name, d, z, ref["z"]))
        print()


if __name__ == "__main__":
    main()
