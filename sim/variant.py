"""Choosing and setting the Mitsuba 3 polarized variant, safely.

Order of preference: ``cuda_ad_mono_polarized`` when a CUDA device is present, ``llvm_ad_mono_polarized`` when
Dr.Jit's LLVM backend is LLVM >= 19, else ``scalar_spectral_polarized`` (about 17x slower). The LLVM check must
run before any render: with LLVM 15 (Debian's default) the first ``mi.render`` aborts the whole process with
``LLVM ERROR: Cannot select ... fminimum`` (exit 134, not catchable), see docs/platform-facts.md. Dr.Jit finds
``libLLVM.so.19.1`` from the ``libllvm19`` package by itself; ``DRJIT_LIBLLVM_PATH`` overrides it.
"""

from __future__ import annotations

import logging
import os

from .errors import SimError

log = logging.getLogger(__name__)

CUDA_VARIANT = "cuda_ad_mono_polarized"
LLVM_VARIANT = "llvm_ad_mono_polarized"
SCALAR_VARIANT = "scalar_spectral_polarized"
POLARIZED_VARIANTS = (CUDA_VARIANT, LLVM_VARIANT, SCALAR_VARIANT)
MIN_LLVM = (19, 0, 0)
ENV_VARIANT = "POLAR_ANO_MI_VARIANT"
"""Environment override of the choice (e.g. to force the scalar fallback in a test); still checked."""

_chosen: str | None = None


def llvm_ok() -> tuple[bool, str]:
    """(usable, reason): whether Dr.Jit's LLVM backend exists and is LLVM >= 19. Touches no Mitsuba variant."""
    import drjit as dr

    if not dr.has_backend(dr.JitBackend.LLVM):
        return False, "Dr.Jit found no LLVM library (install libllvm19 or set DRJIT_LIBLLVM_PATH)"
    version = tuple(dr.detail.llvm_version())
    if version < MIN_LLVM:
        return False, f"LLVM {'.'.join(map(str, version))} is too old (need >= 19; install libllvm19)"
    return True, f"LLVM {'.'.join(map(str, version))}"


def cuda_ok() -> tuple[bool, str]:
    """(usable, reason): whether Dr.Jit sees a CUDA device."""
    import drjit as dr

    try:
        ok = bool(dr.has_backend(dr.JitBackend.CUDA))
    except Exception as exc:  # a broken driver raises instead of answering no
        return False, f"CUDA backend check failed: {exc}"
    return ok, "CUDA device present" if ok else "no CUDA device"


def available_variants() -> list[str]:
    """The polarized variants this machine can render with, best first."""
    import mitsuba as mi

    built = set(mi.variants())
    out = []
    if CUDA_VARIANT in built and cuda_ok()[0]:
        out.append(CUDA_VARIANT)
    if LLVM_VARIANT in built and llvm_ok()[0]:
        out.append(LLVM_VARIANT)
    if SCALAR_VARIANT in built:
        out.append(SCALAR_VARIANT)
    return out


def choose_variant(prefer: str | None = None) -> str:
    """The variant to render with: ``prefer`` (or ``$POLAR_ANO_MI_VARIANT``) if given and usable, else the best
    available. Raises SimError if the requested one cannot run here or none is available."""
    prefer = prefer or os.environ.get(ENV_VARIANT) or None
    usable = available_variants()
    if prefer:
        if prefer not in POLARIZED_VARIANTS:
            raise SimError(f"Mitsuba variant {prefer!r} is not one of {', '.join(POLARIZED_VARIANTS)}")
        if prefer not in usable:
            reason = llvm_ok()[1] if prefer == LLVM_VARIANT else cuda_ok()[1]
            raise SimError(f"Mitsuba variant {prefer!r} cannot run here: {reason}")
        return prefer
    if not usable:
        raise SimError("no polarized Mitsuba variant is available in this mitsuba build")
    return usable[0]


def set_variant(prefer: str | None = None) -> str:
    """Choose (see ``choose_variant``), set it in Mitsuba, log the choice once, and return its name."""
    global _chosen
    import mitsuba as mi

    variant = choose_variant(prefer)
    if mi.variant() != variant:
        mi.set_variant(variant)
    if _chosen != variant:
        why = {CUDA_VARIANT: cuda_ok, LLVM_VARIANT: llvm_ok}.get(variant)
        log.info("Mitsuba variant %s (%s)", variant, why()[1] if why else "fallback: no usable LLVM >= 19 or CUDA")
        _chosen = variant
    return variant
