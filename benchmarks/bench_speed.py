"""Every row of issue 15's speed table in one run: CPU time beside wall time, peers interleaved.

    python benchmarks/bench_speed.py [--repeat 5] [--db-sizes 1000 100000] [--queries 300] [--quick]

The machine is shared (2 cores, many processes): read the CPU column (process
CPU time, ``time.process_time``; for whole processes the child's user+system
time from ``getrusage``) and the ratios; wall times are printed beside them
and vary with the load (the load average is printed at start and end).

Rows (goal in brackets, from the issue):

- text -> BVH, 3 motions, warm API (``animate`` + ``format_bvh``): the database given by URL as the README shows
  it, then an open ``MotionDB``, optimal and constraint [<= 30 ms]; the same sentence again is joins a warm process
  has laid and finished before (``optimal.join.KEPT_JOINS``, ``joinpass.KEPT_FINISHED``, ``hipspath.KEPT_PATHS``): a
  row beside it forgets them before each call, the cost of a sentence not seen before;
- a ten-sentence story in a warm process (the studio's case), animated again and with a sentence added, CPU
  beside the same with the kept joins forgotten;
- planning: sentences per CPU second, ``text2anim.plan(text, url)``, refusals included [>= 1,000];
- ``text2anim TEXT -o x.bvh``, whole process, seeded database [<= 0.5 s];
- ``text2anim plan TEXT``, whole process [<= 0.3 s];
- peak resident memory of a fresh process animating the seed sentence [<= 100 MB];
- issue 41's long texts (a run, then 3秒後に歩く。 n - 1 times; ``--long 8 16 32``), each in a fresh process: CPU,
  wall, peak memory [a few seconds, well under 1 GB, linear in motions];
- first run on an empty database: a new process opening a new file (create + seed) [<= 1 s];
  whole processes run with their bytecode cached (as installed); the CPU of the first two is split into
  interpreter start-up, the imports of numpy, SQLAlchemy, scipy, fugashi, then the rest (our modules and
  the standard library's rest), each timed as a process that only imports, and the run itself;
- join planning, one transition, built-in clips: ``synthesis.optimal.plan_join`` p95 CPU [<= 1 ms];
- join planning at 120 fps: the largest ``plan_join`` CPU time and the peak of traced memory [<= 20 ms];
- synthesis real-time factor: seconds of animation per CPU second, optimal and constraint, the kept joins forgotten
  before each run [>= 500x];
- DB search: p50/p95 CPU per ``MotionDB.search`` (limit 10) at each size, growth, SQL statements per
  search, searches per motion in one animation [p95 <= 1 ms, growth <= 1.5x, 1 query];
- BVH parse: ours against ``bvh`` and ``bvhio`` (``pip install -e '.[bench]'``), the contenders run in
  turn within each round, so the ratio holds when the load moves [>= 5x the fastest]; twice: to joint
  quaternions ``(T, J, 4)`` + root positions (the goal row) and to the raw channel values ``(T, C)``
  (what each contender does to get there: ``benchmarks/bvh_peers.py``);
- analysis: ``nlp.analyze`` against GiNZA, interleaved, when ``ginza``/``ja_ginza`` are installed.

Medians over ``--repeat`` rounds. The first two blocks use the built-in library in a temporary SQLite file.
"""
from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "benchmarks"))

TEXT3 = "太郎は走って、ボールを蹴る。そして喜ぶ。"
SENTENCES = ["太郎は歩く。", "太郎は走って、ボールを蹴る。", TEXT3, "花子は歩いて、止まる。そして振り向いて、手を振る。",
             "太郎は走って、ボールを蹴る。そして喜ぶ。それから歩いて、座る。"]


def timed(fn):
    """(CPU seconds, wall seconds, result) of one call."""
    c, w = time.process_time(), time.perf_counter()
    out = fn()
    return time.process_time() - c, time.perf_counter() - w, out


def median_timed(fn, repeat: int) -> tuple[float, float]:
    cpu, wall = [], []
    for _ in range(repeat):
        c, w, _ = timed(fn)
        cpu.append(c)
        wall.append(w)
    return statistics.median(cpu), statistics.median(wall)


