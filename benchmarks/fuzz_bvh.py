"""Fuzz the BVH reader with mutated CMU files: only BVHError, never over 2 s, never over 500 MB.

    python benchmarks/fuzz_bvh.py [--cases 3060] [--seed 0] [--cmu ../shared/mocap/cmu]

Every case is one real CMU file (``../shared/mocap/cmu``) damaged by one mutation, chosen in
turn from the kinds below, and parsed by :func:`text2anim.core.parse_bvh`. Per case the wall
time, the CPU time and the peak of traced memory (``tracemalloc``, which sees numpy's arrays;
a case over 2 s under it is timed again without it) are measured. The table has one row per
kind; the last row is the total, and the script exits 1 if any case raised something other than
``BVHError``, took over 2 s or traced over 500 MB.

Kinds (the issue 9 cases among them: deep nesting, huge joint counts, denormal frame time,
non-finite and absurd channel values):

- ``truncate``: cut at a random character;
- ``token``: one token replaced by a hostile one (keywords, braces, nan, 1e999, ...);
- ``value``: one frame value replaced by an absurd or non-finite number (1e308, 1e-320, 400 digits);
- ``frame_time``: ``Frame Time`` set to a denormal, zero, negative, huge or non-numeric value;
- ``frames``: ``Frames`` set to a wrong, negative or huge count;
- ``lines``: up to five lines deleted, duplicated or swapped;
- ``bytes``: a few characters replaced by random code points (NUL, controls, non-ASCII);
- ``deep``: a chain of 1,000-3,000 nested joints (no channels) inserted under the root;
- ``wide``: 20,000-100,000 sibling joints inserted under the root;
- ``names``: a duplicate joint name or a second ROOT.

Then (unless ``--no-sizes``) the files at the limits (issue 41), each through the real CLI (``info``,
``metrics``, ``convert``, ``db import``) in a child process, held to the bounds of
``bounded_runs.py`` (no traceback, 10 s, 1 GB peak resident, no raw control character printed): one
63 MB token of ESC bytes, 63 MB of one letter, 60 MB of newlines, exactly 5,000,000 joint-frames of six
channels each (60 MB), a 9,990-joint chain.
"""
from __future__ import annotations

import argparse
import random
import resource
import signal
import sys
import time
import tracemalloc
from collections import defaultdict
from pathlib import Path

from bounded_runs import table, text2anim
from text2anim.core import BVHError, parse_bvh

REPO = Path(__file__).resolve().parents[1]
DEFAULT_CMU = REPO.parent / "shared" / "mocap" / "cmu"
LIMIT_S = 2.0
LIMIT_MB = 500.0
HANG_S = 30  # a case still running after this is stopped and counted as a failure

NASTY = ["", "{", "}", "ROOT", "JOINT", "End", "Site", "MOTION", "Frames:", "CHANNELS", "OFFSET", "HIERARCHY",
         "nan", "inf", "-inf", "1e999", "-1e999", "1e-320", "7", "-1", "0", "6", "3", "0.5.5", "Xrotation",
         "Qrotation", "\t", "\n", "\x00", "ジョイント", "9" * 400]
ABSURD = ["1e308", "-1e308", "1e-320", "4.9e-324", "9e99", "-3e7", "nan", "NaN", "inf", "-inf", "1e400",
          "9" * 400, "0x10", "1_000", "--1", "１２"]
FRAME_TIMES = ["1e-320", "4.9e-324", "1e-308", "2.2e-308", "0", "-0.0083333", "1e300", "inf", "nan", "9" * 400,
               "0.0083333x", "", "1e-6", "3601"]


class Hang(Exception):
    pass


def _on_alarm(signum, frame):
    raise Hang()


# -------------------------------------------------------------------------------- mutations
def _split(text: str) -> tuple[list[str], int]:
    lines = text.split("\n")
    motion = next(i for i, ln in enumerate(lines) if ln.strip().upper() == "MOTION")
    return lines, motion


def m_truncate(text, rng):
    return text[:rng.randrange(len(text))]


def m_token(text, rng):
    tokens = text.split(" ")
    tokens[rng.randrange(len(tokens))] = rng.choice(NASTY)
    return " ".join(tokens)


def m_value(text, rng):
    lines, motion = _split(text)
    k = rng.randrange(motion + 3, len(lines) - 1)
    vals = lines[k].split()
    if vals:
        vals[rng.randrange(len(vals))] = rng.choice(ABSURD)
    lines[k] = " ".join(vals)
    return "\n".join(lines)


def m_frame_time(text, rng):
    lines, motion = _split(text)
    lines[motion + 2] = "Frame Time: " + rng.choice(FRAME_TIMES)
    return "\n".join(lines)


def m_frames(text, rng):
    lines, motion = _split(text)
    n = int(lines[motion + 1].split()[-1])
    lines[motion + 1] = "Frames: " + str(rng.choice([n + 1, n - 1, 0, -1, 10**9, 10**18, n * 2, "9" * 400]))
    return "\n".join(lines)


