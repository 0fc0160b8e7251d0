"""The MVTec AD folder layout, both ways: import captured (or foreign) raw mosaics into a dataset the station's
commands read, and export a rendered set so other tools (anomalib, ...) can train on it.

Layout (names of images are free; masks are matched by name)::

    DIR/train/good/<name>.png|.tif|.tiff          good parts for training
    DIR/val/good/, DIR/val/<type>/                optional (our extension): validation parts, for thresholds
    DIR/test/good/<name>.png                      good test parts
    DIR/test/<defect type>/<name>.png             defective test parts
    DIR/ground_truth/<defect type>/<name>_mask.png   optional defect masks (non-zero = defect)
    DIR/object_masks/<split>/<type>/<name>_object.png  optional object masks (our extension)
    DIR/polar_ano.json                            optional: {"bit_depth", "layout", "dome_segments", "black_level",
                                                  "defect_pixels"}, written by export and capture
    DIR/defect-pixels.png                         optional: the camera's defect pixel map, when polar_ano.json
                                                  names it (``DEFECT_PIXELS_FILE``)
    DIR/frame-K/<split>/<type>/<name>.png         with "dome_segments" (our extension): each part's frame K >= 1,
                                                  one per dome segment in that order; the image above is the first

Images are raw polarizer mosaics (one channel, even sides) as 8-bit or 16-bit PNG/TIFF; a 16-bit file holds codes
of ``--bit-depth`` significant bits (12 for a Mono12 camera). A file whose codes do not fit the stated bit depth,
or a set whose codes all fit a smaller one (the 12-bit-read-as-16-bit trap: 16x too dark), is refused with one
line naming the file.

The imported set is the renderer's format (``sim.dataset``) with ``split_rule`` "folders": every sample keeps the
split of its folder. Without a ``val/`` folder, a fixed share of ``train/good`` (``val_fraction``, chosen by a
seeded shuffle of the names and recorded per sample) becomes the validation split that training's keep-best and
``station threshold`` use. Defective parts without a mask file get no defect mask: image-level metrics only.
"""

from __future__ import annotations

import json
import os
import shutil
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

import cv2
import numpy as np

from model.priors.conventions import CONVENTION_VERSION, LAYOUTS, is_bit_depth
from model.priors.photometric import check_segments
from sim.dataset import FOLDER_SPLIT_RULE, FORMAT, VERSION, Sample, open_dataset, write_sample
from station.datasets import set_black_level, set_defect_pixels
from station.errors import UserError

IMAGE_SUFFIXES = (".png", ".tif", ".tiff")
SPLIT_DIRS = ("train", "val", "test")
INFO_FILE = "polar_ano.json"
DEFECT_PIXELS_FILE = "defect-pixels.png"
"""An imported set's copy of the camera's defect pixel map (``station import --defect-pixels``), and a capture's
or an export's (named in ``polar_ano.json``)."""
BIT_DEPTHS = (8, 10, 12, 14, 16)


class BitDepthError(UserError):
    """A mosaic file does not hold codes of the stated bit depth; the message names the file."""


@dataclass(frozen=True)
class MvtecItem:
    """One image of an MVTec-layout folder: its split and defect type ("good" for good parts), image, masks."""

    split: str
    defect_type: str
    path: Path
    mask: Path | None = None
    object_mask: Path | None = None

    @property
    def label(self) -> int:
        return int(self.defect_type != "good")


@dataclass
class ImportReport:
    """What ``import_mvtec`` wrote: counts per split and type, how many defective parts have masks."""

    out: Path
    bit_depth: int
    layout: str
    width: int
    height: int
    counts: dict[str, dict[str, int]] = field(default_factory=dict)
    n_defective: int = 0
    n_defect_masks: int = 0
    n_object_masks: int = 0
    val_from_train: int = 0

    def describe(self) -> str:
        parts = [f"{split}: " + ", ".join(f"{n} {t}" for t, n in sorted(c.items())) for split, c in self.counts.items()]
        masks = ("no defect masks: image-level metrics only" if self.n_defective and not self.n_defect_masks else
                 f"defect masks for {self.n_defect_masks} of {self.n_defective} defective parts")
        obj = (f"object masks for {self.n_object_masks} samples" if self.n_object_masks
               else "no object masks: the model's region of interest is used")
        val = f"; val: {self.val_from_train} good parts held out of train/good" if self.val_from_train else ""
        return (f"imported {sum(sum(c.values()) for c in self.counts.values())} mosaics {self.width}x{self.height}, "
                f"{self.bit_depth}-bit, layout {self.layout} into {self.out} ({'; '.join(parts)}{val}); {masks}; "
                f"{obj}")


