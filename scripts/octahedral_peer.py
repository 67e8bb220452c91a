#!/usr/bin/python3
"""The octahedral impostor of an asset at a given size in bytes, drawn and scored against the truth
(issue 49 item 4: the view-dependent peer of scripts/far_table.py and fidelity_table.py).

An octahedral impostor is what engines ship for far foliage with a shader of their own: F x F
frames of the asset, rendered from the directions of a grid on the octahedral map of the sphere,
in one atlas; at run time a camera-facing quad blends the three frames nearest the view direction.
It is a peer, not an output (glTF has no such material). Here:
1. Frames: `qf-render render ASSET --octahedral F --fov 2` (near-orthographic, framing the asset's
   bounding sphere, lit by the engine method's headlight from each frame's own direction, so read
   its scores as an upper bound), over black and over white: premultiplied linear colour and alpha
   at --frame-px per frame.
2. The atlas: frames box-filtered to r x r texels, as an RGBA8 PNG (straight sRGB colour, bled into
   empty texels); r is the largest whose PNG fits --bytes (zlib level 9; the quad and shader add
   a few hundred bytes, not counted); F the most of --frames that keeps r >= 0.4 x the size.
   The map's border folds onto itself, so 4 (F - 1) of the F x F frames repeat others (as in
   engines' full-sphere octahedral impostors).
3. Drawing, for each of eval's cameras (`qf-render eval --cameras`): the three frames of the grid
   triangle holding the direction from the sphere's centre to the eye, weighted barycentrically; for
   each, the pixel's ray meets the frame's own plane (through the centre, facing the frame's
   direction), where the frame is sampled (bilinear, trilinear between its box-filtered mips at the
   footprint one screen pixel has); premultiplied colours and alphas are blended, then the alpha
   test at 0.5 shows the blended colour (the common octahedral impostor shader).
4. Scored by `qf-render eval ASSET ASSET --external DIR` (the truth as for every other peer).

The frame grid is runtime_gl/camera.h octahedral_direction (whole sphere: eval's views cover it).
Needs numpy and PIL (Debian python3-numpy, python3-pil).
usage: octahedral_peer.py BIN_DIR ASSET WORK_DIR --bytes N --size PX [--views 8] [--truth 8]
                          [--frames 16,12,8] [--frame-px 128] [-o OUT.json]
Prints (and writes) {"frames", "texels", "bytes", "metrics": eval's mean scores}.
"""
import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np
from PIL import Image

FOV = 2.0  # degrees: the frames' near-orthographic field of view


def srgb_to_linear(c):
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def linear_to_srgb(c):
    c = np.clip(c, 0, 1)
    return np.where(c <= 0.0031308, c * 12.92, 1.055 * np.power(c, 1 / 2.4) - 0.055)


def load(path):
    return np.asarray(Image.open(path).convert("RGB"), dtype=np.float64) / 255.0


def render_frames(a, frames):
    """Premultiplied linear colour (H, W, 3) and alpha (H, W) of the F x F frame sheet."""
    stem = os.path.join(a.work, f"{os.path.basename(a.asset)}.octa{frames}x{a.frame_px}")
    for bg, name in (("0,0,0", "black"), ("255,255,255", "white")):
        out = f"{stem}.{name}.png"
        if not os.path.exists(out):
            subprocess.run([os.path.join(a.bin_dir, "qf-render"), "render", a.asset, "-o", out, "--octahedral", str(frames),
                            "--fov", str(FOV), "--size", str(a.frame_px), "-m", "engine", "--background", bg],
                           check=True, capture_output=True)
    black, white = srgb_to_linear(load(f"{stem}.black.png")), srgb_to_linear(load(f"{stem}.white.png"))
    alpha = np.clip(1 - (white - black).mean(axis=2), 0, 1)
    return black, alpha


def box_resize(img, size):
    """Each channel box-filtered to size x size (PIL's BOX filter on floats)."""
    chans = img if img.ndim == 3 else img[:, :, None]
    out = [np.asarray(Image.fromarray(chans[:, :, c].astype(np.float32), mode="F").resize((size, size), Image.BOX))
           for c in range(chans.shape[2])]
    return np.stack(out, axis=2) if img.ndim == 3 else out[0]


