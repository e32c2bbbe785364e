"""What each thing a text names looks like in the scene: a simple shape, its size and colour.

Sizes are metres ``(w, h, d)`` of the shape's bounding box, for a person of the built-in body's size (the
scene scales them with the actor). A noun not listed is drawn as a small box and said to be a stand-in
(:attr:`scene.types.Thing.known`); a place (駅, 部屋, 公園: the goal of a walk) as a flat marker.
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Shape:
    """A shape of :data:`output.viewer.types.PROP_SHAPES`, its size ``(w, h, d)`` m, colour and how it is held
    (``"one"``: in the right hand, ``"both"``: between the hands)."""

    shape: str
    size: tuple[float, float, float]
    color: str
    grip: str = "one"


_BALL = Shape("sphere", (0.22, 0.22, 0.22), "#e8e8e8")
_BOX = Shape("box", (0.4, 0.3, 0.3), "#b08850", "both")
_BOOK = Shape("book", (0.17, 0.24, 0.03), "#3d6fb6", "both")
_CUP = Shape("cup", (0.08, 0.1, 0.08), "#f0f0f0")
_CHAIR = Shape("chair", (0.45, 0.9, 0.45), "#8a5a2b")
_BENCH = Shape("bench", (1.4, 0.45, 0.4), "#8a5a2b")
_TABLE = Shape("box", (1.0, 0.72, 0.6), "#9c7a4e")
_DOOR = Shape("door", (0.9, 2.0, 0.04), "#c4a574")
_STICK = Shape("stick", (0.03, 0.9, 0.03), "#404040")
_PHONE = Shape("box", (0.07, 0.14, 0.01), "#202020")
_CART = Shape("box", (0.6, 0.35, 0.9), "#7a7a7a")
_PEN = Shape("stick", (0.012, 0.15, 0.012), "#1f3f8f")
_TREE = Shape("cylinder", (0.35, 3.0, 0.35), "#6b4f2a")
_SHELF = Shape("box", (0.8, 1.2, 0.35), "#9c7a4e")
_BOARD = Shape("box", (1.8, 1.9, 0.05), "#2f4f3a")

SHAPES: dict[str, Shape] = {
    **dict.fromkeys("ボール サッカーボール 球 たま 鞠 バスケットボール バレーボール".split(), _BALL),
    **dict.fromkeys("箱 はこ 荷物 段ボール ダンボール 箱物 プレゼント".split(), _BOX),
    **dict.fromkeys("本 ほん 雑誌 ノート 手紙 新聞 絵本 教科書 書類".split(), _BOOK),
    **dict.fromkeys("カップ コップ コーヒー お茶 茶 水 ジュース 牛乳 グラス 湯呑み ビール".split(), _CUP),
    **dict.fromkeys("椅子 いす イス チェア ソファ ソファー".split(), _CHAIR),
    **dict.fromkeys("ベンチ 長椅子".split(), _BENCH),
    **dict.fromkeys("机 つくえ テーブル 台 机の上".split(), _TABLE),
    **dict.fromkeys("ドア 扉 戸 とびら 窓 まど".split(), _DOOR),
    **dict.fromkeys("傘 かさ 棒 バット 杖 ほうき 箒 花".split(), _STICK),
    **dict.fromkeys("ペン 鉛筆 ボールペン 筆".split(), _PEN),
    **dict.fromkeys("電話 スマホ 携帯 携帯電話 スマートフォン".split(), _PHONE),
    **dict.fromkeys("木 樹 樹木 大木 桜 桜の木".split(), _TREE),
    **dict.fromkeys("台車 カート 手押し車 リヤカー 荷車".split(), _CART),
    **dict.fromkeys("棚 本棚 戸棚 食器棚".split(), _SHELF),
    **dict.fromkeys("黒板 ホワイトボード 掲示板".split(), _BOARD),
}
#: What is looked at but is no thing on the floor: the sky and what is above or all around (空を見上げる).
UNDRAWN = frozenset("空 そら 星 月 太陽 雲 天井 景色 風景 夜空 青空".split())
#: A noun the scene has no shape for.
STAND_IN = Shape("box", (0.2, 0.2, 0.2), "#c8b27a")
#: A place (the goal of a walk): a flat marker on the floor.
PLACE = Shape("box", (0.8, 0.02, 0.8), "#5b8c5a")


def shape_of(noun: str) -> tuple[Shape, bool]:
    """The shape of ``noun`` and whether it is its own (``False``: :data:`STAND_IN`)."""
    found = SHAPES.get(noun)
    return (found, True) if found is not None else (STAND_IN, False)