def _images(folder: Path) -> list[Path]:
    return sorted(p for p in folder.iterdir() if p.is_file() and p.suffix.lower() in IMAGE_SUFFIXES)


def _find(folder: Path, stem: str) -> Path | None:
    for suffix in IMAGE_SUFFIXES:
        p = folder / f"{stem}{suffix}"
        if p.is_file():
            return p
    return None


def scan_mvtec(root: str | Path) -> list[MvtecItem]:
    """Every image under ``root``'s split folders, sorted by split, type and name, with its masks when present."""
    root = Path(root)
    if not root.is_dir():
        raise UserError(f"{root}: no such folder")
    items = []
    for split in SPLIT_DIRS:
        sdir = root / split
        if not sdir.is_dir():
            continue
        for tdir in sorted(p for p in sdir.iterdir() if p.is_dir()):
            kind = tdir.name
            if split == "train" and kind != "good":
                raise UserError(f"{tdir}: train/ holds good parts only (train/good/); put defective parts under "
                                f"test/<defect type>/")
            for img in _images(tdir):
                mask = _find(root / "ground_truth" / kind, f"{img.stem}_mask") if kind != "good" else None
                obj = _find(root / "object_masks" / split / kind, f"{img.stem}_object")
                items.append(MvtecItem(split, kind, img, mask, obj))
    if not any(i.split == "train" for i in items) and not any(i.split == "test" for i in items):
        raise UserError(f"{root}: not an MVTec AD layout (no images under train/good/ or test/<type>/)")
    return items


def later_frame(root: Path, rel: str | Path, k: int) -> Path:
    """Where frame ``k`` >= 1 of the part whose first frame is ``root / rel`` is kept (``frame-K/``, module
    docstring)."""
    return root / f"frame-{k}" / rel


def read_info(root: str | Path) -> dict:
    """``polar_ano.json`` of an MVTec-layout folder ({} when absent); UserError naming the file and key unless it is
    an object whose ``bit_depth`` (when present) is an integer in 1..16, ``layout`` a string, ``dome_segments``
    azimuths (``model.priors.photometric.check_segments``), ``black_level`` a code (an integer >= 0) and
    ``defect_pixels`` a file in the folder (the camera's map)."""
    p = Path(root) / INFO_FILE
    if not p.is_file():
        return {}
    try:
        info = json.loads(p.read_text())
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise UserError(f"{p}: unreadable ({exc})") from None
    if not isinstance(info, dict):
        raise UserError(f"{p}: expected a JSON object with bit_depth and layout, got {type(info).__name__}")
    depth = info.get("bit_depth")
    if depth is not None and not is_bit_depth(depth):
        raise UserError(f"{p}: bit_depth: expected an integer in 1..16, got {depth!r}")
    if info.get("layout") is not None and not isinstance(info["layout"], str):
        raise UserError(f"{p}: layout: expected a string, got {info['layout']!r}")
    segments = info.get("dome_segments")
    if segments is not None:
        try:
            if not isinstance(segments, list) or not all(isinstance(a, int | float) for a in segments):
                raise ValueError(f"{segments!r}: a list of azimuths in degrees")
            info["dome_segments"] = list(check_segments(segments))
        except ValueError as exc:
            raise UserError(f"{p}: dome_segments: {exc}") from None
    level = info.get("black_level")
    if level is not None and (isinstance(level, bool) or not isinstance(level, int) or level < 0):
        raise UserError(f"{p}: black_level: expected a code (an integer >= 0), got {level!r}")
    name = info.get("defect_pixels")
    if name is not None and (not isinstance(name, str) or not (Path(root) / name).is_file()):
        raise UserError(f"{p}: defect_pixels: {name!r} is not a file in {root}")
    return info


