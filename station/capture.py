"""Recording raw mosaics from a camera into the MVTec AD layout (``station.mvtec``), with the camera's settings,
timestamps and each frame's brightness statistics, so good parts collected at the line (and defective ones from
the reject bin) import with ``station import`` without flags.

Files under ``OUT``::

    OUT/<split>/<label>/<NNNNNN>.png   raw mosaic as the camera gave it (8-bit, or 16-bit holding bit_depth bits)
    OUT/frame-K/<split>/<label>/<NNNNNN>.png  with ``[camera] dome_segments``: the part's frame K >= 1 (a frame per
                                       segment, in the order taken; the first is the one above, so other tools
                                       reading OUT see one frame per part)
    OUT/capture.jsonl                  one line per part: file(s), ids, timestamps, pixel format, bit depth,
                                       camera settings, frame statistics, ground truth where known
    OUT/polar_ano.json                 bit depth, layout and dome segments, and the camera's black level and
                                       defect pixel map (``[camera] black_level``, ``defect_pixels``, copied to
                                       OUT/defect-pixels.png): station import reads them

Numbering continues after the files already in the label's folder: a second ``station capture`` into the same
``OUT`` adds frames (same bit depth, layout, black level and defect pixel map required). A frame whose ground truth
(the virtual camera's) says it is not a ``--label`` part is left out and counted (``contradicts``);
``capture.jsonl`` then records it.

With a second camera (``[second_camera]``: the camera is a ``drivers.camera_pair.CameraPair``), each part's second
frame goes to a folder of its own, ``SECOND_OUT``, under the same name: the two folders are twins, file for file,
as ``station split`` needs them (after ``station import`` of each). A good part is left out when either camera's
ground truth shows a defect; a defective one when neither does. A part goes to both folders or to neither: its
frames are written to both before either ``capture.jsonl`` line, and when a frame cannot be written (a full disk)
what was written of the part is removed, so the pair stays twins and the next capture continues it.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from contextlib import ExitStack
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TextIO

import cv2
import numpy as np

from drivers.camera import Camera
from drivers.frame import Frame
from model.priors.api import compute_set_priors
from model.priors.frame_stats import FrameStatistics, StatisticsRange, frame_statistics
from model.priors.photometric import frames_per_part
from station.errors import UserError
from station.inspector import significant_bits
from station.mvtec import DEFECT_PIXELS_FILE, INFO_FILE, later_frame, read_info


@dataclass
class CaptureReport:
    out: Path
    folder: Path
    files: list[str] = field(default_factory=list)
    stats: list[FrameStatistics] = field(default_factory=list)
    seconds: float = 0.0
    bit_depth: int = 8
    left_out: int = 0
    """Parts not written: the camera's ground truth (the virtual camera's) contradicted ``--label``."""
    frames_per_part: int = 1
    second: CaptureReport | None = None
    """The second camera's twin folder (``second_out``), or None with one camera."""

    def describe(self) -> str:
        if self.second is not None:
            return f"{self._describe()}\nsecond camera: {self.second._describe()}"
        return self._describe()

    def _describe(self) -> str:
        if not self.stats:
            return f"no frames written to {self.folder}"
        r = StatisticsRange.from_frames(self.stats)
        med = r.median
        skipped = (f"; left out {self.left_out} parts whose ground truth contradicted the label" if self.left_out
                   else "")
        what = (f"{len(self.files)} frames" if self.frames_per_part == 1 else
                f"{len(self.files)} parts of {self.frames_per_part} frames")
        return (f"wrote {what} ({self.bit_depth}-bit) to {self.folder} in {self.seconds:.1f} s; "
                f"medians: level {med['median_level']:.3f}, p95 level {med['high_level']:.3f}, clipped "
                f"{100 * med['clipped_fraction']:.2f} %, DoLP {med['dolp_level']:.3f}{skipped}")


MAX_GRABS_PER_FRAME = 20
"""``capture`` gives up after this many grabs per frame asked for when the ground truth keeps contradicting the
label (a virtual camera whose set has no parts of that kind)."""


