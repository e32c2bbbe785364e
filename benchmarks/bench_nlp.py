"""Benchmark of the nlp stage: ``python benchmarks/bench_nlp.py``.

Prints one table:

- parse throughput: sentences/s through ``nlp.analyze``, warm, one process,
  over the project corpus (tests/corpus/nlp_corpus.jsonl), by wall and by CPU time;
- exact-parse rate per class of the typed corpus (tests/corpus/typed_corpus.jsonl:
  sentences the way users type them, issue 27), checked by ``text2anim batch --check``;
- end-to-end rate per class of the story corpus (tests/corpus/story_corpus.jsonl: stories with
  pronouns, keigo, instructions, spoken text, typos, actors together, issue 39): the parse and,
  where a line names them, the clips its time table plays (the built-in library); the same for the
  phrase corpus (tests/corpus/phrase_corpus.jsonl: idioms, loan verbs, mimetics, issue 39) and the
  scene corpus's analysis (tests/corpus/scene_corpus.jsonl: targets, partners, objects, issue 45);
- cold start: wall time of ``python -m text2anim.cli.main parse TEXT --json`` as a whole
  process (median of several runs), next to a bare ``python -c pass``;
- GiNZA (only if ``ginza`` and ``ja_ginza`` are importable; install them in
  a development venv only, they are not a dependency): load time, throughput
  on the same sentences, the speed ratio, and the predicate-link agreement —
  the fraction of our predicate -> head links (bunsetsu level) that GiNZA's
  dependency tree also makes.
"""
from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT / "tests" / "corpus" / "nlp_corpus.jsonl"
TYPED = ROOT / "tests" / "corpus" / "typed_corpus.jsonl"
STORY = ROOT / "tests" / "corpus" / "story_corpus.jsonl"
PHRASE = ROOT / "tests" / "corpus" / "phrase_corpus.jsonl"
SCENE = ROOT / "tests" / "corpus" / "scene_corpus.jsonl"
COLD_TEXT = "太郎は走って、ボールを蹴る。そして喜ぶ。"

sys.path.insert(0, str(ROOT))


def load_sentences() -> list[str]:
    lines = CORPUS.read_text(encoding="utf-8").splitlines()
    return [json.loads(x)["text"] for x in lines if x.startswith("{")]


def parse_all(sentences: list[str]) -> list:
    from text2anim.nlp import NLPError, analyze

    out = []
    for s in sentences:
        try:
            out.append(analyze(s))
        except NLPError:
            out.append(None)
    return out


def throughput(fn, sentences: list[str], seconds: float, cpu: list | None = None) -> float:
    """Sentences/s by wall time; with ``cpu`` (a list), the rate by CPU time is appended to it."""
    fn(sentences)  # warm up (tagger, caches)
    n, start, start_cpu = 0, time.perf_counter(), time.process_time()
    while time.perf_counter() - start < seconds:
        fn(sentences)
        n += len(sentences)
    if cpu is not None:
        cpu.append(n / max(1e-9, time.process_time() - start_cpu))
    return n / (time.perf_counter() - start)


def typed_scores(corpus: Path = TYPED) -> dict[str, tuple[int, int]]:
    """Category -> (passed, total) of ``corpus`` through ``text2anim batch --check``."""
    import contextlib
    import io
    import tempfile

    from text2anim.cli.main import main as cli

    with tempfile.TemporaryDirectory() as tmp, contextlib.redirect_stdout(io.StringIO()), \
            contextlib.redirect_stderr(io.StringIO()):
        cli(["batch", str(corpus), "--check", "--out", tmp, "--parse-only"])
        summary = json.loads((Path(tmp) / "summary.json").read_text())
    return {k: (v["passed"], v["total"]) for k, v in sorted(summary["categories"].items())}


def cold_start(runs: int) -> tuple[float, float, float]:
    """Median wall seconds of a whole `parse` process, of the nlp stage alone in
    a process (no CLI dispatcher, which imports every sub-command), and of a
    bare interpreter."""
    def median_of(cmd):
        times = []
        for _ in range(runs):
            t = time.perf_counter()
            subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True)
            times.append(time.perf_counter() - t)
        return statistics.median(times)

    parse = median_of([sys.executable, "-m", "text2anim.cli.main", "parse", COLD_TEXT, "--json"])
    alone = median_of([sys.executable, "-c",
                       f"from text2anim import nlp; print(nlp.analyze({COLD_TEXT!r}).to_json())"])
    bare = median_of([sys.executable, "-c", "pass"])
    return parse, alone, bare


