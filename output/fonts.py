"""Which text the installed fonts can draw, for figures with Japanese labels.

matplotlib's default font (DejaVu Sans) has no CJK glyphs: Japanese drawn with it comes out as
boxes. :func:`available` finds a CJK font that matplotlib knows (Noto Sans CJK JP from Debian's
``fonts-noto-cjk``, IPAexGothic, Hiragino, Yu Gothic, ...; none is ever installed at run time), or one
installed after matplotlib cached its font list, by file name (:mod:`.fontfiles`), else the subset of
Noto Sans CJK JP the package ships (:mod:`.embedded_font`: kana and the JIS X 0208 kanji), and
the code points the base font and it can draw, read from the font files' character maps.
:func:`label` then picks what to draw: the text when every character can be drawn, else an
alternative (a clip name, a romanised reading), else the text without what cannot be drawn.

matplotlib is imported only when :func:`available` is first called (figures need it anyway).
"""
from __future__ import annotations

import dataclasses
import re
from functools import lru_cache

#: Families tried, in order, for Japanese text.
CJK_FAMILIES = ("Noto Sans CJK JP", "Noto Sans JP", "IPAexGothic", "IPAPGothic", "IPAGothic", "TakaoPGothic",
                "TakaoGothic", "VL PGothic", "VL Gothic", "Source Han Sans JP", "Source Han Sans",
                "Hiragino Sans", "Hiragino Kaku Gothic ProN", "Yu Gothic", "Meiryo", "MS Gothic",
                "Noto Sans CJK SC", "Noto Sans CJK TC", "WenQuanYi Zen Hei", "Droid Sans Fallback")
#: matplotlib's default family, always first.
BASE_FAMILY = "DejaVu Sans"


@lru_cache(maxsize=1)
def available() -> tuple[str | None, frozenset[int]]:
    """The CJK family matplotlib will fall back to (``None`` when it knows none) and the code
    points that :data:`BASE_FAMILY` and that family can draw together."""
    from matplotlib import font_manager
    from matplotlib.ft2font import FT2Font

    by_name: dict[str, str] = {}
    for f in font_manager.fontManager.ttflist:
        by_name.setdefault(f.name, f.fname)
    chars: set[int] = set()
    cjk = next((fam for fam in CJK_FAMILIES if fam in by_name), None)
    if cjk is None:  # installed after matplotlib cached its font list? found by file name (:mod:`.fontfiles`)
        cjk = _load_cjk_file(font_manager, by_name)
    if cjk is None:  # none on this machine: the one the package ships (:mod:`.embedded_font`)
        cjk = _load_shipped(font_manager, by_name)
    for fam in (BASE_FAMILY, cjk):
        if fam is None:
            continue
        path = by_name.get(fam) or font_manager.findfont(fam, fallback_to_default=True)
        try:
            chars.update(FT2Font(path).get_charmap())
        except Exception:  # an unreadable font file: rely on the other
            continue
    return cjk, frozenset(chars)


def _load_cjk_file(font_manager, by_name: dict[str, str]) -> str | None:
    """The family of the first CJK font file matplotlib can load (:func:`.fontfiles.cjk_font_files`), now
    known to ``font_manager`` (and put in ``by_name``); ``None`` when there is none."""
    from . import fontfiles

    for path in fontfiles.cjk_font_files():
        try:
            name = font_manager.FontProperties(fname=str(path)).get_name()
            for weight in fontfiles.weights_of(path):  # bold too: bold titles without a fallback warning
                font_manager.fontManager.addfont(str(weight))
        except Exception:  # an unreadable font file: try the next
            continue
        by_name.setdefault(name, str(path))
        return name
    return None


def _load_shipped(font_manager, by_name: dict[str, str]) -> str | None:
    """The family of the package's own Japanese font, now known to ``font_manager``; ``None`` if it
    cannot be loaded (a damaged install)."""
    from . import embedded_font

    path = embedded_font.font_path()
    try:
        font_manager.fontManager.addfont(str(path))
    except Exception:
        return None
    regular = next(f for f in reversed(font_manager.fontManager.ttflist) if f.fname == str(path))
    # one weight only: bold titles take the regular glyphs rather than warning that bold is missing
    font_manager.fontManager.ttflist.append(dataclasses.replace(regular, weight=700))
    by_name.setdefault(embedded_font.FAMILY, str(path))
    return embedded_font.FAMILY


def families() -> list[str]:
    """``font.family`` for matplotlib: the base family, then the CJK one when there is one."""
    cjk = available()[0]
    return [BASE_FAMILY] + ([cjk] if cjk else [])


def drawable(text: str, chars: frozenset[int] | None = None) -> bool:
    """True when every character of ``text`` (white space aside) is in ``chars`` (default: :func:`available`)."""
    chars = available()[1] if chars is None else chars
    return all(c.isspace() or ord(c) in chars for c in text)


def label(text: str, alt: str | None = None, fallback: str = "?", chars: frozenset[int] | None = None) -> str:
    """``text`` if it can be drawn, else ``alt`` if that can, else ``text`` without what cannot be
    drawn (empty brackets and stray separators removed), else ``fallback``."""
    chars = available()[1] if chars is None else chars
    text = str(text)
    if drawable(text, chars):
        return text
    if alt and drawable(alt, chars):
        return alt
    kept = "".join(c for c in text if drawable(c, chars))
    kept = re.sub(r"\(\s*\)|\[\s*\]", "", kept)
    kept = re.sub(r"(^|[\s:(])/+|/+(?=[\s)]|$)", r"\1", kept)  # a slash that separated dropped words
    kept = re.sub(r"\s+", " ", kept).strip(" -_:/")
    return kept if re.search(r"\w", kept) else fallback