def child(argv: list[str], env: dict, cwd: str) -> tuple[float, float]:
    """(CPU, wall) seconds of a whole child process (its user + system time)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    w = time.perf_counter()
    proc = subprocess.run(argv, env=env, cwd=cwd, capture_output=True)
    wall = time.perf_counter() - w
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        raise RuntimeError(f"{argv} failed: {proc.stderr.decode()[-2000:]}")
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), wall


ROWS: list[tuple[str, str, str, str]] = []


def row(name: str, cpu: str, wall: str, goal: str) -> None:
    ROWS.append((name, cpu, wall, goal))
    print(f"  {name:52} {cpu:>22} {wall:>22}  {goal}", flush=True)


def ms(s: float) -> str:
    return f"{s * 1000:.1f} ms"


# ----------------------------------------------------------------- pipeline rows
def pipeline_rows(tmp: Path, repeat: int) -> None:
    from text2anim import animate
    from text2anim.motiondb import MotionDB
    from text2anim.pipeline import plan_text
    from text2anim.tracks import build_tracks
    from text2anim.synthesis.optimal import join as optimal  # join_next looks plan_join up there
    from text2anim.synthesis.registry import synthesize_with
    from text2anim.output.bvh_write import format_bvh

    url = f"sqlite:///{tmp}/motions.sqlite"
    # as the README shows the API: the database named by its URL (kept open between calls since issue 43)
    animate(TEXT3, db=url)
    cpu, wall = median_timed(lambda: [format_bvh(m) for m in animate(TEXT3, db=url).motions.values()], repeat)
    row("text -> BVH, 3 motions, warm API, db=URL (optimal)", ms(cpu), ms(wall), "<= 30 ms")
    # a warm process keeps the joins it finished (the studio animates the same joins at every pause in typing):
    # the same sentence with what it kept of its joins forgotten before each call costs what a new sentence does

    def unseen():
        forget_joins()
        return [format_bvh(m) for m in animate(TEXT3, db=url).motions.values()]
    cpu, wall = median_timed(unseen, repeat)
    row("  the same, its joins not seen before (kept joins forgotten)", ms(cpu), ms(wall), "<= 30 ms")
    planning_rate_row(url, repeat)
    story_rows(url, repeat)
    db = MotionDB.open(url)
    animate(TEXT3, db=db)  # warm: analyser, caches
    for blend in ("optimal", "constraint"):
        def run():
            anim = animate(TEXT3, db=db, blend=blend)
            return [format_bvh(m) for m in anim.motions.values()]
        cpu, wall = median_timed(run, repeat)
        row(f"text -> BVH, 3 motions, warm API ({blend})", ms(cpu), ms(wall), "<= 30 ms")

    # searches and SQL statements of one animation's planning, on a database opened afresh: an open SQLite
    # database keeps a plan's answers for the next plan (MotionDB.memoised), which would count none
    from sqlalchemy import event

    warm_db, db = db, MotionDB.open(url)
    statements = [0, 0]  # all (BEGIN included), SELECTs

    def count(conn, cursor, statement, *a):
        statements[0] += 1
        statements[1] += statement.lstrip().upper().startswith("SELECT")
    event.listen(db.engine, "before_cursor_execute", count)
    searches = [0]
    real_search = db.search

    def counting(*a, **k):
        searches[0] += 1
        return real_search(*a, **k)
    db.search = counting  # type: ignore[method-assign]
    planned = plan_text(TEXT3, db)
    del db.search
    event.remove(db.engine, "before_cursor_execute", count)
    n_motions = len(planned.analysis.motions)
    db.close()
    db = warm_db
    row("planning: SELECTs per motion (searches per motion)", f"{statements[1] / n_motions:.1f} SELECT/motion",
        f"{searches[0] / n_motions:.1f} searches, {statements[0] / n_motions:.1f} stmt", "1 query/motion")

    # join planning, per plan_join call
    real_plan = optimal.plan_join
    calls: list[float] = []

    def timed_plan(*a, **k):
        c = time.thread_time()
        out = real_plan(*a, **k)
        calls.append(time.thread_time() - c)
        return out
    optimal.plan_join = timed_plan
    try:
        for _ in range(max(1, repeat // 2)):
            for text in SENTENCES:
                optimal.KEPT_JOINS.clear()  # every join planned (a warm process would take it from those laid)
                animate(text, db=db)
        p50, p95 = np.percentile(calls, [50, 95])
        row(f"join planning, built-in clips ({len(calls)} joins)", f"p50 {ms(p50)} p95 {ms(p95)}", "-", "p95 <= 1 ms")
        calls.clear()
        text2 = SENTENCES[1]
        c, w, _ = timed(lambda: animate(text2, db=db, fps=120.0))
        worst = max(calls) if calls else float("nan")
        optimal.plan_join = real_plan
        optimal.KEPT_JOINS.clear()
        tracemalloc.start()
        animate(text2, db=db, fps=120.0)
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        row("join planning at 120 fps (largest join; peak traced mem)", f"{ms(worst)}; {peak / 2**20:.0f} MB",
            f"whole animate {ms(w)}", "<= 20 ms, O(N0*N1)")
    finally:
        optimal.plan_join = real_plan

    # synthesis real-time factor
    tracks = [build_tracks(plan_text(t, db), db, 30.0) for t in SENTENCES]
    for method in ("optimal", "constraint"):
        seconds = cpu = wall = 0.0
        for tr in tracks:  # each join not seen before: the synthesis' own work
            c, w = median_timed(lambda: forget_joins() or synthesize_with(method, tr, 30.0), max(1, repeat // 2))
            res = synthesize_with(method, tr, 30.0)
            seconds += max(m.duration for m in res.motions.values())
            cpu += c
            wall += w
        row(f"synthesis real-time factor ({method}, {len(tracks)} sentences)", f"{seconds / cpu:.0f}x",
            f"{seconds / wall:.0f}x", ">= 500x")
    db.close()


#: a story of ten sentences, two people (the studio's case: the whole text animated again at every pause in
#: typing), and the sentence typed after it
STORY = ("太郎は走って、ボールを蹴る。そして喜ぶ。花子は歩いて、椅子に座る。それから立ち上がって、手を振る。"
         "太郎はジャンプして、お辞儀をする。花子は走って、止まる。太郎は歩いて、ボールを投げる。花子は踊って、笑う。"
         "太郎は座って、立ち上がる。")
STORY_NEXT = "花子はお辞儀をして、歩く。"


def story_rows(url: str, repeat: int) -> None:
    """A ten-sentence story in a warm process: animated again as it is, and with one sentence added (the
    joins before it as they were); each beside the same text with what the process kept forgotten."""
    from text2anim import animate

    for name, text in (("again", STORY), ("one sentence added", STORY + STORY_NEXT)):
        def warm():
            forget_joins()
            animate(STORY, db=url)  # what the studio animated at the last pause
            c = time.process_time()
            animate(text, db=url)
            return time.process_time() - c

        def cold():
            forget_joins()
            c = time.process_time()
            animate(text, db=url)
            return time.process_time() - c
        w = float(np.median([warm() for _ in range(max(1, repeat // 2))]))
        k = float(np.median([cold() for _ in range(max(1, repeat // 2))]))
        row(f"story of 10 sentences, warm process: {name}", ms(w), f"joins forgotten {ms(k)}", "")


def forget_joins() -> None:
    """Forget what the process kept of the joins it finished (the post-pass's joins and the hips' paths), of the
    joins it planned (the adapted lower bodies) and of the joins it laid (plans and renderings)."""
    from text2anim.synthesis.join import hipspath, joinpass
    from text2anim.synthesis.optimal import adaptation
    from text2anim.synthesis.optimal import join as optimal_join

    joinpass.KEPT_FINISHED.clear()
    hipspath.KEPT_PATHS.clear()
    adaptation.KEPT_ADAPTED.clear()
    optimal_join.KEPT_JOINS.clear()


def planning_rate_row(url: str, repeat: int) -> None:
    """Sentences planned per CPU second, ``text2anim.plan(text, url)`` as the README shows it, over the first
    200 lines of the analysis corpus (refusals included: a refused line costs what it cost to refuse)."""
    import json

    import text2anim

    corpus = REPO / "tests" / "corpus" / "nlp_corpus.jsonl"
    lines = [json.loads(x)["text"] for x in corpus.read_text(encoding="utf-8").splitlines() if x.startswith("{")][:200]
    refused = [0]

    def run():
        refused[0] = 0
        for text in lines:
            try:
                text2anim.plan(text, url)
            except ValueError:
                refused[0] += 1
    run()
    cpu, wall = median_timed(run, max(3, repeat // 2))
    row(f"planning, {len(lines)} corpus lines ({refused[0]} refused), db=URL", f"{len(lines) / cpu:,.0f} /CPU s",
        f"{len(lines) / wall:,.0f} /s", ">= 1,000 /CPU s")
    # the same lines on a database opened afresh each round: nothing asked before is remembered (an open
    # SQLite database keeps each plan's answers for the next while the file is unchanged)
    from text2anim.motiondb import MotionDB

    fresh: list[tuple[float, float]] = []
    for _ in range(max(3, repeat // 2)):
        with MotionDB.open(url) as db:
            c, w, _ = timed(lambda: [_refused(text2anim.plan, text, db) for text in lines])
        fresh.append((c, w))
    cpu, wall = (statistics.median(x[i] for x in fresh) for i in (0, 1))
    row("  the same, first pass on a database opened afresh", f"{len(lines) / cpu:,.0f} /CPU s",
        f"{len(lines) / wall:,.0f} /s", "")


def _refused(plan, text: str, db) -> bool:
    """Whether ``plan(text, db)`` refused the text."""
    try:
        plan(text, db)
    except ValueError:
        return True
    return False


#: prints the process's peak resident memory, KiB: ``VmHWM``, which ``exec`` starts afresh (``ru_maxrss`` keeps
#: the peak of the process that forked it, here the benchmark's own)
PEAK_KIB = "print(next(int(x.split()[1]) for x in open('/proc/self/status') if x.startswith('VmHWM')))"


#: prints the process's resident memory at exit, KiB, as its two kinds: private (``RssAnon``: what the process
#: allocated) and files mapped (``RssFile``: the analyser's dictionary, read in place, and the libraries; shared with
#: every process that maps them, and given back to the page cache under pressure)
SPLIT_KIB = ("print(*(next(int(x.split()[1]) for x in open('/proc/self/status') if x.startswith(k)) "
             "for k in ('RssAnon', 'RssFile')))")


def peak_row(tmp: Path, env: dict) -> None:
    """Peak resident memory of a fresh process animating the seed sentence to BVH (:data:`PEAK_KIB`), and what is
    resident at its end, private and mapped from files (:data:`SPLIT_KIB`)."""
    code = (f"import sys, text2anim\nanim = text2anim.animate(sys.argv[1])\nanim.save_bvh(sys.argv[2])\n"
            f"{SPLIT_KIB}\n{PEAK_KIB}")
    runs = [[int(x) for x in subprocess.run([sys.executable, "-c", code, TEXT3, str(tmp / "peak.bvh")], env=env,
                                            cwd=str(tmp), capture_output=True, text=True,
                                            check=True).stdout.split()[-3:]] for _ in range(3)]
    anon, files, peak = (statistics.median(r[k] for r in runs) / 1024 for k in range(3))
    row("peak memory, seed sentence, fresh process", f"{peak:.0f} MB",
        f"at exit {anon:.0f} MB private, {files:.0f} MB files", "<= 100 MB")


#: issue 41's long text: a run, then (n - 1) times 3秒後に歩く。
def long_text(n: int) -> str:
    return "太郎は走る。" + "3秒後に歩く。" * (n - 1)


def long_rows(tmp: Path, env: dict, sizes: list[int]) -> None:
    """Issue 41's long texts, each animated by the command in a fresh process (``text2anim TEXT -o x.bvh``, as
    ``fuzz_text.py`` runs it): CPU (user + system), wall and peak resident memory."""
    for n in sizes:
        w = time.perf_counter()
        proc = subprocess.Popen([sys.executable, "-m", "text2anim.cli.main", long_text(n), "-o", str(tmp / "long.bvh")],
                                env=env, cwd=str(tmp), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        _, status, usage = os.wait4(proc.pid, 0)  # this child's own figures (its peak: ru_maxrss, KiB)
        proc.returncode = os.waitstatus_to_exitcode(status)
        wall = time.perf_counter() - w
        if proc.returncode != 0:
            raise RuntimeError(f"the {n}-motion text failed: exit {proc.returncode}")
        cpu, peak = usage.ru_utime + usage.ru_stime, usage.ru_maxrss
        row(f"long text, {n} motions ({len(long_text(n))} chars), fresh process",
            f"{cpu:.2f} s; {peak / 1024:.0f} MB", f"{wall:.2f} s", "a few s, << 1 GB, linear")


def bytecode_env(tmp: Path) -> dict:
    """The environment for whole-process rows: compiled bytecode cached (in ``tmp``), as an installed
    package has it; ``PYTHONDONTWRITEBYTECODE`` (set on some machines) would recompile our ~200
    modules in every process (~0.1 s CPU) and time the compiler, not text2anim."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    return {**env, "PYTHONPYCACHEPREFIX": str(tmp / "pycache")}