def our_links(analyses) -> list[tuple[int, tuple[int, int], tuple[int, int], bool]]:
    """(sentence no., dependent span, head span, head is the nearest motion) per link."""
    links = []
    for n, a in enumerate(analyses):
        if a is None:
            continue
        motions = [b for b in a.bunsetsu if b.role == "motion"]
        for k, b in enumerate(motions):
            if b.head is None:
                continue
            head = a.bunsetsu[b.head]
            nearest = k + 1 < len(motions) and motions[k + 1].index == head.index
            links.append((n, b.span, head.span, nearest))
    return links


def ginza_heads(doc, span: tuple[int, int]):
    """Tokens whose head lies outside the character range ``span``."""
    inside = [t for t in doc if span[0] <= t.idx < span[1]]
    return [t.head for t in inside if not (span[0] <= t.head.idx < span[1])]


def ginza_bench(sentences: list[str], analyses, seconds: float) -> dict | None:
    try:
        import spacy  # noqa: F401
        import ginza  # noqa: F401
    except ImportError:
        return None
    t = time.perf_counter()
    try:
        nlp = spacy.load("ja_ginza")
    except OSError:
        return None
    load = time.perf_counter() - t
    docs = list(nlp.pipe(sentences))
    rate = throughput(lambda ss: list(nlp.pipe(ss)), sentences, seconds)
    agree = agree_far = far = 0
    links = our_links(analyses)
    for n, dep, head, nearest in links:
        ok = any(head[0] <= h.idx < head[1] for h in ginza_heads(docs[n], dep))
        agree += ok
        if not nearest:
            far += 1
            agree_far += ok
    return {"load": load, "rate": rate, "links": len(links), "agree": agree,
            "far": far, "agree_far": agree_far}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seconds", type=float, default=3.0, help="time per throughput run")
    ap.add_argument("--runs", type=int, default=7, help="process runs for the cold start")
    args = ap.parse_args(argv)

    sentences = load_sentences()
    cpu: list[float] = []
    ours = throughput(parse_all, sentences, args.seconds, cpu)
    scores = typed_scores()
    stories = typed_scores(STORY)
    phrases = typed_scores(PHRASE)
    scenes = typed_scores(SCENE)
    analyses = parse_all(sentences)
    cold, alone, bare = cold_start(args.runs)
    g = ginza_bench(sentences, analyses, args.seconds)

    rows = [
        ("corpus sentences", f"{len(sentences)}"),
        ("parse throughput (warm, 1 process)", f"{ours:,.0f} sentences/s"),
        ("parse throughput by CPU time", f"{cpu[0]:,.0f} sentences/s"),
        ("typed corpus, exact parses", f"{sum(p for p, _ in scores.values())}/{sum(t for _, t in scores.values())}"),
        *((f"  {k}", f"{p}/{t}") for k, (p, t) in scores.items()),
        ("story corpus, end to end (parse and plan)",
         f"{sum(p for p, _ in stories.values())}/{sum(t for _, t in stories.values())}"),
        *((f"  {k}", f"{p}/{t}") for k, (p, t) in stories.items()),
        ("phrase corpus, parses", f"{sum(p for p, _ in phrases.values())}/{sum(t for _, t in phrases.values())}"),
        *((f"  {k}", f"{p}/{t}") for k, (p, t) in phrases.items()),
        ("scene corpus, parses (targets and roles)",
         f"{sum(p for p, _ in scenes.values())}/{sum(t for _, t in scenes.values())}"),
        *((f"  {k}", f"{p}/{t}") for k, (p, t) in scenes.items()),
        ("cold start `text2anim parse` (median)", f"{cold * 1000:.0f} ms"),
        ("cold start nlp alone (import + analyze)", f"{alone * 1000:.0f} ms"),
        ("bare interpreter", f"{bare * 1000:.0f} ms"),
    ]
    if g is None:
        rows.append(("GiNZA", "not installed"))
    else:
        rows += [
            ("GiNZA model load", f"{g['load'] * 1000:.0f} ms"),
            ("GiNZA throughput (warm)", f"{g['rate']:,.0f} sentences/s"),
            ("speed ratio (ours / GiNZA)", f"{ours / g['rate']:.0f}x"),
            ("predicate-link agreement", f"{g['agree']}/{g['links']} = {g['agree'] / max(1, g['links']):.0%}"),
            ("  on links past the nearest motion",
             f"{g['agree_far']}/{g['far']} = {g['agree_far'] / max(1, g['far']):.0%}"),
        ]
    width = max(len(k) for k, _ in rows)
    print(f"{'measure':<{width}}  value")
    print(f"{'-' * width}  {'-' * 24}")
    for k, v in rows:
        print(f"{k:<{width}}  {v}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
