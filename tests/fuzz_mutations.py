"""Seeded damage to glTF binaries (GLB/VRM): JSON fields replaced by junk or removed, a byte flipped.

Shared by the CI test (tests/core/test_fuzz_rigs.py) and the larger run of benchmarks/fuzz_rig.py.
"""
from __future__ import annotations

import json
import random
import struct

#: What a damaged field becomes.
JUNK = [None, "x", -1, 10**9, 1.5, [], {}, [1, "a"], {"a": 1}, True, [[0]], "0"]


def split(b: bytes) -> tuple[dict, bytes]:
    """A GLB's JSON chunk (parsed) and the bytes after it."""
    n = struct.unpack_from("<I", b, 12)[0]
    return json.loads(b[20:20 + n]), b[20 + n:]


def join(gl: dict, rest: bytes) -> bytes:
    """A GLB from its JSON and the bytes after the JSON chunk (:func:`split`'s inverse)."""
    j = json.dumps(gl).encode()
    j += b" " * (-len(j) % 4)
    body = struct.pack("<II", len(j), 0x4E4F534A) + j + rest
    return b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body


def _paths(o, p=()):
    yield p
    if isinstance(o, dict):
        for k, v in o.items():
            yield from _paths(v, p + (k,))
    elif isinstance(o, list):
        for i, v in enumerate(o[:50]):
            yield from _paths(v, p + (i,))


def mutate(gl: dict, rng: random.Random) -> dict:
    """``gl`` with one to three fields replaced by :data:`JUNK`, removed, or an integer doubled (in place)."""
    ps = [p for p in _paths(gl) if p]
    for _ in range(rng.randint(1, 3)):
        p = rng.choice(ps)
        o = gl
        try:
            for k in p[:-1]:
                o = o[k]
            r = rng.random()
            if r < 0.7:
                o[p[-1]] = rng.choice(JUNK)
            elif isinstance(o, dict):
                del o[p[-1]]
            else:
                o[p[-1]] = o[p[-1]] * 2 if isinstance(o[p[-1]], int) else None
        except (KeyError, IndexError, TypeError):
            pass  # an earlier change removed the path
    return gl


def damaged(base: bytes, rng: random.Random) -> bytes:
    """``base`` (a GLB) with its JSON mutated and, one case in five, a byte changed."""
    gl, rest = split(base)
    data = join(mutate(gl, rng), rest)
    if rng.random() < 0.2:
        b = bytearray(data)
        b[rng.randrange(len(b))] = rng.randrange(256)
        data = bytes(b)
    return data