#: the packages a whole process's CPU time is split by, in the order they are added (see :func:`cpu_split`)
GROUPS = ("numpy", "sqlalchemy", "scipy", "fugashi")


def loaded_modules(argv: list[str], env: dict, cwd: str) -> list[tuple[str, str]]:
    """The modules ``argv`` (``python -X importtime ...``) imports, in the order their imports finished, each
    with its group: the first of :data:`GROUPS` on its chain of importers (numpy's modules that scipy
    imports count for scipy), else ``""``."""
    proc = subprocess.run(argv, env=env, cwd=cwd, capture_output=True, text=True, check=True)
    rows = []
    for line in proc.stderr.splitlines():
        if line.startswith("import time:") and "self [us]" not in line:
            name = line.split("|")[2]
            rows.append(((len(name) - len(name.lstrip())) // 2, name.strip()))
    out, chain = [], []  # chain: the importers of the row being read; read backwards, importers come first
    for depth, name in reversed(rows):
        del chain[depth:]
        chain.append(name)
        out.append((name, next((g for m in chain for g in GROUPS if m == g or m.startswith(g + ".")), "")))
    return out[::-1]


def cpu_split(modules: list[tuple[str, str]], whole: float, env: dict, cwd: str, runs: int) -> list[tuple[str, float]]:
    """Where a whole process's CPU goes: child processes that only import, package after package
    (:data:`GROUPS`, then everything else the process imported: our modules and the standard library's
    rest), each median CPU minus the one before; ``run`` is what is left of ``whole``."""
    # as the command: the collector paused for the imports and frozen at the end, one OpenBLAS thread (cli.main)
    env = {**env, "OPENBLAS_NUM_THREADS": "1"}
    steps, wanted = [("python", "import gc\ngc.disable()\ngc.freeze()")], []
    for group in GROUPS + ("text2anim + rest",):
        mods = [m for m, g in modules if g == group or group == "text2anim + rest"]
        if not mods:
            continue
        wanted += [m for m in mods if m not in wanted and not m.startswith("__")]
        steps.append((group, "import gc, importlib\ngc.disable()\nfor m in %r:\n    try:\n        importlib.import_module(m)\n"
                             "    except ImportError:\n        pass\ngc.freeze()" % (wanted,)))
    out, before = [], 0.0
    for name, code in steps:
        cpu = statistics.median(child([sys.executable, "-c", code], env, cwd)[0] for _ in range(runs))
        out.append((name, cpu - before))
        before = cpu
    return out + [("run", whole - before)]


def process_rows(tmp: Path, repeat: int) -> None:
    env = {**bytecode_env(tmp), "TEXT2ANIM_DB": f"sqlite:///{tmp}/motions.sqlite"}
    exe = [sys.executable, "-m", "text2anim.cli.main"]
    child(exe + ["plan", TEXT3], env, str(tmp))  # warm the file cache, compile the bytecode
    child(exe + [TEXT3, "-o", str(tmp / "x.bvh")], env, str(tmp))
    runs = max(3, repeat)
    res: dict[str, list[tuple[float, float]]] = {"animate": [], "plan": [], "bare": [], "seed": []}
    for k in range(runs):  # interleaved
        res["animate"].append(child(exe + [TEXT3, "-o", str(tmp / "x.bvh")], env, str(tmp)))
        res["plan"].append(child(exe + ["plan", TEXT3], env, str(tmp)))
        res["bare"].append(child([sys.executable, "-c", "pass"], env, str(tmp)))
        if k < 3:
            fresh = {**os.environ, "TEXT2ANIM_DB": f"sqlite:///{tmp}/fresh{k}.sqlite"}
            res["seed"].append(child([sys.executable, "-c", "from text2anim.motiondb import MotionDB;"
                                      "db = MotionDB.open(); db.close()"], fresh, str(tmp)))

    def med(key):
        return tuple(statistics.median(x[i] for x in res[key]) for i in (0, 1))
    for key, name, goal in (("animate", "`text2anim TEXT -o x.bvh`, whole process", "<= 0.5 s"),
                            ("plan", "`text2anim plan TEXT`, whole process", "<= 0.3 s"),
                            ("seed", "first run on an empty database (seeding)", "<= 1 s"),
                            ("bare", "(bare `python -c pass`, for scale)", "")):
        c, w = med(key)
        row(name, f"{c:.2f} s", f"{w:.2f} s", goal)
    timed_exe = [sys.executable, "-X", "importtime", "-m", "text2anim.cli.main"]
    for key, argv in (("animate", [TEXT3, "-o", str(tmp / "x.bvh")]), ("plan", ["plan", TEXT3])):
        split = cpu_split(loaded_modules(timed_exe + argv, env, str(tmp)), med(key)[0], env, str(tmp), runs)
        row(f"  split of `{key}` (CPU s)", ", ".join(f"{n} {c:.2f}" for n, c in split), "-", "")
    peak_row(tmp, env)


# ----------------------------------------------------------------- DB search
def search_rows(sizes: list[int], n_queries: int) -> None:
    from bench_db import build
    from sqlalchemy import event

    from text2anim.motiondb import MotionDB

    p50s, single = [], []
    with tempfile.TemporaryDirectory(prefix="t2a-speed-") as tmp:
        for n in sizes:
            path = Path(tmp) / f"db{n}.sqlite"
            verbs, objects, characters, _ = build(path, n)
            rng = np.random.default_rng(1)
            cpu, wall, hits = [], [], []
            asked = []
            with MotionDB.open(path, seed=False) as db:
                statements = [0]
                db.search(verbs[0], limit=10)
                event.listen(db.engine, "before_cursor_execute", lambda conn, cur, statement, *a: statements.__setitem__(
                    0, statements[0] + statement.lstrip().upper().startswith("SELECT")))
                for _ in range(n_queries):
                    verb = verbs[int(rng.integers(len(verbs)))]
                    obj = objects[int(rng.integers(len(objects)))] if rng.random() < 0.5 else None
                    pref = characters[int(rng.integers(len(characters)))] if rng.random() < 1 / 3 else None
                    c, w, found = timed(lambda: db.search(verb, object=obj, prefer_character=pref, limit=10))
                    cpu.append(c)
                    wall.append(w)
                    hits.append(len(found))
                    asked.append((verb, obj, pref))
                n_statements = statements[0]
                # then the same queries with limit 1: one hit at every size (like for like)
                one = [timed(lambda: db.search(v, object=o, prefer_character=p, limit=1))[0] for v, o, p in asked]
            c50, c95 = np.percentile(cpu, [50, 95])
            w50, w95 = np.percentile(wall, [50, 95])
            p50s.append(c50)
            # a verb has ~3n/1000 clips: below ~3000 clips a search returns fewer than 10, and less to decode
            row(f"DB search, {n} clips, limit 10 ({n_statements / n_queries:.1f} SELECTs, {np.mean(hits):.1f} hits)",
                f"p50 {ms(c50)} p95 {ms(c95)}", f"p50 {ms(w50)} p95 {ms(w95)}", "p95 <= 1 ms")
            o50, o95 = np.percentile(one, [50, 95])
            single.append(o50)
            row("  same queries, limit 1 (1 hit: the per-query cost)", f"p50 {ms(o50)} p95 {ms(o95)}", "-", "")
            if np.mean(hits) > 1.5:  # what each further hit costs: the difference over the hits it adds
                row("  per further hit (limit 10 - limit 1, per hit)",
                    f"{(c50 - o50) / (np.mean(hits) - 1) * 1e6:.0f} us", "-", "")
    if len(p50s) > 1:
        row(f"DB search growth {sizes[0]} -> {sizes[-1]} clips (p50)", f"{p50s[-1] / p50s[0]:.2f}x", "-", "<= 1.5x")
        # the row above compares a few hits (a verb has ~3 clips per 1000) with 10: this one, 1 hit with 1
        row("  growth at limit 1 (1 hit at each size, p50)", f"{single[-1] / single[0]:.2f}x", "-", "")


# ----------------------------------------------------------------- peers
def interleaved(contenders: dict, repeat: int) -> dict[str, tuple[float, float]]:
    """Median (CPU, wall) per contender; each round runs every contender once, the order rotating."""
    names = list(contenders)
    times: dict[str, list[tuple[float, float]]] = {n: [] for n in names}
    for k in range(repeat):
        for n in names[k % len(names):] + names[:k % len(names)]:
            c, w, _ = timed(contenders[n])
            times[n].append((c, w))
    return {n: (statistics.median(t[0] for t in v), statistics.median(t[1] for t in v)) for n, v in times.items()}


def bvh_rows(repeat: int) -> None:
    """Ours against the peers for two outputs, defined in ``bvh_peers.py`` (the same work for each)."""
    from bvh_peers import cmu_paths, contenders

    from text2anim.core import read_bvh

    paths = cmu_paths()
    if not paths:
        row("BVH parse", "no CMU files", "-", "")
        return
    frames = sum(read_bvh(p).n_frames for p in paths)
    for output, what in (("rotations", "to (T,J,4) quaternions"), ("raw", "raw channels (T,C)")):
        fns, notes = contenders(paths, output)
        for note in notes:
            print(f"  ({note})")
        for fn in fns.values():  # imports and caches warmed outside the timing
            fn()
        res = interleaved(fns, repeat)
        ours = res["text2anim"]
        peers = [c for n, (c, _) in res.items() if n != "text2anim"]
        goal = f">= 5x the fastest (now {min(peers) / ours[0]:.1f}x)" if peers else ">= 5x the fastest (no peer)"
        for n, (c, w) in res.items():
            ratio = "" if n == "text2anim" else f", ours {c / ours[0]:.1f}x faster"
            row(f"BVH {what} {n} ({len(paths)} files, {frames} frames)", f"{ms(c)} ({frames / c:,.0f} f/s){ratio}",
                ms(w), goal if n == "text2anim" and output == "rotations" else "")


def nlp_rows(repeat: int) -> None:
    import json

    from text2anim.nlp import NLPError, analyze

    corpus = REPO / "tests" / "corpus" / "nlp_corpus.jsonl"
    sentences = [json.loads(x)["text"] for x in corpus.read_text(encoding="utf-8").splitlines()
                 if x.startswith("{")][:200]

    def ours():
        for s in sentences:
            try:
                analyze(s)
            except NLPError:
                pass
    ours()
    contenders = {"text2anim.nlp": ours}
    try:
        import spacy

        nlp = spacy.load("ja_ginza")
        contenders["GiNZA"] = lambda: list(nlp.pipe(sentences))
    except (ImportError, OSError):
        pass
    res = interleaved(contenders, max(3, repeat // 2))
    for n, (c, w) in res.items():
        extra = "" if n == "text2anim.nlp" else f", ours {c / res['text2anim.nlp'][0]:.0f}x faster"
        row(f"analysis {n} ({len(sentences)} sentences)", f"{ms(c / len(sentences))}/sentence{extra}",
            ms(w / len(sentences)), "")
    if len(res) == 1:
        row("analysis GiNZA", "not installed", "-", "optional")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--db-sizes", type=int, nargs="+", default=[1000, 100000])
    ap.add_argument("--queries", type=int, default=300)
    ap.add_argument("--long", type=int, nargs="+", default=[8, 16, 32], help="motions of the long texts")
    ap.add_argument("--only", nargs="+", choices=["pipeline", "process", "long", "search", "bvh", "nlp"])
    args = ap.parse_args(argv)
    only = set(args.only or ["pipeline", "process", "long", "search", "bvh", "nlp"])
    load0 = os.getloadavg()
    print(f"load average at start: {load0[0]:.1f} ({os.cpu_count()} cores)")
    print(f"  {'figure':52} {'CPU':>22} {'wall':>22}  goal")
    with tempfile.TemporaryDirectory(prefix="t2a-speed-") as tmp:
        if only & {"pipeline", "process", "long"}:
            from text2anim.motiondb import MotionDB

            MotionDB.open(f"sqlite:///{tmp}/motions.sqlite").close()
        if "pipeline" in only:
            pipeline_rows(Path(tmp), args.repeat)
        if "process" in only:
            process_rows(Path(tmp), args.repeat)
        if "long" in only:
            long_rows(Path(tmp), {**bytecode_env(Path(tmp)), "TEXT2ANIM_DB": f"sqlite:///{tmp}/motions.sqlite"},
                      args.long)
    if "search" in only:
        search_rows(args.db_sizes, args.queries)
    if "bvh" in only:
        bvh_rows(args.repeat)
    if "nlp" in only:
        nlp_rows(args.repeat)
    print(f"load average at end: {os.getloadavg()[0]:.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
