"""The virtual polarization camera: ``drivers.camera.Camera`` backed by a rendered dataset (``sim.dataset``).

Each frame is one rendered part, drawn at random (so poses come in random order): with probability
``empty_rate`` from the set's empty samples (the scene without the part, ``sim.dataset``), else with probability
``defect_rate`` from the samples with a defect (label 1), else from the good ones. The frame carries its ground
truth (label, defect mask, sample index, split, scene parameters, whether a part is in view) so the station can
score its decisions live.

Keeping up with the frame rate: samples are decoded once into an in-memory pool at ``open()`` (raw mosaic and
defect mask only; the float ground truth is not loaded), stratified over good and defective samples and capped at
``cache_mb``; grabs then cost no I/O. Pool arrays are read-only and shared between frames (no copy per frame).

A set rendered with one frame per dome segment (``station render --dome-segments``) is played frame by frame:
the camera's ``frames_per_part`` must equal its number of segments, and each part's frames come in the segments' order,
one per ``trigger()``, before the next part is drawn.

A second camera's virtual camera plays the same parts seen from its own viewpoint: made with ``leader=`` the first
camera's, it holds the twin set's samples of the leader's parts (a set rendered with the same seed and indices by the
second camera's preset; each sample must be the same part as the leader's, ``part_identity``) and shows, on each new
part, the part the leader shows (``drivers.camera_pair`` grabs the leader first). The two samples' labels may differ:
a label says whether that camera sees the defect (a front-face dent is not in the line camera's view).

Timing follows the camera config: ``free_run`` paces frames at ``frame_rate_hz``; ``software`` delivers one
frame per ``trigger()`` (at most ``frame_rate_hz``); hardware line triggers do not exist here (config error).
Dataset errors are ``sim.errors.SimError`` naming the file; a dataset unfit for the config is a
``CameraConfigError``.
"""

from __future__ import annotations

import json
import logging
import threading
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from drivers.camera import CameraBase, CameraConfig
from drivers.errors import CameraConfigError, CameraError, CameraTimeout
from drivers.frame import Frame, GroundTruth

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class VirtualCameraConfig:
    """dataset: folder written by ``station render``; defect_rate: fraction of the parts shown that are defective;
    split: replay only this split ("train" | "val" | "test"), None = all; seed: the draw order; cache_mb: memory
    for the decoded pool; empty_rate: fraction of frames with no part in view (the set needs empty samples)."""

    dataset: str
    defect_rate: float = 0.2
    split: str | None = None
    seed: int = 0
    cache_mb: float = 512.0
    empty_rate: float = 0.0

    def __post_init__(self) -> None:
        for name in ("defect_rate", "empty_rate"):
            if not 0.0 <= getattr(self, name) <= 1.0:
                raise CameraConfigError(f"virtual camera {name} = {getattr(self, name)}: must be in [0, 1]")


def part_identity(params: dict) -> str:
    """What a rendered part is, whichever camera renders it (a sample's ``params.json``): no part in view, or the
    defect drawn on it (type, place, size), without what the camera sees of it (``visible_px``, and so the label)."""
    defect = {k: v for k, v in (params.get("defect") or {}).items() if k != "visible_px"}
    return json.dumps({"empty": bool(params.get("empty")), "defect": defect}, sort_keys=True)


@dataclass(frozen=True)
class _Cached:
    index: int
    raws: tuple[np.ndarray, ...]
    """The part's frames: one, or one per dome segment."""
    ground_truth: GroundTruth


