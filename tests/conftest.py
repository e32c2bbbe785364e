"""Shared fixtures.

``db_url``: the database tests run once per backend.

- ``sqlite``: a fresh SQLite file in the test's temporary folder;
- ``postgresql``: a fresh PostgreSQL schema in the server named by
  ``TEXT2ANIM_TEST_PG_URL`` (``.ci/run`` starts one and sets it), reached
  through ``search_path`` in the URL and dropped after the test. Without the
  variable these runs are skipped, saying why.

At the end pytest prints how many database tests ran on each backend
("database tests: N on sqlite, M on postgresql"), and why tests skipped, grouped by what is missing
and how to get it (:mod:`skip_groups`).
"""
from __future__ import annotations

from text2anim import reproducible

reproducible.pin()  # before numpy: the goldens and shipped arrays compare bytes across machines

import logging  # noqa: E402
import os  # noqa: E402
import uuid  # noqa: E402
import warnings  # noqa: E402

import pytest

PG_ENV = "TEXT2ANIM_TEST_PG_URL"
BACKENDS = ("sqlite", "postgresql")
_COUNTS = {b: {"passed": 0, "failed": 0, "skipped": 0} for b in BACKENDS}
_SKIP_REASONS: dict[str, set[str]] = {b: set() for b in BACKENDS}
_ALL_SKIPS: list[str] = []  # every skip's reason, for the grouped summary at the end


@pytest.fixture(params=BACKENDS)
def db_url(request, tmp_path):
    """The URL of an empty database (no tables yet) on each backend."""
    if request.param == "sqlite":
        yield f"sqlite:///{tmp_path / 'motions.sqlite'}"
        return
    base = os.environ.get(PG_ENV, "").strip()
    if not base:
        pytest.skip(f"PostgreSQL run: {PG_ENV} is not set (.ci/run starts a server and sets it)")
    pytest.importorskip("psycopg2", reason="PostgreSQL run: psycopg2 is not installed (pip install '.[postgres]')")
    from sqlalchemy import create_engine, text
    from sqlalchemy.engine import make_url

    schema = f"t2a_test_{uuid.uuid4().hex[:12]}"
    admin = create_engine(base)
    try:
        with admin.begin() as conn:
            conn.execute(text(f'CREATE SCHEMA "{schema}"'))
        url = make_url(base).update_query_dict({"options": f"-csearch_path={schema}"})
        yield url.render_as_string(hide_password=False)
    finally:
        try:
            with admin.begin() as conn:
                conn.execute(text(f'DROP SCHEMA IF EXISTS "{schema}" CASCADE'))
        finally:
            admin.dispose()


def _backend(item) -> str | None:
    callspec = getattr(item, "callspec", None)
    if callspec is None:
        return None
    value = callspec.params.get("db_url")
    return value if value in BACKENDS else None


def _skip_reason(report) -> str:
    longrepr = report.longrepr
    if isinstance(longrepr, tuple) and len(longrepr) == 3:
        return str(longrepr[2]).removeprefix("Skipped: ")
    return str(longrepr)


def pytest_collectreport(report):
    if report.skipped:  # a module skipped as a whole (importorskip at its top)
        _ALL_SKIPS.append(_skip_reason(report))


@pytest.hookimpl(wrapper=True)
def pytest_runtest_makereport(item, call):
    report = yield
    if report.skipped:
        _ALL_SKIPS.append(_skip_reason(report))
    backend = _backend(item)
    if backend is not None:
        counts = _COUNTS[backend]
        if report.skipped:
            counts["skipped"] += 1
            _SKIP_REASONS[backend].add(_skip_reason(report))
        elif report.failed:
            counts["failed"] += 1
        elif report.when == "call":
            counts["passed"] += 1
    return report


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    _database_summary(terminalreporter)
    from skip_groups import summary

    for line in summary(_ALL_SKIPS):
        terminalreporter.write_line(line)


def _database_summary(terminalreporter):
    ran = {b: _COUNTS[b]["passed"] + _COUNTS[b]["failed"] for b in BACKENDS}
    if not any(ran.values()) and not any(_COUNTS[b]["skipped"] for b in BACKENDS):
        return
    parts = [f"{ran[b]} on {b}" for b in BACKENDS]
    line = "database tests: " + ", ".join(parts)
    extra = []
    for b in BACKENDS:
        c = _COUNTS[b]
        if c["failed"]:
            extra.append(f"{c['failed']} failed on {b}")
        if c["skipped"]:
            reasons = "; ".join(sorted(_SKIP_REASONS[b])) or "skipped"
            extra.append(f"{c['skipped']} skipped on {b} ({reasons})")
    if extra:
        line += " — " + ", ".join(extra)
    terminalreporter.write_line(line)