def contradicts(frame: Frame, label: str) -> bool:
    """Whether ``frame``'s ground truth (the virtual camera's; a real camera has none) says it is not a ``label``
    part: no part in view, a defective part for "good", a good one for a defect type."""
    gt = frame.ground_truth
    return gt is not None and (not gt.present or (label == "good") == bool(gt.label))


def part_contradicts(frame: Frame, label: str) -> bool:
    """``contradicts`` for a part seen by two cameras (``frame.companion``): a good part when either camera's ground
    truth shows a defect (or no part), a defective one when neither shows it."""
    if frame.companion is None:
        return contradicts(frame, label)
    seen = (contradicts(frame, label), contradicts(frame.companion, label))
    return any(seen) if label == "good" else all(seen)


def label_folder(out: Path, label: str, split: str | None) -> Path:
    """``train/good`` for good parts, ``test/<label>`` for defect types (``split`` overrides)."""
    if not label or "/" in label or label in (".", ".."):
        raise UserError(f"--label {label!r}: a folder name (good, or a defect type such as scratch)")
    split = split or ("train" if label == "good" else "test")
    if split == "train" and label != "good":
        raise UserError("--split train takes good parts only (MVTec layout): use --label good or --split test")
    return out / split / label


def _next_number(folder: Path) -> int:
    nums = [int(p.stem) for p in folder.glob("[0-9]" * 6 + ".png")]
    return max(nums) + 1 if nums else 0


@dataclass(frozen=True)
class SensorCalibration:
    """What a capture folder records of its camera for ``station import`` (``polar_ano.json``): its black level
    (codes, ``[camera] black_level``) and defect pixel map (a PNG path, ``[camera] defect_pixels``; "" for none)."""

    black_level: int = 0
    defect_pixels: str = ""

    def same_as(self, out: Path, info: dict[str, Any]) -> bool:
        """Whether the folder ``out`` (its ``polar_ano.json``: ``info``) records this calibration."""
        from model.priors.defect_pixels import read_defect_pixel_map

        if (info.get("black_level", 0) != self.black_level
                or bool(info.get("defect_pixels")) != bool(self.defect_pixels)):
            return False
        return not self.defect_pixels or np.array_equal(read_defect_pixel_map(out / info["defect_pixels"]),
                                                        read_defect_pixel_map(self.defect_pixels))


def _check_info(out: Path, bit_depth: int, layout: str, segments: tuple[float, ...],
                calibration: SensorCalibration) -> None:
    import shutil

    from model.priors.photometric import describe_segments

    p = out / INFO_FILE
    if p.is_file():
        old = read_info(out)
        old_segments = tuple(old.get("dome_segments") or ())
        if old.get("bit_depth") != bit_depth or old.get("layout") != layout or old_segments != segments:
            raise UserError(f"{p}: this folder holds {old.get('bit_depth')}-bit {old.get('layout')} frames, "
                            f"{describe_segments(old_segments)}; the camera gives {bit_depth}-bit {layout}, "
                            f"{describe_segments(segments)}: capture into another folder")
        if not calibration.same_as(out, old):
            raise UserError(f"{p}: this folder's frames were taken with black level {old.get('black_level', 0)} and "
                            f"{'a' if old.get('defect_pixels') else 'no'} defect pixel map; the camera now has "
                            f"{calibration.black_level} and {calibration.defect_pixels or 'none'}: capture into "
                            "another folder")
    else:
        if calibration.defect_pixels:
            shutil.copyfile(calibration.defect_pixels, out / DEFECT_PIXELS_FILE)
        p.write_text(json.dumps({"bit_depth": bit_depth, "layout": layout,
                                 **({"dome_segments": list(segments)} if segments else {}),
                                 **({"black_level": calibration.black_level} if calibration.black_level else {}),
                                 **({"defect_pixels": DEFECT_PIXELS_FILE} if calibration.defect_pixels else {}),
                                 "note": "written by station capture"}, indent=1))


@dataclass
class _StagedPart:
    """One camera's part on disk before its ``capture.jsonl`` line (``_CameraFolder.stage``): the PNGs written, the
    line (its ``file``: the part's first PNG relative to the folder), the frame statistics."""

    paths: list[Path]
    line: dict[str, Any]
    stats: FrameStatistics