def tiles(premult, alpha, frames, texels):
    """Per frame (row-major), premultiplied colour and alpha at texels x texels."""
    step = premult.shape[0] // frames
    out = []
    for k in range(frames * frames):
        r, c = divmod(k, frames)
        sl = (slice(r * step, (r + 1) * step), slice(c * step, (c + 1) * step))
        out.append((box_resize(premult[sl], texels), box_resize(alpha[sl], texels)))
    return out


def bleed(colour, alpha, passes=8):
    """Straight colour where alpha is 0 taken from covered neighbours (as exporters bleed atlases)."""
    known = alpha > 0
    colour = colour.copy()
    for _ in range(passes):
        if known.all():
            break
        acc, cnt = np.zeros_like(colour), np.zeros(known.shape)
        for dy, dx in ((-1, 0), (1, 0), (0, -1), (0, 1)):
            k = np.roll(known, (dy, dx), axis=(0, 1))
            acc += np.roll(colour, (dy, dx), axis=(0, 1)) * k[:, :, None]
            cnt += k
        fill = ~known & (cnt > 0)
        colour[fill] = acc[fill] / cnt[fill][:, None]
        known = known | fill
    return colour


def encode_atlas(tile_list, frames, texels, path):
    """The atlas as an RGBA8 PNG; returns its bytes and the decoded tiles (premultiplied, alpha)."""
    side = frames * texels
    rgba = np.zeros((side, side, 4), np.uint8)
    for k, (pm, al) in enumerate(tile_list):
        r, c = divmod(k, frames)
        straight = np.where(al[:, :, None] > 0, pm / np.maximum(al[:, :, None], 1e-6), 0)
        straight = bleed(straight, al)
        block = rgba[r * texels:(r + 1) * texels, c * texels:(c + 1) * texels]
        block[:, :, :3] = np.round(linear_to_srgb(straight) * 255)
        block[:, :, 3] = np.round(np.clip(al, 0, 1) * 255)
    Image.fromarray(rgba, "RGBA").save(path, compress_level=9)
    decoded = []
    for k in range(frames * frames):
        r, c = divmod(k, frames)
        block = rgba[r * texels:(r + 1) * texels, c * texels:(c + 1) * texels].astype(np.float64) / 255
        al = block[:, :, 3]
        decoded.append((srgb_to_linear(block[:, :, :3]) * al[:, :, None], al))
    return os.path.getsize(path), decoded


def mips(pm, al):
    levels = [(pm, al)]
    while levels[-1][1].shape[0] > 1:
        p, a = levels[-1]
        n = p.shape[0] // 2
        levels.append((p[:2 * n, :2 * n].reshape(n, 2, n, 2, 3).mean(axis=(1, 3)), a[:2 * n, :2 * n].reshape(n, 2, n, 2).mean(axis=(1, 3))))
    return levels


def bilinear(pm, al, x, y):
    """Sample at texel coordinates (x, y: centres at i + 0.5), clamped to the tile."""
    n = al.shape[0]
    x, y = np.clip(x - 0.5, 0, n - 1), np.clip(y - 0.5, 0, n - 1)
    x0, y0 = np.minimum(np.floor(x).astype(int), n - 1), np.minimum(np.floor(y).astype(int), n - 1)
    x1, y1 = np.minimum(x0 + 1, n - 1), np.minimum(y0 + 1, n - 1)
    fx, fy = x - x0, y - y0
    w = [((1 - fx) * (1 - fy)), (fx * (1 - fy)), ((1 - fx) * fy), (fx * fy)]
    idx = [(y0, x0), (y0, x1), (y1, x0), (y1, x1)]
    p = sum(wi[..., None] * pm[iy, ix] for wi, (iy, ix) in zip(w, idx))
    a = sum(wi * al[iy, ix] for wi, (iy, ix) in zip(w, idx))
    return p, a


def frame_direction(col, row, frames):
    u, v = -1 + 2 * col / (frames - 1), -1 + 2 * row / (frames - 1)
    x, z, y = u, v, 1 - abs(u) - abs(v)
    if y < 0:
        x, z = (1 - abs(v)) * (-1 if u < 0 else 1), (1 - abs(u)) * (-1 if v < 0 else 1)
    d = np.array([x, y, z])
    return d / np.linalg.norm(d)


