"""The Japanese font the package ships, and a page's subset of it.

``fontdata/NotoSansCJKjp-JIS0208.otf`` is Noto Sans CJK JP Regular (SIL Open Font License 1.1, the
licence beside it) cut down to JIS X 0208 (every kana, the 6,355 kanji of levels 1 and 2, full-width
forms) and ASCII: 1.5 MB (1.3 MB zipped in the wheel) instead of the 19 MB collection; made by
``tools/build_jp_font.py``. A machine without a Japanese font showed the viewer page's names, verbs and
time table as boxes: :func:`font_face_css` embeds, in each page, a WOFF subset of it for the
characters that page shows (a few KB for a sentence: 5.3 KB for ``太郎は走って、ボールを蹴る。``), and
contact sheets draw Japanese with the file itself when the machine has no CJK font (:mod:`.fonts`).
A character outside JIS X 0208 (a rare kanji) is left to the browser's own fonts.

fontTools makes the subsets (a dependency of the package; matplotlib needs it as well).
"""
from __future__ import annotations

import base64
import io
from functools import lru_cache
from importlib import resources
from pathlib import Path

#: The font file (in the installed package).
FONT_FILE = "NotoSansCJKjp-JIS0208.otf"
#: Its family name, as matplotlib and the font's name table call it.
FAMILY = "Noto Sans CJK JP JIS0208"
#: The family name a page gives its embedded subset. The page's CSS lists it first: listed after the system
#: fonts, Chromium laid the title out with the Latin font's boxes before the subset had loaded and kept them.
PAGE_FAMILY = "t2a-jp"


def font_path() -> Path:
    """The shipped font file."""
    return Path(str(resources.files(__package__).joinpath("fontdata").joinpath(FONT_FILE)))


@lru_cache(maxsize=1)
def covered() -> frozenset[int]:
    """The code points the shipped font draws."""
    from fontTools.ttLib import TTFont

    return frozenset(TTFont(font_path(), lazy=True).getBestCmap())


#: The first code point of the CJK blocks (radicals, punctuation, kana, ideographs, full-width forms): the
#: characters a Latin system font lacks. Below it (…, ←, ×) every system font draws them.
CJK_FROM = 0x2E80


def page_chars(text: str) -> str:
    """The characters of ``text`` the embedded font is for: CJK (:data:`CJK_FROM`) that the shipped font has,
    sorted."""
    have = covered()
    return "".join(sorted({c for c in text if ord(c) >= CJK_FROM and ord(c) in have}))


def subset_woff(chars: str) -> bytes:
    """A WOFF font of the shipped font's glyphs for ``chars`` (no hinting, no layout features)."""
    from fontTools import subset
    from fontTools.ttLib import TTFont

    font = TTFont(font_path(), recalcTimestamp=False)
    opts = subset.Options()
    opts.layout_features = []
    opts.hinting = False
    opts.name_IDs = [0, 1, 2, 3, 4, 5, 6, 13, 14]  # the copyright and licence stay with the font
    opts.notdef_outline = True
    sub = subset.Subsetter(opts)
    sub.populate(text=chars)
    sub.subset(font)
    font.flavor = "woff"
    buf = io.BytesIO()
    font.save(buf)
    return buf.getvalue()


def font_face_css(text: str) -> str:
    """An ``@font-face`` rule of family :data:`PAGE_FAMILY` with the glyphs ``text`` needs (a data URL), or
    ``""`` when it needs none (an all-ASCII page)."""
    chars = page_chars(text)
    if not chars:
        return ""
    data = base64.b64encode(subset_woff(chars)).decode("ascii")
    return (f'@font-face {{ font-family: "{PAGE_FAMILY}"; font-display: block; unicode-range: U+{CJK_FROM:X}-FFFF; '
            f'src: url(data:font/woff;base64,{data}) format("woff"); }}')