@dataclass
class _CameraFolder:
    """One camera's capture folder while parts are written: its report, its ``capture.jsonl`` and what each part's
    line records (module docstring)."""

    report: CaptureReport
    log: TextIO
    layout: str
    segments: tuple[float, ...]
    settings: dict[str, Any]
    priors_bit_depth: int | None
    label: str
    calibration: SensorCalibration

    def stage(self, number: int, shots: list[Frame]) -> _StagedPart:
        """Part ``number``'s frames (one, or one per dome segment) written as PNGs, its ``capture.jsonl`` line not
        yet: ``commit`` writes it, ``discard`` removes the PNGs (a part goes to every camera's folder or to none).
        UserError when a frame cannot be written; what was written of the part is removed first."""
        out, folder, frame = self.report.out, self.report.folder, shots[0]
        try:
            bits = significant_bits(frame, self.priors_bit_depth)
        except ValueError as exc:
            raise UserError(str(exc)) from None
        if not self.report.files:
            _check_info(out, bits, self.layout, self.segments, self.calibration)
            self.report.bit_depth = bits
        elif bits != self.report.bit_depth:
            raise UserError(f"frame {frame.frame_id}: {bits}-bit after {self.report.bit_depth}-bit frames; one "
                            "capture, one pixel format")
        rel = str((folder / f"{number:06d}.png").relative_to(out))
        written: list[Path] = []
        try:
            for path, shot in zip([out / rel] + [later_frame(out, rel, k) for k in range(1, len(shots))], shots,
                                  strict=True):
                path.parent.mkdir(parents=True, exist_ok=True)
                written.append(path)
                if not cv2.imwrite(str(path), np.ascontiguousarray(shot.raw)):
                    raise UserError(f"could not write {path}")
            priors = compute_set_priors([s.raw for s in shots], self.segments, self.layout,
                                        priors=("intensity", "dolp"), bit_depth=bits)  # the whole dome's, as a set
        except BaseException:
            self.discard(written)
            raise
        stats = frame_statistics(priors, raw=frame.raw, bit_depth=bits)
        line = {
            "file": rel, **({"frame_ids": [s.frame_id for s in shots]} if self.segments else {}),
            "frame_id": frame.frame_id, "device_frame_id": frame.device_frame_id,
            "timestamp_ns": frame.timestamp_ns, "host_timestamp_ns": frame.host_timestamp_ns,
            "pixel_format": frame.pixel_format, "bit_depth": bits, "label": self.label,
            "camera": self.settings, "statistics": stats.as_dict(),
            **({"ground_truth": frame.ground_truth.label} if frame.ground_truth is not None else {})}
        return _StagedPart(written, line, stats)

    def commit(self, part: _StagedPart) -> FrameStatistics:
        """The staged part's line in ``capture.jsonl``, and the part in the report."""
        self.log.write(json.dumps(part.line) + "\n")
        self.log.flush()
        self.report.files.append(part.line["file"])
        self.report.stats.append(part.stats)
        return part.stats

    @staticmethod
    def discard(paths: list[Path]) -> None:
        """Remove a staged part's PNGs (``_StagedPart.paths``)."""
        for path in paths:
            path.unlink(missing_ok=True)


def _capture_folder(out: Path, label: str, split: str | None, option: str = "--out") -> Path:
    """The label's folder under ``out`` (given as ``option``), created; UserError for a data set's or a model's
    folder."""
    if (out / "manifest.json").exists() or any(out.glob("*.pt")):
        raise UserError(f"{option} {out}: a rendered data set or a model folder, not a capture folder; capture into "
                        "a folder of its own (station import turns it into a data set)")
    folder = label_folder(out, label, split)
    folder.mkdir(parents=True, exist_ok=True)
    return folder


