"""Clusters of good parts by appearance (``model.draem.appearance_clusters``, ``VariationModel``'s ``clusters``):
two kinds of good part on one line each get their own spread, so a faint defect where only the other kind varies is
seen; the clusters survive a model file, a file whose cluster buffers disagree is refused, and too few parts fit
none."""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np
import pytest
import torch

from model.draem import appearance_clusters
from model.draem.checkpoint import load_checkpoint, save_checkpoint
from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.draem.errors import CheckpointError
from model.draem.variation import VariationModel
from model.draem.with_variation import add_variation
from tests.model.test_variation import H, W, parts


def two_kinds(x: torch.Tensor, seed: int, kind: int | None = None, faint_defect: bool = False) -> torch.Tensor:
    """Good parts of two kinds, as a part's yaw may or may not catch a stray light: kind 0 has a bright lobe on its
    left end with a mottle that differs from part to part (a glint on a rough finish), kind 1 has neither (``kind``
    None: alternating). ``faint_defect``: a part with a faint dark spot (-25 % intensity, 2 px) where kind 0 is
    mottled."""
    rng = np.random.default_rng(seed)
    yy, xx = np.mgrid[0:H, 0:W].astype(np.float32)
    lobe = np.exp(-((yy - H / 2) ** 2 + (xx - W / 2 + 16) ** 2) / 40.0)
    out = x.clone()
    for i in range(len(out)):
        k = i % 2 if kind is None else kind
        mottle = cv2.GaussianBlur(rng.standard_normal((H, W)).astype(np.float32), (0, 0), 1.0)
        gain = np.exp((k == 0) * lobe * (1.0 + 0.3 * mottle))
        if faint_defect:
            gain = gain * (1 - 0.25 * np.exp(-((yy - H / 2) ** 2 + (xx - W / 2 + 16) ** 2) / 4.0))
        out[i, 0] *= torch.from_numpy(gain.astype(np.float32))
    return out


def test_kmeans_finds_separate_groups_and_group_merges_small_clusters_and_needs_enough_parts() -> None:
    rng = np.random.default_rng(0)
    points = np.concatenate([rng.normal(0, 0.1, (60, 3)), rng.normal(5, 0.1, (60, 3)), [[10.0, 10.0, 10.0]]])
    centres, labels = appearance_clusters.kmeans(points, 3)
    assert len(set(labels[:60])) == 1 and len(set(labels[60:120])) == 1 and len(set(labels)) == 3
    again = appearance_clusters.kmeans(points, 3)
    assert np.array_equal(again[1], labels)  # deterministic
    found = appearance_clusters.group(points, 3)  # the lone point's cluster is below MIN_CLUSTER_PARTS: merged
    assert found is not None
    centres, _, labels = found
    assert len(centres) == 2 and np.bincount(labels).min() >= appearance_clusters.MIN_CLUSTER_PARTS
    assert appearance_clusters.group(points[:60], 8) is None  # one cluster per 40 parts: 60 parts make one, none
    mean, scale = appearance_clusters.residual_stats(np.zeros((5, 2, 7)))
    assert not mean.any() and bool((scale == appearance_clusters.SCALE_FLOOR).all())


def test_a_part_is_weighed_against_the_clusters_near_it_and_a_nan_part_against_one() -> None:
    centres = np.array([[0.0, 0.0], [1.0, 0.0], [10.0, 0.0]])
    w = appearance_clusters.weights(centres, np.array([0.5, 0.0]))
    assert w[0] == pytest.approx(0.5) and w[1] == pytest.approx(0.5) and w[2] == 0.0  # halfway; the far one left out
    assert appearance_clusters.weights(centres, np.array([9.9, 0.0]))[2] > 0.99
    assert appearance_clusters.weights(centres, np.array([np.nan, 0.0])).sum() == 1.0
    mean, scale = appearance_clusters.blend(np.array([0.5, 0.5]), [(np.zeros(3), np.full(3, 1.0)),
                                                                    (np.full(3, 2.0), np.full(3, 7.0))])
    assert np.allclose(mean, 1.0) and np.allclose(scale, 5.0)  # sqrt((1 + 49) / 2)


def test_two_kinds_of_good_part_each_judged_within_its_own_cluster_show_a_faint_defect_the_plain_fit_misses(
        tmp_path: Path) -> None:
    """One global spread per pixel serves both kinds: where kind 0 is mottled, kind 1's faint defect hides in
    kind 0's spread. Clustered, kind 1 is judged against kind 1's spread there, and the defect stands out."""
    good = two_kinds(parts(120, 0), 10)
    plain, clustered = (VariationModel(4, (H, W), intensity=0) for _ in range(2))
    plain.fit(good, good[:, 0] > 0.15)
    signed = clustered.fit(good, good[:, 0] > 0.15, clusters=4)
    assert clustered.clusters >= 2 and plain.clusters == 0 and signed.shape == (120, 4, H, W)
    assert np.isfinite(signed).all()
    test_good = two_kinds(parts(30, 1), 11, kind=1)
    test_bad = two_kinds(parts(30, 2), 12, kind=1, faint_defect=True)

    def auroc(vm: VariationModel) -> float:
        g, b = vm.zmaps(test_good)[1].numpy(), vm.zmaps(test_bad)[1].numpy()
        return float((b[:, None] > g[None]).mean())

    assert auroc(clustered) > 0.95 > 0.8 > auroc(plain)
    # both kinds' good parts still score as good parts (the clusters did not make the other kind look defective)
    other_kind = clustered.zmaps(two_kinds(parts(30, 3), 13, kind=0))[1]
    assert float(other_kind.median()) < 2 * float(clustered.zmaps(test_good)[1].median()) + 0.5
    clustered.fit(good[:60], good[:60, 0] > 0.15)  # a refit keeps the model's own count; 60 parts make none
    assert clustered.clusters == 0


def test_a_clustered_model_survives_its_file_and_a_file_whose_clusters_disagree_is_refused(tmp_path: Path) -> None:
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp", "aolp"), "fused", 32, "band"))
    det.init_weights(torch.Generator().manual_seed(0))
    det.eval()
    good = two_kinds(parts(100, 0), 10)
    with_var = add_variation(det, good, None, two_kinds(parts(10, 3), 13), clusters=3)
    assert with_var.variation is not None and with_var.variation.clusters >= 2
    path = tmp_path / "clustered"
    save_checkpoint(path, with_var, threshold=0.5, threshold_rule="test")
    loaded = load_checkpoint(path).detector
    assert loaded.variation is not None and loaded.variation.clusters == with_var.variation.clusters
    assert loaded.variation.cluster_mean.dtype == torch.float16
    x = two_kinds(parts(6, 5), 15, kind=1, faint_defect=True)
    assert torch.equal(loaded.predict(x).score, with_var.predict(x).score)
    pt = path.with_suffix(".pt")
    state = torch.load(pt, weights_only=True)
    state["variation.cluster_scale"] = state["variation.cluster_scale"][:, :, :-1]
    torch.save(state, pt)
    with pytest.raises(CheckpointError, match=r"clustered\.pt: variation model: cluster_scale has shape"):
        load_checkpoint(path, verify_hash=False)
