"""How an element of the time table joins the element before it (docs/timetable.md §1).

The one vocabulary of the scheduler (which writes it into the time table) and the
synthesis engines (which join the clips so): ``initial`` starts a track,
``connection`` follows the previous element after it ends, ``transition``
overlaps its end, ``composition`` lays a body part onto it.
"""
from __future__ import annotations

from typing import Literal, get_args

Method = Literal["initial", "connection", "transition", "composition"]
#: Every :data:`Method`, in this order. (``METHODS`` is another vocabulary: the joining methods,
#: :data:`text2anim.synthesis.registry.METHODS`.)
ELEMENT_METHODS: tuple[Method, ...] = get_args(Method)
