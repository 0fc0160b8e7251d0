"""Stop 67 probe: a side camera at belt level under a flat dome, for the front faces (physics only, no model).

Every camera above the belt sees a vertical front face mirror the belt in front of it, which no light above the belt
fills (rule 31's strip, stop 66's Brewster camera). A camera at belt level looking square at the front face sees it
mirror the camera's own side. A flat dome there (a diffuse panel the camera looks through, as a flat-dome or large
coaxial light is built) puts the face in bright field: a dent's slope or a scratch's roughness sends its mirror
image off the panel, and it reads dark.

Per sample of a validation set (its own draws: part, pose, defect, light, materials), rendered at the set's spp:
  line      the set's own ground truth (the line camera, as rendered)
  side      a camera SIDE_DISTANCE_M from the part, SIDE_HEIGHT_M above the belt, looking horizontally at the
            part from the line camera's azimuth; the dome and panel of the line as they are
  flat      that camera with a flat dome: an emitting rectangle (one-sided, toward the part) the camera's rays pass
            through (null BSDF), FLAT_DISTANCE_M from the part, FLAT_WIDTH_M wide, from just above the belt to
            FLAT_TOP_M, radiance FLAT_RADIANCE
Measured on the front face (camera-frame normal z > 0.9 for the side camera, 0.7 < z for the line camera, body only):
  contrast  |mean S0 on the defect - mean S0 on a band 2-6 px around it| / the band's mean
  good      the same statistic on good parts, for the defect's mask shape placed at random on their front face
Usage (repository root): python docs/results/2026-11-30-side-view/probe.py DATA OUT.json [MAX_DEFECTS MAX_GOOD]"""

from __future__ import annotations

import json
import math
import sys

import cv2
import numpy as np

import sim.render as render
from sim.dataset import Dataset, DatasetSpec, draw_sample, prepare
from sim.render import render_sample
from sim.scene import part_centre

SIDE_DISTANCE_M = 0.39
SIDE_HEIGHT_M = 0.002
SIDE_TARGET_HEIGHT_M = 0.005
FLAT_DISTANCE_M = 0.30
FLAT_WIDTH_M = 0.22
FLAT_TOP_M = 0.03
FLAT_BOTTOM_M = 0.0005
FLAT_RADIANCE = 6.0
BODY = 1
BUILD = render.build_scene


def with_flat_dome(params, *args, **kwargs):
    """``sim.scene.build_scene`` plus the probe's flat dome when ``params`` carries one."""
    scene, keys = BUILD(params, *args, **kwargs)
    flat = params.get("flat_dome")
    if flat and kwargs.get("lights", True):
        import mitsuba as mi

        c, toward = np.asarray(flat["centre"]), np.asarray(flat["toward"])
        frame = mi.ScalarTransform4f().look_at(origin=c.tolist(), target=(c + toward).tolist(), up=[0, 0, 1])
        scene["flat_dome"] = {
            "type": "rectangle", "bsdf": {"type": "null"},
            "to_world": frame @ mi.ScalarTransform4f().scale([flat["width"] / 2, flat["height"] / 2, 1.0]),
            "emitter": {"type": "area", "radiance": {"type": "spectrum", "value": float(flat["radiance"])}}}
    return scene, keys


render.build_scene = with_flat_dome


def side_params(params: dict, model, flat: bool) -> dict:
    """The sample's scene from the side camera (and with the flat dome)."""
    centre = part_centre(model, params["pose"])
    line = np.asarray(params["camera"]["origin"]) - centre
    az = math.atan2(line[1], line[0])
    u = np.array([math.cos(az), math.sin(az), 0.0])
    origin = np.array([centre[0], centre[1], SIDE_HEIGHT_M]) + SIDE_DISTANCE_M * u
    target = np.array([centre[0], centre[1], SIDE_TARGET_HEIGHT_M])
    cam = {"origin": origin.tolist(), "target": target.tolist(), "up": [0.0, 0.0, 1.0],
           "fov_x_deg": params["camera"]["fov_x_deg"]}  # the line camera's lens
    out = {**params, "camera": cam}
    if flat:
        mid = 0.5 * (FLAT_TOP_M + FLAT_BOTTOM_M)
        out["flat_dome"] = {"centre": (np.array([centre[0], centre[1], mid]) + FLAT_DISTANCE_M * u).tolist(),
                            "toward": (-u).tolist(), "width": FLAT_WIDTH_M, "height": FLAT_TOP_M - FLAT_BOTTOM_M,
                            "radiance": FLAT_RADIANCE}
    return out


