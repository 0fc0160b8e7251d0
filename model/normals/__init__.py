"""Surface normals from polarization: the physics baseline (``sfp``: diffuse shape from polarization, numpy only)
and a learned estimator (``net``, ``train``: a small U-Net trained on rendered ground-truth normals; torch).

Conventions: normals and viewing directions are unit vectors in camera coordinates, x image right, y image up,
z toward the camera (``model.draem.config``, ``sim.scene.camera_axes``); AoLP as in ``model.priors.conventions``.
Importing this package or ``model.normals.sfp`` does not import torch. Imports nothing from station, sim or
drivers.
"""
