"""Demosaic + priors on full-resolution mosaics: frames/s and error per method, against polanalyser."""

from __future__ import annotations

import argparse


def add_arguments(p: argparse.ArgumentParser) -> None:
    pass


def run(args: argparse.Namespace) -> int:
    raise NotImplementedError