def read_mosaic(path: Path, bit_depth: int) -> np.ndarray:
    """A raw mosaic file as uint8/uint16 codes of ``bit_depth`` bits; BitDepthError/UserError naming the file."""
    raw = cv2.imread(str(path), cv2.IMREAD_UNCHANGED)
    if raw is None:
        raise UserError(f"{path}: not a readable PNG or TIFF image")
    if raw.ndim != 2:
        raise UserError(f"{path}: {raw.shape[2] if raw.ndim == 3 else raw.ndim} channels; a raw polarizer mosaic "
                        f"has one (save the camera's Mono/Polarized frame, not a colour rendering)")
    if raw.dtype not in (np.uint8, np.uint16):
        raise UserError(f"{path}: pixel type {raw.dtype}; raw mosaics are 8- or 16-bit integers")
    if raw.shape[0] % 2 or raw.shape[1] % 2:
        raise UserError(f"{path}: {raw.shape[1]}x{raw.shape[0]} has an odd side; a mosaic is whole 2x2 superpixels")
    container = raw.dtype.itemsize * 8
    if bit_depth > container:
        raise BitDepthError(f"{path}: an {container}-bit file cannot hold {bit_depth}-bit codes; "
                            f"pass --bit-depth {container}")
    if bit_depth < container:
        top = int(raw.max())
        if top > 2**bit_depth - 1:
            raise BitDepthError(f"{path}: code {top} exceeds the {bit_depth}-bit range (max {2**bit_depth - 1}); "
                                f"wrong --bit-depth? (the file's codes need {top.bit_length()} bits)")
    return raw


def read_mask(path: Path, shape: tuple[int, int]) -> np.ndarray:
    m = cv2.imread(str(path), cv2.IMREAD_UNCHANGED)
    if m is None:
        raise UserError(f"{path}: not a readable mask image")
    if m.ndim == 3:
        m = m.max(axis=2)
    if m.shape != shape:
        raise UserError(f"{path}: mask {m.shape[1]}x{m.shape[0]} differs from its image {shape[1]}x{shape[0]}")
    return m > 0


def check_not_smaller(bit_depth: int, top: int, brightest: Path) -> None:
    """The 12-bit-as-16-bit trap: codes that all fit a smaller standard depth are refused, naming the brightest file."""
    if bit_depth <= 8:
        return
    smaller = [b for b in BIT_DEPTHS if b < bit_depth and top <= 2**b - 1]
    if smaller and top > 0:
        raise BitDepthError(f"{brightest}: the brightest code of the whole set is {top}, which fits {smaller[0]} "
                            f"bits: read as {bit_depth}-bit the frames are {2 ** (bit_depth - smaller[0])}x too dark; "
                            f"pass --bit-depth {smaller[0]} (or --bit-depth {bit_depth} --allow-dark if they "
                            f"really are that dark)")


def _val_names(items: list[MvtecItem], fraction: float, seed: int) -> set[Path]:
    good = [i.path for i in items if i.split == "train"]
    if any(i.split == "val" for i in items) or fraction <= 0 or len(good) < 2:
        return set()
    n = max(1, round(fraction * len(good)))
    order = np.random.default_rng(seed).permutation(len(good))
    return {good[k] for k in order[:n]}


