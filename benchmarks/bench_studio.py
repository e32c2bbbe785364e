"""The studio's latency in a real browser, as an animator types: from the last keystroke of a sentence to the
first frame of its animation on screen, measured by the page itself (``window.__studio.keyLatencies``: the time of
the last ``input`` event of the text sent to the first frame drawn after its answer: a new sentence's draft), and
to the first frame of its finished animation (``finishLatencies``: the draft replaced).

``python benchmarks/bench_studio.py [--seconds 10] [--no-load] [--story] [--forget-joins]`` (needs /usr/bin/chromium
and Playwright, as the tests do).

For each reading the benchmark types sentences into the page for ``--seconds`` seconds of wall time, one
character every 90 ms (``keyboard.type``: an ``input`` event each, as committed kana and kanji arrive), waits for
each sentence's finished animation, and goes on with the next one: the typing pause (120 ms) is part of every
figure.

- **seen**: five sentences typed again and again (the studio keeps recent results: the page's own cost, the
  pause, the request and the viewer's first frame);
- **new**: sentences never animated before (names × verbs): analysis, synthesis and the viewer page too;
- **story** (``--story``): ten sentences typed one after another at the end of one text, as a story is written;
  each pause animates the whole text again (``--forget-joins``: with no laid join kept, to compare).

Unless ``--no-load``, one other CPU-bound process (``python -c "while 1: pass"``) runs for the whole benchmark,
as on a machine where something else is working; it is stopped at the end. Wall times on this machine.
"""
from __future__ import annotations

import argparse
import itertools
import statistics
import subprocess
import sys
import tempfile
import threading
import time

NAMES = ["太郎", "花子", "一郎", "二郎", "三郎", "健太", "翔太", "大輔", "美咲", "由美", "直子", "裕子", "陽子", "恵子"]
VERBS = ["走って、ボールを蹴る。", "歩いて、座る。", "ジャンプして、喜ぶ。", "手を振って、歩く。", "歩いて、お辞儀する。",
         "走って、止まる。", "座って、立つ。"]
SEEN = ["太郎は走って、ボールを蹴る。", "花子は歩いて、座る。", "一郎はジャンプして、喜ぶ。", "美咲は手を振って、歩く。",
        "健太は走って、止まる。"]
FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync"]
#: Milliseconds between two typed characters.
KEY_MS = 90
#: A story typed into one text, sentence after sentence (``--story``): two people, ten sentences.
STORY = ["太郎は走って、ボールを蹴る。", "そして喜ぶ。", "花子は歩いて、椅子に座る。", "それから立ち上がって、手を振る。",
         "太郎はジャンプして、お辞儀をする。", "花子は走って、止まる。", "太郎は歩いて、ボールを投げる。", "花子は踊って、笑う。",
         "太郎は座って、立ち上がる。", "花子はお辞儀をして、歩く。"]


def serve(db_url: str):
    import uvicorn

    from text2anim.cli.cmd_studio import free_port
    from text2anim.cli.studio.app import create_app
    from text2anim.cli.studio.slow import server_config

    port = free_port("127.0.0.1")
    server = uvicorn.Server(server_config(create_app(db_url, "127.0.0.1", port), "127.0.0.1", port,
                                          log_level="warning"))
    threading.Thread(target=server.run, daemon=True).start()
    while not server.started:
        time.sleep(0.05)
    return server, f"http://127.0.0.1:{port}/"


def type_sentence(page, text: str) -> tuple[float, float | None] | None:
    """Select the box's text and type ``text`` over it; the keystroke-to-frame latencies (ms) of its first frame
    and of its finished animation's when a draft came first (else None), or None when it failed."""
    return _typed(page, "Control+a", text, text)


def append_sentence(page, text: str, sentence: str) -> float | None:
    """Type ``sentence`` at the end of the box, which holds ``text``; keystroke to the first frame of the whole
    text's finished animation (ms; the first frame when no draft came first), or None when it failed."""
    got = _typed(page, "Control+End", sentence, text + sentence)
    return None if got is None else got[1] if got[1] is not None else got[0]


def _typed(page, where: str, typed: str, whole: str) -> tuple[float, float | None] | None:
    """Press ``where`` in the box (select all, or go to its end), type ``typed`` so that the box holds ``whole``;
    the latencies of :func:`type_sentence`."""
    n = page.evaluate("window.__studio.keyLatencies.length")
    done = page.evaluate("window.__studio.finishLatencies.length")
    page.focus("#text")
    page.keyboard.press(where)
    page.keyboard.type(typed, delay=KEY_MS)
    page.wait_for_function("([n, text]) => window.__studio.text === text && !window.__studio.busy "
                           "&& (window.__studio.keyLatencies.length > n || window.__studio.error)", arg=[n, whole],
                           timeout=120000)
    if page.evaluate("window.__studio.error"):
        print(f"{whole}: {page.evaluate('window.__studio.error')}", file=sys.stderr)
        return None
    first = float(page.evaluate("window.__studio.keyLatencies[window.__studio.keyLatencies.length - 1]"))
    finished = page.evaluate("([k]) => window.__studio.finishLatencies.length > k ? "
                             "window.__studio.finishLatencies[window.__studio.finishLatencies.length - 1] : null", [done])
    return first, finished