class VirtualCamera(CameraBase):
    """See the module docstring."""

    def __init__(self, config: CameraConfig, sim: VirtualCameraConfig, leader: VirtualCamera | None = None) -> None:
        super().__init__(config)
        self.sim = sim
        self.leader = leader
        """The first camera's virtual camera, whose parts this one shows from its own viewpoint (module docstring)."""
        self._twins: dict[int, _Cached] = {}  # with a leader: its parts' samples in this set, by sample index
        self.current: _Cached | None = None
        """The part in view (drawn at the grab that started it)."""
        self._good: list[_Cached] = []
        self._bad: list[_Cached] = []
        self._empty: list[_Cached] = []
        self._rng = np.random.default_rng(sim.seed)
        self._opened = False
        self._started = False
        self._triggers = 0
        self._cond = threading.Condition()
        self._next_due = 0.0
        self._frame_id = 0
        self._playing: list[np.ndarray] = []  # the current part's frames still to deliver (a dome-segment set)
        self._t0_ns = 0
        self.pixel_format = "Mono8"
        self.bit_depth = 8

    def open(self) -> None:
        if self._opened:
            return
        self._check_config(self.config)
        from model.priors.photometric import describe_segments, frames_per_part
        from sim.dataset import open_dataset

        ds = open_dataset(self.sim.dataset)
        frames = frames_per_part(ds.dome_segments)
        if frames != self.config.frames_per_part:  # playing another number of frames would mislead the model
            hint = "" if ds.dome_segments else " or play a set rendered with --dome-segments"
            raise CameraConfigError(f"virtual camera: {self.sim.dataset} holds {describe_segments(ds.dome_segments)}"
                                    + (" for each part" if ds.dome_segments else "") + ", the camera's "
                                    f"frames_per_part is {self.config.frames_per_part}: set frames_per_part = "
                                    f"{frames}{hint}")
        indices = ds.indices(self.sim.split, empty=None)
        if not indices:
            raise CameraConfigError(f"virtual camera: {self.sim.dataset} has no complete samples"
                                    + (f" in split {self.sim.split!r}" if self.sim.split else ""))
        m = ds.manifest
        w, h, self.bit_depth = int(m["width"]), int(m["height"]), int(m["bit_depth"])
        if (self.config.width and self.config.width != w) or (self.config.height and self.config.height != h):
            raise CameraConfigError(f"virtual camera: camera region {self.config.width}x{self.config.height} but "
                                    f"{self.sim.dataset} holds {w}x{h} frames (set width = height = 0)")
        self.pixel_format = "Mono8" if self.bit_depth <= 8 else "Mono16"
        if self.leader is not None:
            self._load_twins(ds, set(indices))
        else:
            self._load_pool(ds, indices, frames * w * h * (1 if self.bit_depth <= 8 else 2))
        self._opened = True
        self._t0_ns = time.monotonic_ns()

    def _load_pool(self, ds: object, indices: list[int], frame_bytes: int) -> None:
        from tqdm import tqdm

        labels = {i: self._label(ds, i) for i in indices}
        empty = [i for i in indices if labels[i] is None]
        good = [i for i in indices if labels[i] == 0]
        bad = [i for i in indices if labels[i] == 1]
        where = self.sim.dataset + (f" (split {self.sim.split!r})" if self.sim.split else "")
        if self.sim.empty_rate > 0 and not empty:
            raise CameraConfigError(f"virtual camera: empty_rate {self.sim.empty_rate} but {where} has no empty "
                                    f"sample (no part in view); render a set with `station render --empty-rate`")
        if self.sim.empty_rate < 1:
            if self.sim.defect_rate > 0 and not bad:
                raise CameraConfigError(f"virtual camera: defect_rate {self.sim.defect_rate} but {where} "
                                        f"has no sample with a defect (label 1)")
            if self.sim.defect_rate < 1 and not good:
                raise CameraConfigError(f"virtual camera: {where} has no good sample (label 0)")
        budget = max(3, int(self.sim.cache_mb * 2**20 // (2 * frame_bytes)))  # raws + mask per sample
        n_empty = min(len(empty), max(1 if empty and self.sim.empty_rate else 0, round(budget * self.sim.empty_rate)))
        parts_budget = budget - n_empty
        n_bad = min(len(bad), max(1 if bad else 0, round(parts_budget * self.sim.defect_rate)))
        n_good = min(len(good), parts_budget - n_bad)
        picks = [self._rng.permutation(pool)[:n] if pool else [] for pool, n in
                 ((good, n_good), (bad, n_bad), (empty, n_empty))]
        for i in tqdm([i for pick in picks for i in pick], desc="virtual camera: loading parts", unit="part",
                      disable=len(indices) < 50):
            c = self._load(ds, int(i))
            gt = c.ground_truth
            (self._empty if not gt.present else self._bad if gt.label else self._good).append(c)
        log.info("virtual camera: %d good + %d defective parts + %d empty views of %d in memory (%s, %d-bit)",
                 len(self._good), len(self._bad), len(self._empty), len(indices), self.sim.dataset, self.bit_depth)

    def _load_twins(self, ds: object, indices: set[int]) -> None:
        """This set's samples of the leader's parts; CameraConfigError when one is missing or is not the same part."""
        leader = self.leader
        assert leader is not None
        if not leader._opened:
            raise CameraConfigError("virtual camera: open the first camera before its twin")
        for c in leader._good + leader._bad + leader._empty:
            if c.index not in indices:
                raise CameraConfigError(f"virtual camera: {self.sim.dataset} has no sample {c.index}, which the first "
                                        f"camera's set {leader.sim.dataset} shows: render the twin set with the same "
                                        "seed and number of samples")
            twin = self._load(ds, c.index)
            a, b = part_identity(c.ground_truth.params), part_identity(twin.ground_truth.params)
            if a != b:
                raise CameraConfigError(f"virtual camera: sample {c.index} of {self.sim.dataset} ({b}) is not the part "
                                        f"sample {c.index} of {leader.sim.dataset} shows ({a}): not a twin set (same "
                                        "seed, same parts, another camera)")
            self._twins[c.index] = twin
        log.info("virtual camera: %d twin samples of %s's parts in memory (%s)", len(self._twins),
                 leader.sim.dataset, self.sim.dataset)

    @staticmethod
    def _label(ds: object, index: int) -> int | None:
        """The sample's label, None for an empty sample (no part in view)."""
        import json

        from sim.dataset import sample_dir

        path = sample_dir(ds.root, index) / "params.json"  # type: ignore[attr-defined]
        try:
            params = json.loads(path.read_text())
            return None if params.get("empty") else int(params["label"])
        except (OSError, ValueError, KeyError) as exc:
            raise CameraConfigError(f"virtual camera: {path}: no readable label ({exc})") from None

    @staticmethod
    def _load(ds: object, index: int) -> _Cached:
        from sim.dataset import sample_dir

        sample = ds.load(index, ground_truth=False)  # type: ignore[attr-defined]
        mask = None
        gt_path = Path(sample_dir(ds.root, index)) / "gt.npz"  # type: ignore[attr-defined]
        if gt_path.is_file():
            with np.load(gt_path) as gt:  # reads only this member of the archive
                if "defect_mask" in gt:
                    mask = np.ascontiguousarray(gt["defect_mask"], dtype=bool)
                    mask.flags.writeable = False
        raws = tuple(np.ascontiguousarray(r) for r in sample.raws)
        for raw in raws:
            raw.flags.writeable = False
        return _Cached(index, raws, GroundTruth(sample.label, mask, index, sample.split, sample.params,
                                               present=not sample.params.get("empty", False)))

    def _check_config(self, config: CameraConfig) -> None:
        if config.trigger not in ("free_run", "software"):
            raise CameraConfigError(f"virtual camera: trigger {config.trigger!r} needs hardware lines; use "
                                    "'free_run' or 'software'")

    def configure(self, config: CameraConfig) -> None:
        if self._started:
            raise CameraError("virtual camera: configure while streaming; stop() first")
        self._check_config(config)
        self.config = config

    def start(self) -> None:
        if not self._opened:
            raise CameraError("virtual camera: start before open")
        self._started = True
        self._next_due = time.monotonic()

    def trigger(self) -> None:
        if self.config.trigger != "software":
            raise CameraError(f"virtual camera: trigger() needs trigger = 'software', not {self.config.trigger!r}")
        if not self._started:
            raise CameraError("virtual camera: trigger before start")
        with self._cond:
            self._triggers += 1
            self._cond.notify_all()

    def grab(self, timeout_ms: int | None = None) -> Frame:
        if not self._started:
            raise CameraError("virtual camera: grab before start")
        timeout_s = (timeout_ms if timeout_ms is not None else self.config.timeout_ms) / 1e3
        deadline = time.monotonic() + timeout_s
        if self.config.trigger == "software":
            with self._cond:
                if not self._cond.wait_for(lambda: self._triggers > 0, timeout=timeout_s):
                    self._stats.timeouts += 1
                    raise CameraTimeout(f"virtual camera: no trigger within {timeout_s * 1e3:.0f} ms")
                self._triggers -= 1
        wait_s = self._next_due - time.monotonic()  # the sensor's frame rate bounds both modes
        if time.monotonic() + max(wait_s, 0.0) > deadline:
            time.sleep(max(deadline - time.monotonic(), 0.0))
            self._stats.timeouts += 1
            raise CameraTimeout(f"virtual camera: next frame due in {wait_s * 1e3:.0f} ms, after the "
                                f"{timeout_s * 1e3:.0f} ms timeout ({self.config.frame_rate_hz} Hz)")
        if wait_s > 0:
            time.sleep(wait_s)
        now = time.monotonic()
        self._next_due = max(self._next_due + 1.0 / self.config.frame_rate_hz, now - 1.0 / self.config.frame_rate_hz)
        if not self._playing:  # the next part: its frames come one per grab
            part = self._draw()
            self.current, self._playing = part, list(part.raws)
        raw = self._playing.pop(0)
        self._frame_id += 1
        self._stats.completed += 1
        return Frame(raw=raw, pixel_format=self.pixel_format, bit_depth=self.bit_depth, frame_id=self._frame_id,
                     timestamp_ns=time.monotonic_ns() - self._t0_ns, host_timestamp_ns=time.time_ns(),
                     device_frame_id=self._frame_id, ground_truth=self.current.ground_truth)

    def _draw(self) -> _Cached:
        """A part at random: an empty view at ``empty_rate``, else defective at ``defect_rate``; with a leader, the
        leader's part."""
        if self.leader is not None:
            shown = self.leader.current
            if shown is None:
                raise CameraError("virtual camera: its first camera has shown no part yet (grab the first camera "
                                  "first)")
            return self._twins[shown.index]
        if self._empty and (not (self._good or self._bad) or self._rng.random() < self.sim.empty_rate):
            pool = self._empty
        else:
            pool = self._bad if (self._bad and (not self._good or self._rng.random() < self.sim.defect_rate)) \
                else self._good
        return pool[int(self._rng.integers(len(pool)))]

    def stop(self) -> None:
        self._started = False

    def close(self) -> None:
        self.stop()
        self._good, self._bad, self._empty, self._playing = [], [], [], []
        self._twins, self.current = {}, None
        self._opened = False