def front(normal: np.ndarray, part: np.ndarray, lo: float) -> np.ndarray:
    m = (part == BODY) & (normal[..., 2] > lo) & (np.abs(normal[..., 0]) < 0.3)
    return cv2.erode(m.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)


def contrast(s0: np.ndarray, mask: np.ndarray, face: np.ndarray) -> float | None:
    mask = mask & face
    if mask.sum() < 4:
        return None
    k = lambda r: np.ones((2 * r + 1, 2 * r + 1), np.uint8)  # noqa: E731
    band = (cv2.dilate(mask.astype(np.uint8), k(6)) > 0) & ~(cv2.dilate(mask.astype(np.uint8), k(2)) > 0) & face
    if band.sum() < 8:
        return None
    b = float(s0[band].mean())
    return abs(float(s0[mask].mean()) - b) / max(b, 1e-6)


def placed(shape: np.ndarray, face: np.ndarray, rng: np.random.Generator, tries: int = 20) -> list[np.ndarray]:
    """The defect's mask shape moved to random places wholly on ``face``."""
    ys, xs = np.nonzero(shape)
    ys, xs = ys - ys.min(), xs - xs.min()
    fy, fx = np.nonzero(face)
    out = []
    for _ in range(tries):
        j = rng.integers(len(fy))
        yy, xx = ys + fy[j], xs + fx[j]
        if yy.max() < face.shape[0] and xx.max() < face.shape[1] and face[yy, xx].all():
            m = np.zeros_like(face)
            m[yy, xx] = True
            out.append(m)
    return out


def main() -> None:
    data, out_path = sys.argv[1], sys.argv[2]
    max_defects, max_good = (int(v) for v in sys.argv[3:5]) if len(sys.argv) > 3 else (16, 8)
    ds = Dataset(data)
    spec = DatasetSpec.from_dict(json.load(open(f"{data}/manifest.json"))["config"])
    model = prepare(spec)
    settings = spec.render_settings()
    picked, good = [], []
    for i in ds.indices():
        s = ds.load(i)
        if s.label and s.params["defect"]["type"] in ("dent", "scratch") and len(picked) < max_defects:
            m = s.defect_mask
            if m.sum() >= 4 and np.median(s.normal[m][:, 2]) > 0.7:
                picked.append(i)
        elif not s.label and len(good) < max_good:
            good.append(i)
        if len(picked) >= max_defects and len(good) >= max_good:
            break
    rows, shapes = [], {}
    for i in picked + good:
        s = ds.load(i)
        draw = draw_sample(spec, model, i)
        row = {"index": i, "type": s.params["defect"]["type"] if s.label else "good"}
        views = {"line": (s.s0, s.defect_mask, front(s.normal, s.part_index, 0.7))}
        for name, flat in (("side", False), ("flat", True)):
            o = render_sample(model, side_params(draw.params, model, flat), draw.defect, settings, draw.mitsuba_seed)
            if name == "side":  # the flat dome's rectangle is the first hit of every mask pass: the side's masks
                mask = o.defect_mask if o.defect_mask is not None else np.zeros(o.s0.shape, bool)
                face = front(o.normal, o.part_index, 0.9)
            views[name] = (o.s0, mask, face)
            np.savez_compressed(f"{out_path}.{i}.{name}.npz", s0=o.s0, s1=o.s1, s2=o.s2, mask=mask, face=face)
        for name, (s0, mask, face) in views.items():
            row[name] = {"face_px": int(face.sum()), "face_level": float(np.median(s0[face])) if face.any() else None}
            if s.label:
                row[name]["defect_px"] = int((mask & face).sum())
                row[name]["contrast"] = contrast(s0, mask, face)
                shapes.setdefault(name, []).append(mask & face)
        rows.append(row)
        print(json.dumps(row), flush=True)
    rng = np.random.default_rng(0)
    for row in rows:  # good parts: each defect's shape placed at random on their front face
        if row["type"] != "good":
            continue
        for name in ("line", "side", "flat"):
            z = np.load(f"{out_path}.{row['index']}.{name}.npz") if name != "line" else None
            s = ds.load(row["index"])
            s0, face = (s.s0, front(s.normal, s.part_index, 0.7)) if z is None else (z["s0"], z["face"])
            vals = [contrast(s0, m, face) for shape in shapes.get(name, []) if shape.any()
                    for m in placed(shape, face, rng, 3)]
            row[name]["good_contrasts"] = [v for v in vals if v is not None]
    json.dump(rows, open(out_path, "w"), indent=1)


if __name__ == "__main__":
    main()
