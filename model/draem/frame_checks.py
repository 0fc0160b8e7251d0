"""The variation model's frame checks by name, and what its own renders give: torch-free, so the station's log,
report and viewer read them without loading the model.

A frame check describes the frame rather than a defect (``model.draem.variation``, module docstring: highlights,
noise): ``highlight_fraction`` is the share of the part region hidden as a highlight (0-1), ``noise_level`` the frame's
median z against a good part's (about 1 on the model's own line; the z map is divided by it where it is above 1)."""

FRAME_CHECKS = ("highlight_fraction", "noise_level")
"""``VariationOutput`` fields that say what the frame's rules found; the station logs them per inspection."""

OWN_RENDERS_NOISE_LEVEL_MAX = 1.38
"""Highest ``noise_level`` of a good part of the shipped model's own validation and held-out renders (16 spp):
a line whose median lies above it is noisier than the renders (module docstring of variation: noise)."""
