#!/usr/bin/env python3
"""The viewer's voxel view held to a ray cast of the same voxels (tests/run.sh, example_viewer).

    viewer_voxels.py SHOT.ppm PREFIX OX OY OZ VOXEL_SIZE EX EY EZ TX TY TZ FOVY

SHOT.ppm is the viewer's screenshot of `--method voxels` (instanced cubes, rasterised on GL);
PREFIX.npy and PREFIX.albedo.npy are the voxels it drew (--voxels-npy), on the grid the viewer
printed. Here every pixel's centre casts voxgi's camera ray (gluLookAt up +Y, the pixel's centre
at (2 (x + 0.5) / w - 1, 1 - 2 (y + 0.5) / h) times tan(fovy / 2), the width scaled by w / h)
through the grid voxel by voxel (Amanatides and Woo), and the first set voxel's face it enters
takes the viewer's colour: albedo times the face's shade, through the sRGB transfer, rounded to
a byte. Prints the measures; exit 1 when more than 0.5% of the pixels differ by more than one
level in a channel (the pixels whose centre lies on a cube's edge may go either way), or when the
view shows no voxel.
"""
import math
import sys

import numpy as np

SHADE = np.array([0.8, 0.8, 1.0, 0.5, 0.65, 0.65])  # +x -x +y -y +z -z, as examples/viewer.c


def read_ppm(path):
    with open(path, "rb") as f:
        data = f.read()
    parts = data.split(maxsplit=4)
    if parts[0] != b"P6" or parts[3] != b"255":
        raise SystemExit(f"{path}: not an 8-bit P6 PPM")
    w, h = int(parts[1]), int(parts[2])
    return np.frombuffer(parts[4][: w * h * 3], dtype=np.uint8).reshape(h, w, 3)


def srgb8(c):
    c = np.clip(c, 0.0, 1.0)
    s = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)
    return np.floor(s * 255 + 0.5).astype(np.int32)


def cast(occ, albedo, origin, size, eye, target, fovy, w, h):
    res = np.array(occ.shape)
    f = np.array(target) - np.array(eye)
    f /= np.linalg.norm(f)
    right = np.array([-f[2], 0.0, f[0]])
    right /= np.linalg.norm(right)
    up = np.cross(right, f)
    t = math.tan(math.radians(fovy) / 2)
    ys, xs = np.mgrid[0:h, 0:w]
    px = (2 * (xs + 0.5) / w - 1) * t * w / h
    py = (1 - 2 * (ys + 0.5) / h) * t
    d = f[None, None, :] + px[..., None] * right + py[..., None] * up
    d = d.reshape(-1, 3)
    n = d.shape[0]
    o = np.broadcast_to((np.array(eye) - np.array(origin)) / size, (n, 3))
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / d
        ta = (0 - o) * inv
        tb = (res - o) * inv
    near = np.where(d == 0, np.where((o >= 0) & (o <= res), -np.inf, np.inf), np.minimum(ta, tb))
    far = np.where(d == 0, np.where((o >= 0) & (o <= res), np.inf, -np.inf), np.maximum(ta, tb))
    t_in = np.maximum(near.max(axis=1), 0.0)
    t_out = far.min(axis=1)
    alive = t_in <= t_out
    axis = np.where(near.max(axis=1) > 0, near.argmax(axis=1), -1)  # the face the ray enters the grid by
    v = np.clip(np.floor(o + t_in[:, None] * d), 0, res - 1).astype(np.int64)
    step = np.sign(d).astype(np.int64)
    with np.errstate(divide="ignore", invalid="ignore"):
        t_max = np.where(d != 0, (v + (step > 0) - o) * inv, np.inf)
        t_delta = np.where(d != 0, np.abs(inv), np.inf)
    colour = np.zeros((n, 3))
    rows = np.arange(n)
    while alive.any():
        idx = np.nonzero(alive)[0]
        vi = v[idx]
        hit = occ[vi[:, 0], vi[:, 1], vi[:, 2]] != 0
        if hit.any():
            hi = idx[hit]
            a = axis[hi]
            face = np.where(a < 0, 2, 2 * np.maximum(a, 0) + (step[hi, np.maximum(a, 0)] > 0))
            colour[hi] = albedo[v[hi, 0], v[hi, 1], v[hi, 2]] * SHADE[face][:, None]
            alive[hi] = False
        idx = np.nonzero(alive)[0]
        if not len(idx):
            break
        a = t_max[idx].argmin(axis=1)
        v[idx, a] += step[idx, a]
        t_max[idx, a] += t_delta[idx, a]
        axis[idx] = a
        inside = (v[idx, a] >= 0) & (v[idx, a] < res[a])
        alive[idx[~inside]] = False
    del rows
    return srgb8(colour).reshape(h, w, 3)


def main(argv):
    if len(argv) != 14:
        raise SystemExit(__doc__)
    shot = read_ppm(argv[1]).astype(np.int32)
    occ = np.load(argv[2] + ".npy")
    albedo = np.load(argv[2] + ".albedo.npy").astype(np.float64)
    origin, size = [float(x) for x in argv[3:6]], float(argv[6])
    eye, target, fovy = [float(x) for x in argv[7:10]], [float(x) for x in argv[10:13]], float(argv[13])
    h, w = shot.shape[:2]
    ref = cast(occ, albedo, origin, size, eye, target, fovy, w, h)
    off = (np.abs(shot - ref) > 1).any(axis=2)
    covered = (ref > 0).any(axis=2)
    print(f"    voxels: {occ.sum()} set; the view shows voxels in {covered.sum()} of {w * h} pixels; "
          f"{off.sum()} pixels ({100 * off.mean():.2f}%) differ from the ray cast by more than one level, "
          f"mean absolute difference {np.abs(shot - ref).mean():.3f} levels")
    if not covered.any():
        print("voxels: the ray cast sees no voxel")
        return 1
    if off.mean() > 0.005:
        print(f"voxels: {100 * off.mean():.2f}% of the pixels differ from the ray cast (at most 0.5%)")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