def capture(camera: Camera, frames: int, out: str | Path, label: str = "good", split: str | None = None,
            settings: dict[str, Any] | None = None, layout: str = "imx250mzr", software_trigger: bool = True,
            timeout_ms: int | None = None, progress: bool = True,
            on_frame: Callable[[int, FrameStatistics], None] | None = None,
            bit_depth: int | None = None, segments: tuple[float, ...] = (),
            second_out: str | Path | None = None, second_settings: dict[str, Any] | None = None,
            calibration: SensorCalibration = SensorCalibration(),
            second_calibration: SensorCalibration = SensorCalibration()) -> CaptureReport:
    """Grab ``frames`` parts from the open ``camera`` (started and stopped here) into ``out`` (module docstring):
    one frame each, or with ``segments`` (``[camera] dome_segments``) one per segment, each triggered.
    ``settings``: the camera settings to record with each part; ``on_frame(n, stats)`` after each part;
    ``bit_depth``: ``[priors] bit_depth``, the significant bits when the pixel format's are wider.
    ``second_out``: the second camera's twin folder (the camera is a ``CameraPair``), ``second_settings`` its
    settings; each part's ``companion`` frame is written there under the same name. ``calibration``,
    ``second_calibration``: each camera's black level and defect pixel map, recorded in its folder's
    ``polar_ano.json``."""
    from tqdm import tqdm

    if frames < 1:
        raise UserError(f"--frames must be >= 1, got {frames}")
    out = Path(out)
    folder = _capture_folder(out, label, split)
    report = CaptureReport(out, folder, frames_per_part=frames_per_part(segments))
    number = _next_number(folder)
    if second_out is not None:
        second_out = Path(second_out)
        if second_out.resolve() == out.resolve():
            raise UserError(f"--second-out {second_out}: the same folder as --out; the second camera's frames need "
                            "a twin folder of their own")
        second_folder = _capture_folder(second_out, label, split, "--second-out")
        report.second = CaptureReport(second_out, second_folder)
        if _next_number(second_folder) != number:
            raise UserError(f"{folder} and {second_folder} are not twins: their next frame numbers are {number} and "
                            f"{_next_number(second_folder)}; capture both cameras into new folders")
    t0 = time.perf_counter()
    camera.start()
    try:
        with ExitStack() as stack:
            bar = stack.enter_context(tqdm(total=frames, unit="frame", disable=not progress, dynamic_ncols=True))
            def folder_of(r: CaptureReport, segs: tuple[float, ...], s: dict[str, Any] | None,
                          c: SensorCalibration) -> _CameraFolder:
                return _CameraFolder(r, stack.enter_context(open(r.out / "capture.jsonl", "a")), layout, segs,
                                     s or {}, bit_depth, label, c)

            first = folder_of(report, segments, settings, calibration)
            second = (folder_of(report.second, (), second_settings, second_calibration) if report.second is not None
                      else None)
            grabs = 0
            while len(report.files) < frames:
                grabs += 1
                if grabs > MAX_GRABS_PER_FRAME * frames:
                    raise UserError(f"{report.left_out} of {grabs - 1} frames contradicted --label {label} (the "
                                    "virtual camera's ground truth): its set has too few such parts")
                n = len(report.files)
                shots: list[Frame] = []
                for _ in range(report.frames_per_part):  # a part's frames, in the segments' order
                    if software_trigger:
                        camera.trigger()
                    shots.append(camera.grab(timeout_ms) if timeout_ms else camera.grab())
                frame = shots[0]
                if second is not None and frame.companion is None:
                    raise UserError(f"frame {frame.frame_id}: no second camera's frame with it; --second-out needs "
                                    "[second_camera] enabled in the config")
                if part_contradicts(frame, label):
                    report.left_out += 1
                    continue
                part = first.stage(number, shots)
                if second is not None:  # a part goes to both folders or to neither
                    try:
                        companion = second.stage(number, [frame.companion])
                    except BaseException:
                        first.discard(part.paths)
                        raise
                    second.commit(companion)
                stats = first.commit(part)
                bar.set_postfix(level=f"{stats.median_level:.3f}", clipped=f"{100 * stats.clipped_fraction:.2f}%",
                                dolp=f"{stats.dolp_level:.3f}")
                bar.update(1)
                if on_frame:
                    on_frame(n, stats)
                number += 1
    finally:
        camera.stop()
    report.seconds = time.perf_counter() - t0
    if report.second is not None:
        report.second.seconds = report.seconds
    return report
