"""Derive ``nlp/verb_meaning.npz`` (word vectors of Japanese verbs) from ja_ginza's chiVe vectors.

The word vectors shipped inside the spaCy model package ``ja-ginza`` (MIT) are
chiVe (Works Applications, Apache-2.0): 300-d word2vec vectors trained on the
NINJAL Web Japanese Corpus, pruned by GiNZA to 20 000 rows (the 480 443 keys
share those rows; a pruned word points to the row of its nearest kept word).

This script keeps the keys that are verbs or サ変 nouns (and the words of the
built-in library's verbs), reduces their rows by a truncated SVD to ``DIMS``
dimensions, re-normalises them and stores them as int8 (x 127).  At run time
``text2anim.nlp.meaning`` compares words by the cosine of these vectors; the
file is about 1 MB and loads in a few milliseconds with numpy alone.

Usage (needs ``msgpack``; spaCy itself is not needed)::

    pip download --no-deps ja-ginza==5.3.0 -d /tmp/ginza
    python tools/derive_meaning.py /tmp/ginza/ja_ginza-5.3.0-py3-none-any.whl

Output is deterministic for one wheel.
"""
from __future__ import annotations

import argparse
import glob
import hashlib
import json
import struct
import sys
import zipfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "nlp" / "verb_meaning.npz"
DIMS = 128
MAX_CHARS = 10
_M64 = (1 << 64) - 1


def murmurhash64a(text: str, seed: int = 1) -> int:
    """spaCy's string hash (MurmurHash64A of the UTF-8 bytes, seed 1): the keys of key2row."""
    data = text.encode("utf8")
    m, r, n = 0xC6A4A7935BD1E995, 47, len(data)
    h = (seed ^ (n * m)) & _M64
    for i in range(n // 8):
        k = struct.unpack_from("<Q", data, i * 8)[0]
        k = (k * m) & _M64
        k ^= k >> r
        k = (k * m) & _M64
        h = ((h ^ k) * m) & _M64
    tail = data[n // 8 * 8:]
    for i in reversed(range(len(tail))):
        h ^= tail[i] << (8 * i)
    if tail:
        h = (h * m) & _M64
    h ^= h >> r
    h = (h * m) & _M64
    return h ^ (h >> r)


def read_wheel(path: str) -> tuple[np.ndarray, dict[int, int], list[str], str]:
    """(vectors (R, 300) float32, key hash -> row, strings, wheel sha256) of a ja_ginza wheel."""
    import io

    import msgpack

    raw = Path(path).read_bytes()
    with zipfile.ZipFile(io.BytesIO(raw)) as z:
        vocab = next(n for n in z.namelist() if n.endswith("/vocab/vectors")).rsplit("/", 1)[0]
        vectors = np.load(io.BytesIO(z.read(vocab + "/vectors")), allow_pickle=False)
        key2row = msgpack.unpackb(z.read(vocab + "/key2row"), strict_map_key=False)
        strings = json.loads(z.read(vocab + "/strings.json"))
    return vectors, key2row, strings, hashlib.sha256(raw).hexdigest()


def library_words() -> set[str]:
    """Words of the built-in library's verbs (ジャンプ of ジャンプする, 振る of 手を振る)."""
    import fugashi

    tagger = fugashi.Tagger()
    words = set()
    for f in sorted(glob.glob(str(ROOT / "motiondb" / "library" / "clips" / "*.json"))):
        data = json.loads(Path(f).read_text(encoding="utf-8"))
        for clip in data.get("clips", [data]):
            for verb in clip.get("verbs", []):
                for w in tagger(verb):
                    if w.feature.pos1 in ("動詞", "名詞"):
                        words.update({w.feature.orthBase or w.surface, (w.feature.lemma or "").split("-")[0]})
    return {w for w in words if w}


def select(strings: list[str], key2row: dict[int, int]) -> list[tuple[str, int]]:
    """(word, row) of every key that is one verb (in its dictionary form) or one サ変 noun."""
    import fugashi

    tagger = fugashi.Tagger()
    extra = library_words()
    out = []
    for s in strings:
        if not s or len(s) > MAX_CHARS:
            continue
        h = murmurhash64a(s)
        if h not in key2row:
            continue
        words = tagger(s)
        if len(words) != 1:
            continue
        f = words[0].feature
        verb = f.pos1 == "動詞" and f.orthBase == s
        sahen = f.pos1 == "名詞" and f.pos3 == "サ変可能"
        if verb or sahen or s in extra:
            out.append((s, key2row[h]))
    return sorted(set(out))


def reduce(vectors: np.ndarray, rows: list[int]) -> tuple[np.ndarray, list[int]]:
    """Unit rows of ``vectors`` reduced by truncated SVD to ``DIMS``, as int8 ``(R', DIMS)``."""
    uniq = sorted(set(rows))
    x = vectors[uniq].astype(np.float64)
    x /= np.maximum(np.linalg.norm(x, axis=1, keepdims=True), 1e-12)
    _, _, vt = np.linalg.svd(x, full_matrices=False)
    y = x @ vt[:DIMS].T
    y /= np.maximum(np.linalg.norm(y, axis=1, keepdims=True), 1e-12)
    index = {r: i for i, r in enumerate(uniq)}
    return np.round(y * 127).astype(np.int8), [index[r] for r in rows]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("wheel", help="ja_ginza-5.3.0-py3-none-any.whl (pip download --no-deps ja-ginza==5.3.0)")
    ap.add_argument("-o", "--out", default=str(OUT))
    args = ap.parse_args(argv)
    vectors, key2row, strings, sha = read_wheel(args.wheel)
    chosen = select(strings, key2row)
    q, rows = reduce(vectors, [r for _, r in chosen])
    words = np.array([w for w, _ in chosen])
    source = (f"chiVe word vectors as shipped in {Path(args.wheel).name} (sha256 {sha}); "
              f"verbs and サ変 nouns, truncated SVD to {DIMS} dims, int8; tools/derive_meaning.py")
    np.savez_compressed(args.out, words=words, rows=np.array(rows, dtype=np.int32), vectors=q,
                        source=np.array(source))
    print(f"{len(words)} words, {q.shape[0]} vectors x {q.shape[1]} -> {args.out} "
          f"({Path(args.out).stat().st_size / 1e6:.2f} MB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