def m_lines(text, rng):
    lines = text.split("\n")
    a = rng.randrange(len(lines))
    b = min(len(lines), a + rng.randint(1, 5))
    op = rng.choice(["delete", "duplicate", "swap"])
    if op == "delete":
        lines[a:b] = []
    elif op == "duplicate":
        lines[a:a] = lines[a:b]
    else:
        c = rng.randrange(len(lines))
        lines[a], lines[c] = lines[c], lines[a]
    return "\n".join(lines)


def m_bytes(text, rng):
    chars = list(text)
    for _ in range(rng.randint(1, 8)):
        chars[rng.randrange(len(chars))] = chr(rng.choice([0, 1, 7, 27, 127, 0xFEFF, 0x202E, rng.randrange(32, 0x3000)]))
    return "".join(chars)


def _insert_after_root_header(text: str, block: str) -> str:
    """``block`` inserted as children of the root, after its CHANNELS line."""
    lines = text.split("\n")
    k = next(i for i, ln in enumerate(lines) if ln.strip().upper().startswith("CHANNELS"))
    lines[k + 1:k + 1] = [block]
    return "\n".join(lines)


def m_deep(text, rng):
    n = rng.randint(1000, 3000)
    opening = "".join(f"JOINT deep{k}\n{{\nOFFSET 0 0.1 0\nCHANNELS 0\n" for k in range(n))
    return _insert_after_root_header(text, opening + "End Site\n{\nOFFSET 0 0.1 0\n}\n" + "}\n" * n)


def m_wide(text, rng):
    n = rng.randint(20_000, 100_000)
    block = "".join(f"JOINT wide{k}\n{{\nOFFSET 0 0.1 0\nCHANNELS 0\n}}\n" for k in range(n))
    return _insert_after_root_header(text, block)


def m_names(text, rng):
    lines = text.split("\n")
    if rng.random() < 0.5:
        joints = [i for i, ln in enumerate(lines) if ln.strip().upper().startswith("JOINT")]
        a, b = rng.sample(joints, 2)
        lines[b] = lines[b].split("JOINT")[0] + "JOINT " + lines[a].split(None, 1)[1]
        return "\n".join(lines)
    _, motion = _split(text)
    return "\n".join(lines[:motion] + lines[1:motion] + lines[motion:])  # a second ROOT


KINDS = {"truncate": m_truncate, "token": m_token, "value": m_value, "frame_time": m_frame_time,
         "frames": m_frames, "lines": m_lines, "bytes": m_bytes, "deep": m_deep, "wide": m_wide,
         "names": m_names}


# ------------------------------------------------------------------------------- at the limits
def _chain(n: int) -> str:
    s = ["HIERARCHY", "ROOT j0", "{", "OFFSET 0 0 0", "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation"]
    for k in range(1, n):
        s += [f"JOINT j{k}", "{", "OFFSET 0 0.1 0", "CHANNELS 3 Zrotation Xrotation Yrotation"]
    s += ["End Site", "{", "OFFSET 0 0.1 0", "}"] + ["}"] * n + ["MOTION", "Frames: 1", "Frame Time: 0.0333333"]
    return "\n".join(s + [" ".join(["0"] * (6 + 3 * (n - 1)))]) + "\n"


def _six_channels(joint_frames: int, joints: int = 31) -> str:
    chans = "CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation"
    s = ["HIERARCHY", "ROOT Hips", "{", "OFFSET 0 0 0", chans]
    for k in range(1, joints):
        s += [f"JOINT j{k}", "{", "OFFSET 0 -2 0", chans]
    frames = joint_frames // joints
    s += ["End Site", "{", "OFFSET 0 0.1 0", "}"] + ["}"] * joints
    s += ["MOTION", f"Frames: {frames}", "Frame Time: 0.0083333"]
    return "\n".join(s) + "\n" + (" ".join(["0"] * (6 * joints)) + "\n") * frames


def size_runs(tmp: Path) -> list:
    """The files at the limits through the CLI, each command a child process measured by ``bounded_runs``."""
    files = {"63 MB token of ESC": b"\x1b" * 63_000_000, "63 MB of one letter": b"a" * 63_000_000,
             "60 MB of newlines": b"\n" * 60_000_000, "5,000,000 joint-frames": _six_channels(5_000_000).encode(),
             "9,990-joint chain": _chain(9990).encode()}
    runs = []
    for k, (name, data) in enumerate(files.items()):
        path = tmp / f"limit{k}.bvh"
        path.write_bytes(data)
        del data
        runs.append(text2anim(f"{name}: info", "info", path))
        runs.append(text2anim(f"{name}: metrics", "metrics", path))
        runs.append(text2anim(f"{name}: convert", "convert", path, "-o", tmp / "out.bvh"))
        runs.append(text2anim(f"{name}: db import", "db", "import", path, "--verb", "歩く",
                              "--db", f"sqlite:///{tmp / 'm.sqlite'}"))
        path.unlink()
        (tmp / "out.bvh").unlink(missing_ok=True)
    return runs