def import_mvtec(src: str | Path, out: str | Path, bit_depth: int | None = None, layout: str | None = None,
                 val_fraction: float = 0.1, seed: int = 0, allow_dark: bool = False, progress: bool = True,
                 defect_pixels: str | Path | None = None, black_level: int | None = None) -> ImportReport:
    """Import the MVTec-layout folder ``src`` into a new dataset ``out`` (module docstring). ``bit_depth`` and
    ``layout`` default to ``src/polar_ano.json``'s, then to 8 bits for 8-bit files and the IMX250MZR layout; a
    16-bit set needs its bit depth stated. ``defect_pixels``: the camera's defect pixel map (a PNG of the frames'
    size), copied into the set and named in its manifest, so every command that reads the set fills those pixels
    (``station.datasets.set_defect_pixels``). ``black_level``: the camera's pedestal in the files' codes, named in
    the manifest and removed by every command that reads the set (``station.datasets.set_black_level``). Both
    default to ``src/polar_ano.json``'s (``station capture`` records the camera's), then to none."""
    from tqdm import tqdm

    from model.priors.black_level import check_black_level
    from model.priors.defect_pixels import read_defect_pixel_map

    src, out = Path(src), Path(out)
    info = read_info(src)
    if defect_pixels is None and info.get("defect_pixels"):
        defect_pixels = src / info["defect_pixels"]
    if black_level is None:
        black_level = info.get("black_level", 0)
    defect_map = None
    if defect_pixels is not None:
        try:
            defect_map = read_defect_pixel_map(defect_pixels)
        except ValueError as exc:
            raise UserError(f"--defect-pixels: {exc}") from None
    layout = layout or info.get("layout") or "imx250mzr"
    segments = info.get("dome_segments") or []
    if layout not in LAYOUTS:
        raise UserError(f"--layout {layout!r}: unknown; known: {', '.join(LAYOUTS)}")
    items = scan_mvtec(src)
    if out.exists() and (not out.is_dir() or any(out.iterdir())):
        raise UserError(f"{out}: exists and is not an empty folder; import into a new folder")
    first = cv2.imread(str(items[0].path), cv2.IMREAD_UNCHANGED)
    if bit_depth is None:
        bit_depth = info.get("bit_depth")
        if bit_depth is None:
            if first is not None and first.dtype == np.uint16:
                raise BitDepthError(f"{items[0].path}: a 16-bit file; pass --bit-depth (10, 12, 14 or 16: the "
                                    f"camera's pixel format, e.g. 12 for Mono12)")
            bit_depth = 8
    if bit_depth not in BIT_DEPTHS:
        raise BitDepthError(f"--bit-depth {bit_depth}: choose from {', '.join(map(str, BIT_DEPTHS))}")
    try:
        check_black_level(black_level, bit_depth)
    except ValueError as exc:
        raise UserError(f"--black-level: {exc}") from None
    val = _val_names(items, val_fraction, seed)
    tmp = out.with_name(f"{out.name}.tmp-{os.getpid()}")
    if tmp.exists():
        shutil.rmtree(tmp)
    (tmp / "samples").mkdir(parents=True)
    report = ImportReport(out, bit_depth, layout, 0, 0)
    splits: dict[str, str] = {}
    shape, top, brightest = None, -1, items[0].path
    try:
        for index, item in enumerate(tqdm(items, desc="importing", unit="image", disable=not progress)):
            raw = read_mosaic(item.path, bit_depth)
            if shape is None:
                shape = raw.shape
            elif raw.shape != shape:
                raise UserError(f"{item.path}: {raw.shape[1]}x{raw.shape[0]}, the set's first image "
                                f"{items[0].path.name} is {shape[1]}x{shape[0]}; one set, one frame size")
            if int(raw.max()) > top:
                top, brightest = int(raw.max()), item.path
            split = "val" if item.path in val else item.split
            defect = item.mask is not None and read_mask(item.mask, raw.shape)
            later = []
            for k in range(1, len(segments)):  # the part's other frames, one per dome segment
                path = later_frame(src, item.path.relative_to(src), k)
                if not path.is_file():
                    raise UserError(f"{path}: missing; {src / INFO_FILE} names {len(segments)} dome segments, so "
                                    f"each part has {len(segments)} frames")
                later.append(read_mosaic(path, bit_depth))
                if later[-1].shape != raw.shape:
                    raise UserError(f"{path}: {later[-1].shape[1]}x{later[-1].shape[0]}, its part's first frame "
                                    f"{item.path.name} is {raw.shape[1]}x{raw.shape[0]}")
            sample = Sample(index, raw, {}, item.label, split, segment_raws=(raw, *later) if later else ())
            if item.label == 0:
                sample.defect_mask = np.zeros(raw.shape, bool)  # a good part's mask is known: empty
            elif item.mask is not None:
                sample.defect_mask = defect
                report.n_defect_masks += 1
            if item.object_mask is not None:
                sample.object_mask = read_mask(item.object_mask, raw.shape)
                report.n_object_masks += 1
            sample.params = {"index": index, "split": split, "label": item.label,
                             "defect": {"type": item.defect_type} if item.label else None,
                             "source": {"file": str(item.path.relative_to(src)),
                                        "mask": str(item.mask.relative_to(src)) if item.mask else None}}
            write_sample(tmp, sample)
            splits[str(index)] = split
            report.counts.setdefault(split, Counter())[item.defect_type] += 1
            report.n_defective += item.label
            report.val_from_train += item.path in val
        if not allow_dark:
            check_not_smaller(bit_depth, top, brightest)
        assert shape is not None
        report.height, report.width = shape
        if defect_map is not None and defect_map.shape != shape:
            raise UserError(f"--defect-pixels {defect_pixels}: a {defect_map.shape[1]}x{defect_map.shape[0]} map for "
                            f"{shape[1]}x{shape[0]} frames: a map is made for one region of interest")
        manifest = {"format": FORMAT, "version": VERSION, "convention_version": CONVENTION_VERSION,
                    "width": shape[1], "height": shape[0], "layout": layout, "bit_depth": bit_depth,
                    "count": len(items), "split_rule": FOLDER_SPLIT_RULE, "sample_splits": splits,
                    "config": {"dome_segments": segments} if segments else {},
                    "source": {"format": "mvtec", "path": str(src.resolve()),
                                             "val_fraction": val_fraction if val else 0.0, "seed": seed,
                                             "defect_masks": report.n_defect_masks,
                                             "object_masks": report.n_object_masks}}
        if defect_map is not None:
            shutil.copyfile(defect_pixels, tmp / DEFECT_PIXELS_FILE)
            manifest["defect_pixels"] = DEFECT_PIXELS_FILE
        if black_level:
            manifest["black_level"] = black_level
        (tmp / "manifest.json").write_text(json.dumps(manifest, indent=1))
        out.parent.mkdir(parents=True, exist_ok=True)
        if out.is_dir():
            out.rmdir()  # empty (checked above)
        os.rename(tmp, out)
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)
    report.counts = {k: dict(v) for k, v in report.counts.items()}
    return report