def basis(direction):
    """orbit_camera's right and up vectors looking along -direction."""
    f = -direction
    up = np.array([0, 0, -1.0]) if abs(direction[1]) > 0.99 else np.array([0, 1.0, 0])
    s = np.cross(f, up)
    s /= np.linalg.norm(s)
    return s, np.cross(s, f)


def nearest_frames(view, frames):
    """The grid triangle holding `view` on the octahedral map: [(column, row, weight)] * 3."""
    p = view / np.abs(view).sum()
    if p[1] >= 0:
        u, v = p[0], p[2]
    else:
        u, v = (1 - abs(p[2])) * (-1 if p[0] < 0 else 1), (1 - abs(p[0])) * (-1 if p[2] < 0 else 1)
    gx, gy = (u + 1) / 2 * (frames - 1), (v + 1) / 2 * (frames - 1)
    i, j = min(int(gx), frames - 2), min(int(gy), frames - 2)
    fa, fb = gx - i, gy - j
    if fa + fb <= 1:
        return [(i, j, 1 - fa - fb), (i + 1, j, fa), (i, j + 1, fb)]
    return [(i + 1, j + 1, fa + fb - 1), (i + 1, j, 1 - fb), (i, j + 1, 1 - fa)]


def draw_view(cam, pyramid, frames, texels):
    """The impostor from one eval camera: (over black, over white) as uint8 RGB images."""
    eye, centre, up = (np.array(cam[k], np.float64) for k in ("eye", "target", "up"))
    w, h, fovy = cam["width"], cam["height"], math.radians(cam["fovy_degrees"])
    dist = np.linalg.norm(eye - centre)
    radius = dist * math.sin(min(fovy / 2, math.atan(math.tan(fovy / 2) * w / h)))  # eval frames the sphere
    half = radius / math.cos(math.radians(FOV / 2))  # the frames' half extent on their plane
    f = (centre - eye) / dist
    s = np.cross(f, up)
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    t = math.tan(fovy / 2)
    xs = (2 * (np.arange(w) + 0.5) / w - 1) * t * w / h
    ys = (1 - 2 * (np.arange(h) + 0.5) / h) * t
    ray = f[None, None, :] + xs[None, :, None] * s[None, None, :] + ys[:, None, None] * u[None, None, :]
    # The quad: the pixels whose ray passes within the bounding sphere's radius of its centre.
    along = ray @ (centre - eye)
    closest = eye + ray * (along / (ray * ray).sum(axis=2))[:, :, None]
    inside = np.linalg.norm(closest - centre, axis=2) <= radius
    # One screen pixel's footprint at the centre, in texels: the mip level.
    level = math.log2(max(1e-9, (dist * 2 * t / h) / (2 * half / texels)))
    pm_sum, a_sum = np.zeros((h, w, 3)), np.zeros((h, w))
    for col, row, weight in nearest_frames((eye - centre) / dist, frames):
        if weight <= 0:
            continue
        d = frame_direction(col, row, frames)
        fs, fu = basis(d)
        tk = ((centre - eye) @ d) / (ray @ d)
        hit = eye + ray * tk[:, :, None] - centre
        x = ((hit @ fs) / half + 1) / 2 * texels
        y = (1 - (hit @ fu) / half) / 2 * texels
        levels = pyramid[row * frames + col]
        l0 = min(max(0, int(math.floor(level))), len(levels) - 1)
        l1, frac = min(l0 + 1, len(levels) - 1), min(1.0, max(0.0, level - l0))
        p, a = bilinear(*levels[l0], x / 2 ** l0, y / 2 ** l0)
        if frac > 0 and l1 != l0:
            p1, a1 = bilinear(*levels[l1], x / 2 ** l1, y / 2 ** l1)
            p, a = (1 - frac) * p + frac * p1, (1 - frac) * a + frac * a1
        pm_sum += weight * p
        a_sum += weight * a
    shown = inside & (a_sum >= 0.5)
    colour = np.round(linear_to_srgb(pm_sum / np.maximum(a_sum, 1e-6)[:, :, None]) * 255).astype(np.uint8)
    black, white = np.zeros((h, w, 3), np.uint8), np.full((h, w, 3), 255, np.uint8)
    black[shown], white[shown] = colour[shown], colour[shown]
    return black, white


