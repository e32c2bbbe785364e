"""The pinned floating-point paths under which byte records are made and checked (text2anim.reproducible)."""
from __future__ import annotations

import subprocess
import sys

import pytest

from text2anim import reproducible


def _run(code: str) -> subprocess.CompletedProcess:
    env = {k: v for k, v in __import__("os").environ.items()
           if k not in ("NPY_DISABLE_CPU_FEATURES", "OPENBLAS_CORETYPE")}
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120)


@pytest.mark.skipif(not reproducible.has_avx2(),
                    reason="pinning applies to x86-64 machines with AVX2 only")
def test_a_fresh_interpreter_pinned_runs_numpy_without_avx512_kernels():
    out = _run("from text2anim import reproducible; print(reproducible.pin());"
               "import numpy as np; from numpy._core import _multiarray_umath as m;"
               # the dispatch targets above AVX2 that are on: numpy 2.4 dispatches on X86_V4/AVX512_ICL/AVX512_SPR
               # and still reports the CPU's own sub-features (AVX512F...) as present when they are disabled
               "print([k for k in getattr(m, '__cpu_dispatch__', m.__cpu_features__) "
               "if m.__cpu_features__.get(k) and k.startswith(('AVX512', 'X86_V4'))])")
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["True", "[]"]


def test_pinning_after_numpy_is_imported_is_refused():
    out = _run("import numpy; from text2anim import reproducible; reproducible.pin()")
    assert out.returncode != 0 and "before numpy is imported" in out.stderr