# ----------------------------------------------------------------------------------- running
def run_case(text: str) -> tuple[str, float, float, float]:
    """Parse once: (outcome, wall s, CPU s, peak MB); outcome is ``ok``, ``BVHError`` or an exception name."""
    tracemalloc.start()
    signal.alarm(HANG_S)
    t0, c0 = time.perf_counter(), time.process_time()
    try:
        parse_bvh(text, source="fuzz", scale="auto")
        outcome = "ok"
    except BVHError:
        outcome = "BVHError"
    except Hang:
        outcome = "hang"
    except Exception as exc:  # noqa: BLE001 - what the fuzz is for
        outcome = type(exc).__name__
    finally:
        signal.alarm(0)
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
    return outcome, wall, cpu, peak / 1e6


def retime(text: str) -> tuple[float, float]:
    """Wall and CPU seconds of one parse without tracemalloc."""
    t0, c0 = time.perf_counter(), time.process_time()
    try:
        parse_bvh(text, source="fuzz", scale="auto")
    except Exception:  # noqa: BLE001 - the outcome was recorded by run_case
        pass
    return time.perf_counter() - t0, time.process_time() - c0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cases", type=int, default=3060)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--cmu", type=Path, default=DEFAULT_CMU)
    ap.add_argument("--no-sizes", action="store_true", help="skip the files at the limits")
    args = ap.parse_args(argv)
    files = sorted(args.cmu.glob("*.bvh"))
    if not files:
        print(f"no CMU files in {args.cmu}", file=sys.stderr)
        return 2
    texts = [f.read_text() for f in files]
    signal.signal(signal.SIGALRM, _on_alarm)
    rows: dict[str, dict] = defaultdict(lambda: defaultdict(float))
    failures: list[str] = []
    names = list(KINDS)
    t_start = time.perf_counter()
    for case in range(args.cases):
        kind = names[case % len(names)]
        k = (case // len(names)) % len(files)
        rng = random.Random(f"{args.seed}:{case}")
        text = KINDS[kind](texts[k], rng)
        outcome, wall, cpu, mb = run_case(text)
        if wall > LIMIT_S:  # tracemalloc's bookkeeping or a busy machine: time it again, untraced
            wall, cpu = retime(text)
        if (case + 1) % 300 == 0:
            print(f"  {case + 1} cases, {time.perf_counter() - t_start:.0f} s", file=sys.stderr, flush=True)
        r = rows[kind]
        r["cases"] += 1
        r[outcome if outcome in ("ok", "BVHError") else "other"] += 1
        r["wall"], r["cpu"], r["mb"] = max(r["wall"], wall), max(r["cpu"], cpu), max(r["mb"], mb)
        r["cpu_sum"] += cpu
        r["slow"] += wall > LIMIT_S
        r["big"] += mb > LIMIT_MB
        if outcome not in ("ok", "BVHError") or wall > LIMIT_S or mb > LIMIT_MB:
            failures.append(f"case {case} ({kind} of {files[k].name}, seed {args.seed}): {outcome}, "
                            f"{wall:.2f} s, {mb:.0f} MB")
    total = defaultdict(float)
    head = (f"{'kind':11} {'cases':>6} {'parsed':>7} {'BVHError':>8} {'other':>6} {'max wall s':>10} "
            f"{'max CPU s':>9} {'mean CPU ms':>11} {'max MB':>7} {'>2 s':>5} {'>500 MB':>7}")
    print(f"BVH fuzz: {args.cases} mutated CMU files ({len(files)} sources), seed {args.seed}")
    print(head)
    print("-" * len(head))

    def line(name, r):
        print(f"{name:11} {int(r['cases']):6d} {int(r['ok']):7d} {int(r['BVHError']):8d} {int(r['other']):6d} "
              f"{r['wall']:10.3f} {r['cpu']:9.3f} {1000 * r['cpu_sum'] / max(r['cases'], 1):11.1f} "
              f"{r['mb']:7.1f} {int(r['slow']):5d} {int(r['big']):7d}")

    for name in names:
        r = rows[name]
        line(name, r)
        for key in ("cases", "ok", "BVHError", "other", "cpu_sum", "slow", "big"):
            total[key] += r[key]
        for key in ("wall", "cpu", "mb"):
            total[key] = max(total[key], r[key])
    print("-" * len(head))
    line("total", total)
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"run: {time.perf_counter() - t_start:.0f} s wall; process peak RSS {rss:.0f} MB")
    for f in failures[:20]:
        print("FAIL", f)
    if not args.no_sizes:
        import tempfile

        with tempfile.TemporaryDirectory() as tmp:
            runs = size_runs(Path(tmp))
        print("\nFiles at the limits, through the CLI:")
        print(table(runs))
        failures += [f"{r.case}: {'; '.join(r.failures)}" for r in runs if r.failures]
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