# --------------------------------------------------------------- test motions
CMU_LIKE_JOINTS = (
    # name, parent, offset (metres)
    ("Hips", -1, (0.0, 0.0, 0.0)),
    ("LHipJoint", 0, (0.09, -0.05, 0.0)),
    ("LeftUpLeg", 1, (0.0, -0.02, 0.0)),
    ("LeftLeg", 2, (0.0, -0.42, 0.0)),
    ("LeftFoot", 3, (0.0, -0.40, 0.0)),
    ("LeftToeBase", 4, (0.0, -0.04, 0.12)),
    ("RHipJoint", 0, (-0.09, -0.05, 0.0)),
    ("RightUpLeg", 6, (0.0, -0.02, 0.0)),
    ("RightLeg", 7, (0.0, -0.42, 0.0)),
    ("RightFoot", 8, (0.0, -0.40, 0.0)),
    ("RightToeBase", 9, (0.0, -0.04, 0.12)),
    ("LowerBack", 0, (0.0, 0.1, 0.0)),
    ("Spine", 11, (0.0, 0.2, 0.0)),
    ("Neck", 12, (0.0, 0.2, 0.0)),
    ("Head", 13, (0.0, 0.12, 0.0)),
    ("LeftShoulder", 12, (0.05, 0.18, 0.0)),
    ("LeftArm", 15, (0.15, 0.0, 0.0)),
    ("LeftForeArm", 16, (0.28, 0.0, 0.0)),
    ("LeftHand", 17, (0.25, 0.0, 0.0)),
    ("RightShoulder", 12, (-0.05, 0.18, 0.0)),
    ("RightArm", 19, (-0.15, 0.0, 0.0)),
    ("RightForeArm", 20, (-0.28, 0.0, 0.0)),
    ("RightHand", 21, (-0.25, 0.0, 0.0)),
)


def make_skeleton(without_toes: bool = False, scale: float = 1.0):
    import numpy as np

    from text2anim.core import Skeleton

    joints = [j for j in CMU_LIKE_JOINTS if not (without_toes and "Toe" in j[0])]
    names = [j[0] for j in joints]
    old_names = [j[0] for j in CMU_LIKE_JOINTS]
    parents = [-1 if p < 0 else names.index(old_names[p]) for _, p, _ in joints]
    offsets = np.array([o for _, _, o in joints]) * scale
    head = names.index("Head")
    return Skeleton(names, parents, offsets, end_sites=((head, np.array([0.0, 0.1, 0.0])),))


def make_motion(frames: int = 24, fps: float = 30.0, seed: int = 0, *, skeleton=None,
                translations: bool = False, speed: float = 0.0):
    """A small deterministic motion: hips at 0.96 m, gentle joint rotations, moving forward at ``speed`` m/s."""
    import numpy as np
    from scipy.spatial.transform import Rotation

    from text2anim.core import Motion

    skel = skeleton if skeleton is not None else make_skeleton()
    rng = np.random.default_rng(seed)
    J = skel.n_joints
    t = np.arange(frames) / fps
    rotvec = 0.05 * rng.standard_normal((1, J, 3)) * np.sin(2 * np.pi * t)[:, None, None]
    rots = Rotation.from_rotvec(rotvec.reshape(-1, 3)).as_quat().reshape(frames, J, 4)
    root = np.stack([np.zeros(frames), np.full(frames, 0.96), speed * t], axis=1)
    trans = None
    if translations:
        trans = np.broadcast_to(skel.offsets, (frames, J, 3)) + 0.001 * rng.standard_normal((frames, J, 3))
    return Motion(skel, fps, root, rots, trans)


@pytest.fixture
def record():
    """``record(name, verbs, **fields)``: a :class:`ClipRecord` with a small synthetic motion."""
    from text2anim.motiondb import ClipRecord

    def make(name: str, verbs=("歩く",), *, seed: int | None = None, frames: int = 24, fps: float = 30.0,
             skeleton=None, translations: bool = False, **fields):
        motion = make_motion(frames, fps, seed if seed is not None else sum(map(ord, name)),
                             skeleton=skeleton, translations=translations)
        return ClipRecord(name=name, motion=motion, verbs=tuple(verbs), **fields)

    return make


@pytest.fixture
def empty_db(db_url):
    """An open, empty database (created without the built-in library) on each backend."""
    from text2anim.motiondb import MotionDB

    db = MotionDB.open(db_url, seed=False)
    yield db
    db.close()


@pytest.fixture(scope="session", autouse=True)
def _private_default_database(tmp_path_factory):
    """No test writes to the user's data or cache directory: the default database and the cache
    (the built-in library's tag) live in temp folders."""
    path = tmp_path_factory.mktemp("default-db") / "motions.sqlite"
    given = {"TEXT2ANIM_DB": str(path), "XDG_CACHE_HOME": str(tmp_path_factory.mktemp("cache"))}
    old = {k: os.environ.get(k) for k in given}
    os.environ.update(given)
    yield path
    for k, v in old.items():
        if v is None:
            os.environ.pop(k, None)
        else:
            os.environ[k] = v


@pytest.fixture(scope="session")
def library_db(tmp_path_factory) -> str:
    """URL of an SQLite database seeded with the built-in library (shared by the session's tests)."""
    from text2anim.motiondb import MotionDB

    url = f"sqlite:///{tmp_path_factory.mktemp('library-db') / 'motions.sqlite'}"
    MotionDB.open(url).close()
    return url


@pytest.fixture(scope="session")
def walk(library_db):
    """太郎は歩く。 animated with the built-in library (the animation the rig and glTF exports are checked on)."""
    import text2anim

    return text2anim.animate("太郎は歩く。", db=library_db)


@pytest.fixture(scope="session")
def walk_motion(walk):
    """The one actor's motion of :func:`walk`, as the engines made it."""
    (motion,) = walk.motions.values()
    return motion


@pytest.fixture
def strict(caplog):
    """No Python warnings and no matplotlib log warnings (missing glyphs, font fallbacks, fixed limits) while a
    figure is drawn."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with caplog.at_level(logging.WARNING, logger="matplotlib"):
            yield
    assert [r.getMessage() for r in caplog.records if r.name.startswith("matplotlib")] == []
