"""What a batch came to: lines by status and reason, expectations, and the quality figures' spread."""
from __future__ import annotations

import heapq
from array import array
from collections import Counter

import numpy as np

STATUSES = ("animated", "parsed", "refused", "failed")
#: What became of a line (:func:`outcome`): each line is counted once, under one of these.
CHECKS = ("passed", "refused", "failed", "errored")
#: Quality figures summarised over every join (key in a record's ``joins``, label, unit).
JOIN_FIGURES = (
    ("skating_ratio", "join foot-skating ratio", ""),
    ("root_pop", "join root pop", "m/s²"),
    ("jerk_p99", "join jerk p99", "m/s³"),
    ("max_slide_cm_s", "join max foot slide", "cm/s"),
    ("core_fidelity_cm", "join core fidelity", "cm"),
)
PERCENTILES = (50, 90, 99)


def outcome(rec: dict) -> str:
    """The line's ``check``, except that a line refused without asking for an error (a verb the database
    lacks: its parse met the expectation, so ``--check`` lets it pass) is ``refused``, not ``passed``."""
    if rec["check"] == "passed" and rec["status"] == "refused" and not rec.get("expected_error"):
        return "refused"
    return rec["check"]


class Summary:
    """Counts and figures accumulated one record at a time (any order), for the table and summary.json."""

    def __init__(self, max_listed: int = 20):
        self.total = 0
        self.checks: Counter = Counter()
        self.categories: dict[str, Counter] = {}
        self.statuses: Counter = Counter()
        self.reasons: dict[str, Counter] = {"refused": Counter(), "failed": Counter()}
        self.line_skating = array("d")  # compact: a million lines stay small
        self.joins = {k: array("d") for k, _, _ in JOIN_FIGURES}
        self.n_joins = 0
        self.n_meeting = 0  # joins whose window meets every criterion against its source clips
        self.max_listed = max_listed
        self._bad: list[tuple[int, dict]] = []  # max-heap (by -line) of the first lines not passing

    def add(self, rec: dict) -> None:
        self.total += 1
        line = outcome(rec)
        self.checks[line] += 1
        if rec.get("category"):
            self.categories.setdefault(rec["category"], Counter())[line] += 1
        self.statuses[rec["status"]] += 1
        if rec["status"] in self.reasons:
            self.reasons[rec["status"]][rec["reason"]] += 1
        if rec.get("skating_ratio") is not None:
            self.line_skating.append(rec["skating_ratio"])
        for j in rec.get("joins", ()):
            self.n_joins += 1
            self.n_meeting += bool(j.get("meets")) and all(j["meets"].values())
            for key in self.joins:
                if j.get(key) is not None:
                    self.joins[key].append(j[key])
        if rec["check"] != "passed":
            heapq.heappush(self._bad, (-rec["line"], rec))
            if len(self._bad) > self.max_listed:
                heapq.heappop(self._bad)

    @property
    def ok(self) -> bool:
        """No line missed its expectation or errored (what ``--check`` asks)."""
        return not (self.checks["failed"] or self.checks["errored"])

    def to_dict(self) -> dict:
        out = {
            "total": self.total, **{c: self.checks[c] for c in CHECKS},
            "categories": {c: {k: n[k] for k in CHECKS} | {"total": sum(n.values())}
                           for c, n in sorted(self.categories.items())},
            "status": {s: self.statuses[s] for s in STATUSES},
            "reasons": {s: dict(r.most_common()) for s, r in self.reasons.items()},
        }
        if self.line_skating or self.n_joins:
            out["quality"] = {"joins": self.n_joins, "joins_meeting_sources": self.n_meeting,
                              "skating_ratio": spread(self.line_skating),
                              **{f"join_{k}": spread(v) for k, v in self.joins.items()}}
        return out

    def format(self, top_reasons: int = 8) -> str:
        """The table printed at the end of a batch."""
        lines = []
        bad = [rec for _, rec in sorted(self._bad, key=lambda x: -x[0])]
        for rec in bad:
            lines.append(f"{rec['check'].upper()} line {rec['line']}: {rec['text']}")
            lines.extend(f"    {m}" for m in rec["mismatches"])
            if rec["check"] == "errored":
                lines.append(f"    {rec.get('error')}")
        n_bad = self.checks["failed"] + self.checks["errored"]
        if n_bad > len(bad):
            lines.append(f"... and {n_bad - len(bad)} more")
        if self.categories:
            width = max(len(c) for c in self.categories)
            for cat, c in sorted(self.categories.items()):
                lines.append(f"  {cat:<{width}}" + "".join(f"  {k} {c[k]:>3}" for k in CHECKS))
        lines.append(f"{'lines':<32}{'count':>8}{'share':>8}")
        for s in STATUSES:
            n = self.statuses[s]
            if n or s in ("refused", "failed"):
                lines.append(f"{s:<32}{n:>8}{100 * n / max(self.total, 1):>7.1f}%")
            for reason, k in self.reasons.get(s, Counter()).most_common(top_reasons):
                lines.append(f"  {reason:<30}{k:>8}")
            more = len(self.reasons.get(s, ())) - top_reasons
            if more > 0:
                lines.append(f"  ... {more} more reasons")
        if self.line_skating or self.n_joins:
            lines.append(f"{'quality':<32}" + "".join(f"{'p' + str(p):>9}" for p in PERCENTILES) + f"{'max':>9}")
            rows = [("foot-skating ratio (whole)", "", self.line_skating)]
            rows += [(label, unit, self.joins[k]) for k, label, unit in JOIN_FIGURES]
            for label, unit, values in rows:
                sp = spread(values)
                name = f"{label} ({unit})" if unit else label
                if sp["n"]:
                    lines.append(f"{name:<32}" + "".join(f"{sp['p' + str(p)]:>9.4g}" for p in PERCENTILES)
                                 + f"{sp['max']:>9.4g}")
            lines.append(f"({self.n_joins} joins in {self.statuses['animated']} animated lines; {self.n_meeting} "
                         "meet every criterion against their source clips)")
        lines.append(", ".join(f"{k} {self.checks[k]}" for k in CHECKS) + f" (of {self.total})")
        return "\n".join(lines) + "\n"


def spread(values) -> dict:
    """``n``, the :data:`PERCENTILES` and the largest of ``values`` (None for an empty list)."""
    if not len(values):
        return {"n": 0, **{f"p{p}": None for p in PERCENTILES}, "max": None}
    a = np.frombuffer(values, dtype=float) if isinstance(values, array) else np.asarray(values, float)
    qs = np.percentile(a, PERCENTILES)
    return {"n": int(a.size), **{f"p{p}": round(float(q), 6) for p, q in zip(PERCENTILES, qs)},
            "max": round(float(a.max()), 6)}