def story_reading(page) -> list[float]:
    """A story typed sentence after sentence into one text (:data:`STORY`): keystroke to its finished animation
    after each sentence, ms."""
    page.focus("#text")
    page.keyboard.press("Control+a")
    page.keyboard.press("Delete")
    out, text = [], ""
    for sentence in STORY:
        ms = append_sentence(page, text, sentence)
        text += sentence
        if ms is not None:
            out.append(ms)
    return out


def pct(values: list[float], q: int) -> float:
    return statistics.quantiles(values, n=100, method="inclusive")[q - 1] if len(values) > 1 else values[0]


def reading(page, sentences, seconds: float) -> tuple[list[float], list[float]]:
    """Keystroke to first frame and (for those that had a draft) to the finished animation's, ms."""
    first, finished, end = [], [], time.monotonic() + seconds
    for text in sentences:
        if time.monotonic() > end:
            break
        ms = type_sentence(page, text)
        if ms is not None:
            first.append(ms[0])
            if ms[1] is not None:
                finished.append(ms[1])
    return first, finished


def main(argv: list[str]) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--seconds", type=float, default=10.0, help="seconds of typing per reading (default 10)")
    p.add_argument("--no-load", action="store_true", help="no other CPU-bound process while it runs")
    p.add_argument("--story", action="store_true", help="also type a ten-sentence story into one text")
    p.add_argument("--forget-joins", action="store_true",
                   help="keep no laid joins (optimal.join.KEPT_JOINS): the studio as before it kept them, to compare")
    args = p.parse_args(argv)
    if args.forget_joins:
        from text2anim.synthesis.optimal import join as optimal_join
        optimal_join.KEPT_JOINS.budget = 0
    from playwright.sync_api import sync_playwright

    from text2anim.motiondb import MotionDB

    load = None if args.no_load else subprocess.Popen([sys.executable, "-c", "while 1: pass"])
    try:
        with tempfile.TemporaryDirectory() as tmp:
            url = f"sqlite:///{tmp}/lib.sqlite"
            MotionDB.open(url).close()
            server, base = serve(url)
            with sync_playwright() as pw:
                browser = pw.chromium.launch(executable_path="/usr/bin/chromium", headless=True, args=FLAGS)
                page = browser.new_page(viewport={"width": 1280, "height": 1000}, locale="ja-JP")
                page.goto(base)
                page.wait_for_function("window.__studio && window.__studio.renders >= 1", timeout=60000)
                for text in SEEN:  # warm-up: the seen sentences animated once
                    type_sentence(page, text)
                seen = reading(page, itertools.cycle(SEEN), args.seconds)
                fresh = (f"{n}は{v}" for n, v in itertools.product(NAMES, VERBS) if f"{n}は{v}" not in SEEN)
                new = reading(page, fresh, args.seconds)
                phases = page.evaluate("window.__studio.phases.slice(-%d)" % len(new[0])) if new[0] else []
                story = story_reading(page) if args.story else []
                browser.close()
            server.should_exit = True
    finally:
        if load is not None:
            load.kill()
            load.wait()
    print(f"keystroke to first frame, typing {args.seconds:g} s per reading, one character every {KEY_MS} ms, "
          f"{'one other CPU-bound process running' if load is not None else 'no other load'}:")
    print("| sentences | renders | p50 ms | p95 ms |")
    print("| --- | ---: | ---: | ---: |")
    for label, v in (("seen (typed before)", seen[0]), ("new (never animated): first frame", new[0]),
                     ("new: finished animation (draft replaced)", new[1])):
        if v:
            print(f"| {label} | {len(v)} | {statistics.median(v):.0f} | {pct(v, 95):.0f} |")
    if phases:
        print("new sentences, median ms: " + ", ".join(
            f"{k} {statistics.median(p[k] for p in phases):.0f}" for k in ("pause", "request", "shown")))
    if story:
        print(f"a story typed into one text{' (laid joins not kept)' if args.forget_joins else ''}, keystroke to "
              "its finished animation after each sentence, ms: " + " ".join(f"{v:.0f}" for v in story))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
