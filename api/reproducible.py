"""Floating-point paths pinned so that recorded bytes compare across x86 machines.

numpy picks its SIMD kernels (``sin``, ``exp``, ``arctan2``…) and OpenBLAS its matrix kernels by
the CPU it runs on; an AVX-512 machine and an AVX2 machine then differ in the last bits of some
results, and so in the bytes of a BVH. The same machine always gives the same bytes. The records
that compare bytes across machines (the goldens of ``tests/test_golden.py``, the shipped library
arrays that a fresh build must reproduce) are made and checked with the paths pinned to the AVX2
level that every x86-64 machine of the last decade has: :func:`pin` must run before numpy is
first imported (``tests/conftest.py`` and the library's build scripts call it first).
"""
from __future__ import annotations

import os
import platform
import sys
from pathlib import Path

#: numpy's dispatch groups above AVX2, by the names of numpy 2.4 (``X86_V4``…) and before (``AVX512F``…).
ABOVE_AVX2 = "X86_V4 AVX512_ICL AVX512_SPR AVX512F AVX512CD AVX512_SKX AVX512_CLX AVX512_CNL AVX512_KNL AVX512_KNM"


def has_avx2() -> bool:
    """Whether this CPU reports AVX2 (Linux: /proc/cpuinfo)."""
    try:
        return " avx2" in Path("/proc/cpuinfo").read_text(encoding="ascii", errors="replace")
    except OSError:
        return False


def pin() -> bool:
    """Pin numpy and OpenBLAS to their AVX2 kernels on an x86-64 machine that has AVX2.

    Returns whether the paths are pinned. Raises ``RuntimeError`` when numpy is already
    imported unpinned (too late to pin); a second call after a first is a no-op, and
    variables the caller set beforehand are kept.
    """
    if platform.machine().lower() not in ("x86_64", "amd64") or not has_avx2():
        return False
    if "numpy" in sys.modules:
        if "NPY_DISABLE_CPU_FEATURES" in os.environ and "OPENBLAS_CORETYPE" in os.environ:
            return True
        raise RuntimeError("reproducible.pin() must run before numpy is imported")
    os.environ.setdefault("NPY_DISABLE_CPU_FEATURES", ABOVE_AVX2)
    os.environ.setdefault("OPENBLAS_CORETYPE", "Haswell")
    return True
