"""The time table as the paper prints it (section 5.2), plus start and end times."""
from __future__ import annotations

from .types import Element, TimeTable

_METHOD_NAMES = {"initial": "初期動作", "connection": "Connection", "transition": "Transition",
                 "composition": "Composition"}
#: docs/language.md §8's target roles and sides in the table's own words.
_ROLES = {"goal": "行き先", "source": "出発点", "addressee": "相手", "patient": "相手", "recipient": "受け手",
          "partner": "一緒にする相手", "support": "支え", "destination": "置き場所", "at": "場所"}
_SIDES = {"front": "前", "behind": "後ろ", "beside": "隣", "near": "そば", "on": "上", "left": "左", "right": "右"}


def format_table(table: TimeTable) -> str:
    """One block per element: 要素 / 動作主格 / 動作データ / 動作名 / 接続形式 / 前要素 / 開始 / 終了."""
    out = [f"入力: 「{table.text}」", ""]
    for e in table.elements:
        out.append(f"[要素 {e.id}]")
        out.append(f"  動作主格  {e.actor or '(既定のキャラクター)'}")
        part = f"  (部位: {e.body_part})" if e.body_part else ""
        out.append(f"  動作データ {e.clip}{part}")
        out.append(f"  動作名    {e.verb}")
        if e.object:
            out.append(f"  対象物    {e.object}")
        if e.target:
            side = f" ({_SIDES.get(e.target_side, e.target_side)})" if e.target_side else ""
            out.append(f"  相手/場所 {e.target}{side} [{_ROLES.get(e.target_role or '', e.target_role)}]")
        if e.manner:
            out.append(f"  様態      {_manner(e)}")
        out.append(f"  接続形式  {_METHOD_NAMES[e.method]}")
        if e.prev is not None:
            out.append(f"  前要素    要素 {e.prev}")
        out.append(f"  開始      {e.start:.2f} s")
        out.append(f"  終了      {e.end:.2f} s")
        out.append("")
    return "\n".join(out).rstrip() + "\n"


def _manner(e: Element) -> str:
    """疲れて: tired 1.4 (modifiers, speed 0.732); にこにこ: no style (not shown)."""
    m = e.manner
    assert m is not None
    if m.style is None:
        return f"{m.word}: no style (not shown)"
    by = "a clip of the style" if m.by == "clip" else "modifiers"
    return f"{m.word}: {m.style} {m.intensity:g} ({by}, speed {e.speed:g})"