def fit_atlas(a, frames, stem):
    """The largest frame side in texels whose F x F atlas fits --bytes: (texels, bytes, decoded), or None."""
    premult, alpha = render_frames(a, frames)
    best, lo, hi = None, 2, a.frame_px
    while lo <= hi:
        texels = (lo + hi) // 2
        size, decoded = encode_atlas(tiles(premult, alpha, frames, texels), frames, texels, stem + ".atlas.png")
        if size <= a.bytes:
            best, lo = (texels, size, decoded), texels + 1
        else:
            hi = texels - 1
    if best:  # the file on disk: the one chosen
        encode_atlas(tiles(premult, alpha, frames, best[0]), frames, best[0], stem + ".atlas.png")
    return best


def choose_atlas(a, stem):
    """The grid: the most frames (of --frames) whose side still has 0.4 texel per pixel of the
    sphere's diameter on screen, else the fewest. More frames blend nearer views, fewer keep more
    texels. Measured on a seeded oak (generate oak --seed 7): at 74 px and 241 KB, 16 x 16 frames
    of 30 texels 21.2 dB, 12 x 12 of 48 20.8, 8 x 8 of 89 19.4; at 23 px and 21 KB, 12 x 12 of 9
    texels 19.9, 8 x 8 of 16 20.0. Returns (frames, texels, bytes, decoded tiles)."""
    grids = sorted((int(f) for f in a.frames.split(",")), reverse=True)
    for i, frames in enumerate(grids):
        fit = fit_atlas(a, frames, stem)
        if fit and (fit[0] >= 0.4 * a.size or i == len(grids) - 1):
            return (frames,) + fit
    sys.exit(f"octahedral_peer: no {grids[-1]}x{grids[-1]} atlas fits {a.bytes} bytes")


def main():
    ap = argparse.ArgumentParser(description="the octahedral impostor peer at equal bytes, scored against the truth")
    ap.add_argument("bin_dir")
    ap.add_argument("asset")
    ap.add_argument("work")
    ap.add_argument("--bytes", type=int, required=True)
    ap.add_argument("--size", type=int, required=True)
    ap.add_argument("--views", type=int, default=8)
    ap.add_argument("--truth", type=int, default=8)
    ap.add_argument("--frames", default="16,12,8", help="grid sizes to choose from (see fit_atlas)")
    ap.add_argument("--frame-px", type=int, default=128)
    ap.add_argument("-o", "--output")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    render = os.path.join(a.bin_dir, "qf-render")
    stem = os.path.join(a.work, f"{os.path.basename(a.asset)}.octa.{a.bytes}.{a.size}")
    # 1-2. Frames, and the atlas that fits the bytes.
    frames, texels, size, decoded = choose_atlas(a, stem)
    # 3. Eval's cameras, and the impostor drawn from each.
    cams = stem + ".cameras.json"
    subprocess.run([render, "eval", a.asset, a.asset, "--views", str(a.views), "--size", str(a.size), "--truth", "1", "-m", "engine",
                    "--cameras", cams, "-o", stem + ".cams-eval.json", "--diff", stem + ".cams-diff"], check=True, capture_output=True)
    views = json.load(open(cams))["views"]
    ext = stem + ".views"
    os.makedirs(ext, exist_ok=True)
    pyramid = [mips(pm, al) for pm, al in decoded]
    for i, cam in enumerate(views):
        black, white = draw_view(cam, pyramid, frames, texels)
        Image.fromarray(black, "RGB").save(f"{ext}/view_{i}_black.png")
        Image.fromarray(white, "RGB").save(f"{ext}/view_{i}_white.png")
    # 4. Scored against the truth.
    ev = stem + ".eval.json"
    subprocess.run([render, "eval", a.asset, a.asset, "--views", str(a.views), "--size", str(a.size), "--truth", str(a.truth), "-m", "engine",
                    "--external", ext, "-o", ev, "--diff", stem + ".diff"], check=True, capture_output=True)
    result = {"frames": frames, "texels": texels, "bytes": size, "metrics": json.load(open(ev))["mean"]["external"]}
    if a.output:
        json.dump(result, open(a.output, "w"), indent=1)
    print(json.dumps(result))


if __name__ == "__main__":
    main()
