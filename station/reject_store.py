"""Raw mosaic and anomaly heatmap of rejected parts, one ``.npz`` per part, referenced from the log row.

Files go to ``<image_dir>/<YYYY-MM-DD>/<part id>_f<frame id>_<ns>.npz`` (``ns``: the host's clock at saving, so
that two rejects never share a file when part and frame ids repeat, as after a restart) with arrays ``raw`` (the
camera's mosaic, its own dtype; a part imaged once per dome segment adds ``raw_1``, ``raw_2``... for its later
frames, in the order taken) and ``heatmap`` (float16 anomaly probability in [0, 1], frame-sized; absent when the
model did not run). Written to a temporary name, then renamed, so a crash leaves no half file under the final name.
A failed write (full or read-only disk) is logged and the part's row keeps ``image_path`` NULL: the decision
and its log row never depend on the image. Images are not written when less than ``reserve_bytes`` would stay free
on their file system, so that images never take the room the log's rows need when both share a disk.
"""

from __future__ import annotations

import logging
import os
import re
import time
from pathlib import Path

import numpy as np

log = logging.getLogger(__name__)

_UNSAFE = re.compile(r"[^A-Za-z0-9_.:-]+")


RESERVE_BYTES = 16 * 2**20
"""Free space kept for the inspection log: about 30,000 rows."""


class RejectStore:
    def __init__(self, image_dir: str | Path, reserve_bytes: int = RESERVE_BYTES) -> None:
        self.root = Path(image_dir).absolute()  # rows keep absolute paths: the log outlives the working directory
        self.reserve_bytes = reserve_bytes
        self.failures = 0

    def _free_bytes(self) -> int:
        """Free bytes on the file system the images go to (its nearest existing folder)."""
        import shutil

        folder = self.root
        while not folder.exists() and folder != folder.parent:
            folder = folder.parent
        try:
            return shutil.disk_usage(folder).free
        except OSError:
            return 0

    def save(self, part_id: str, frame_id: int | None, raw: np.ndarray, heatmap: np.ndarray | None,
             later: tuple[np.ndarray, ...] = (), second_raw: np.ndarray | None = None,
             second_heatmap: np.ndarray | None = None) -> str | None:
        """Write one rejected part (``later``: the frames after ``raw`` of a part imaged more than once; ``second_raw``
        and ``second_heatmap``: a second camera's frame of it and its heatmap); returns the file path, or None when it
        could not be written (logged)."""
        day = time.strftime("%Y-%m-%d")
        name = f"{_UNSAFE.sub('_', part_id)[:64]}_f{frame_id if frame_id is not None else 'none'}_{time.time_ns()}"
        path = self.root / day / f"{name}.npz"
        arrays = {"raw": raw, **{f"raw_{k}": r for k, r in enumerate(later, 1)}}
        if heatmap is not None:
            arrays["heatmap"] = heatmap.astype(np.float16)
        if second_raw is not None:
            arrays["second_raw"] = second_raw
        if second_heatmap is not None:
            arrays["second_heatmap"] = second_heatmap.astype(np.float16)
        tmp = path.with_name(path.name + ".tmp")
        try:
            size = sum(a.nbytes for a in arrays.values())
            if self._free_bytes() - size < self.reserve_bytes:
                raise OSError(f"less than {self.reserve_bytes / 2**20:.0f} MiB would stay free for the log")
            path.parent.mkdir(parents=True, exist_ok=True)
            with open(tmp, "wb") as f:
                np.savez(f, **arrays)
            os.replace(tmp, path)
        except OSError as exc:
            self.failures += 1
            if self.failures == 1 or self.failures % 100 == 0:
                log.error("cannot save the image of rejected part %s to %s (%s); %d failures so far; the log row "
                          "is kept without an image", part_id, path, exc, self.failures)
            try:
                tmp.unlink(missing_ok=True)
            except OSError:
                pass
            return None
        return str(path)

    def delete(self, paths: list[str]) -> int:
        """Remove image files (retention); returns how many were removed. Only ``.npz`` files inside the image
        folder are removed: a row's path elsewhere (another tool's log, a path written by hand) is left alone."""
        removed = 0
        root = self.root.resolve()
        for p in paths:
            target = Path(p).resolve()
            if target.suffix != ".npz" or not target.is_relative_to(root):
                log.warning("retention: %s is not an image of %s; left alone", p, self.root)
                continue
            try:
                target.unlink()
                removed += 1
            except FileNotFoundError:
                pass
            except OSError as exc:
                log.warning("retention: cannot delete %s (%s)", p, exc)
        return removed
