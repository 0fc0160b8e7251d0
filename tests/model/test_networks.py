import pytest
import torch

from model.draem.config import PRIOR_CHANNELS, ModelConfig, NetworkConfig
from model.draem.errors import ModelError
from model.draem.networks import Draem, DraemEvalOutput, DraemTrainOutput, count_parameters


def test_paper_parameter_count_matches_published():
    # construct on the meta device: 97 M parameters without allocating them
    with torch.device("meta"):
        net = Draem(NetworkConfig(3, 128, 64, 256))
    assert round(count_parameters(net.reconstructive) / 1e6, 1) == 69.0
    assert round(count_parameters(net.discriminative) / 1e6, 1) == 28.4


def test_train_and_eval_outputs_are_typed_and_shaped():
    net = Draem(NetworkConfig(2, 8, 4, 64))
    x = torch.randn(2, 2, 64, 64)
    out = net(x)
    assert isinstance(out, DraemTrainOutput)
    assert out.reconstruction.shape == (2, 2, 64, 64) and out.logits.shape == (2, 2, 64, 64)
    net.eval()
    with torch.no_grad():
        ev = net(x)
    assert isinstance(ev, DraemEvalOutput) and ev.anomaly_map.shape == (2, 64, 64)
    assert float(ev.anomaly_map.min()) >= 0 and float(ev.anomaly_map.max()) <= 1
    with pytest.raises(ValueError, match=r"\(N, 2, H, W\)"):
        net(torch.randn(1, 3, 64, 64))


def test_config_channels_and_presets():
    cfg = ModelConfig.from_preset("paper", "intensity,dolp,aolp,normal", "fused")
    assert cfg.in_channels == sum(PRIOR_CHANNELS[p] for p in cfg.priors) == 7
    assert (cfg.reconstructive_width, cfg.discriminative_width, cfg.input_size_px) == (128, 64, 256)
    assert cfg.score_window == 21
    ens = ModelConfig.from_preset("fast", ("aolp", "normal"))
    assert {k: v.in_channels for k, v in ens.networks().items()} == {"aolp": 2, "normal": 3}
    with pytest.raises(ModelError, match="unknown"):
        ModelConfig.from_preset("fast", ("intensity", "colour"))
    # the tilt priors need their dome segments; the sidecar keeps one-frame models as they were
    pair = ModelConfig.from_preset("fast", "intensity,tilt_x", "fused", dome_segments=(180, 0))
    assert pair.in_channels == 2 and pair.dome_segments == (180.0, 0.0)
    assert ModelConfig.from_dict(pair.to_dict()) == pair and pair.to_dict()["dome_segments"] == [180.0, 0.0]
    assert "dome_segments" not in cfg.to_dict() and ModelConfig.from_dict(cfg.to_dict()) == cfg
    with pytest.raises(ModelError, match="tilt_y needs frames at 90 and 270 deg"):
        ModelConfig.from_preset("fast", "intensity,tilt_y", dome_segments=(0, 180))
    with pytest.raises(ModelError, match="normal prior"):
        ModelConfig.from_preset("fast", "intensity,normal", dome_segments=(0, 180))
    with pytest.raises(ModelError, match="multiple of 32"):
        ModelConfig.from_preset("fast", ("dolp",), input_size_px=100)


def test_lean_preset_costs_a_fraction_of_fast():
    # the lean preset's note promises ~2.5x fewer FLOPs than fast for the same input
    from torch.utils.flop_counter import FlopCounterMode

    def gflop(preset: str) -> float:
        cfg = ModelConfig.from_preset(preset, "intensity,aolp", "fused")
        with torch.device("meta"):
            net = Draem(cfg.networks()["fused"]).eval()
            x = torch.empty(1, cfg.in_channels, cfg.input_size_px, cfg.input_size_px)
        with FlopCounterMode(display=False) as fc, torch.no_grad():
            net(x)
        return fc.get_total_flops() / 1e9

    fast, lean = gflop("fast"), gflop("lean")
    assert ModelConfig.from_preset("lean").input_size_px == ModelConfig.from_preset("fast").input_size_px
    assert 2.2 < fast / lean < 2.8