@dataclass
class ExportReport:
    out: Path
    counts: dict[str, int]
    moved_to_test: int

    def describe(self) -> str:
        moved = (f"; {self.moved_to_test} defective train samples went to test/ (MVTec's train/ is good parts only)"
                 if self.moved_to_test else "")
        return f"exported {sum(self.counts.values())} samples to {self.out} (" + ", ".join(
            f"{k}: {v}" for k, v in self.counts.items()) + f"){moved}"


def export_mvtec(data: str | Path, out: str | Path, object_masks: bool = True, progress: bool = True
                 ) -> ExportReport:
    """Write the set ``data`` in the MVTec AD layout under ``out``: each sample as ``<split>/<good|type>/<index>.png``
    (raw mosaic, codes unchanged), defect masks as ``ground_truth/<type>/<index>_mask.png`` (0/255), object masks
    (``object_masks=True``, when the set has them) under ``object_masks/``, and ``polar_ano.json`` (bit depth,
    layout, source; the set's black level and defect pixel map, when it has them). The val split goes to ``val/``;
    defective train samples to ``test/``. A set with a frame per
    dome segment writes each part's later frames under ``frame-K/`` and its segments in ``polar_ano.json``."""
    from tqdm import tqdm

    ds = open_dataset(data)
    out = Path(out)
    if out.exists() and any(out.iterdir()):
        raise UserError(f"{out}: exists and is not empty; export into a new folder")
    black_level = set_black_level(data, ds.manifest)
    has_map = set_defect_pixels(data, ds.manifest) is not None
    counts: Counter[str] = Counter()
    moved = 0
    for i in tqdm(ds.indices(), desc="exporting", unit="sample", disable=not progress):
        s = ds.load(i)
        split = ds.split(i)
        if split == "train" and s.label:
            split, moved = "test", moved + 1
        kind = (s.params.get("defect") or {}).get("type", "defect") if s.label else "good"
        name = f"{i:06d}"
        _write(out / split / kind / f"{name}.png", s.raw)
        for k, later in enumerate(s.raws[1:], 1):
            _write(later_frame(out, Path(split) / kind / f"{name}.png", k), later)
        if s.label and s.defect_mask is not None:
            _write(out / "ground_truth" / kind / f"{name}_mask.png", s.defect_mask.astype(np.uint8) * 255)
        if object_masks and s.object_mask is not None:
            _write(out / "object_masks" / split / kind / f"{name}_object.png", s.object_mask.astype(np.uint8) * 255)
        counts[split] += 1
    if has_map:
        shutil.copyfile(Path(data) / ds.manifest["defect_pixels"], out / DEFECT_PIXELS_FILE)
    (out / INFO_FILE).write_text(json.dumps({
        "bit_depth": ds.manifest.get("bit_depth") or 8, "layout": ds.manifest.get("layout", "imx250mzr"),
        **({"dome_segments": list(ds.dome_segments)} if ds.dome_segments else {}),
        **({"black_level": black_level} if black_level else {}),
        **({"defect_pixels": DEFECT_PIXELS_FILE} if has_map else {}),
        "source": str(Path(data).resolve()), "note": "raw polarizer mosaics; codes of bit_depth bits"}, indent=1))
    return ExportReport(out, dict(counts), moved)


def _write(path: Path, image: np.ndarray) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    if not cv2.imwrite(str(path), image):
        raise UserError(f"could not write {path}")
