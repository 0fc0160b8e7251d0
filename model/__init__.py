"""Polar-Ano model: the polarization priors core (``model.priors``, numpy only) and the detector.

``model`` imports nothing from ``station``, ``drivers`` or ``sim``.
"""
