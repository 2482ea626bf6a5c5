"""Names retired: each still works, with a ``DeprecationWarning`` that gives the name now.

Every quantity has one name in every front end (docs/library.md, "One name per quantity"):
the CSV column, the JSON key, the attribute. Where Python cannot use the column's name (the
motion class's ``class`` is a keyword) the attribute is ``motion_class``; ``result["class"]``
works as well.
"""

from __future__ import annotations

import warnings
from typing import Any, Callable, Dict, Optional, TypeVar

T = TypeVar("T")


def warn_renamed(owner: str, old: str, new: str, stacklevel: int = 3) -> None:
    """Warn that ``owner.old`` is now ``owner.new``."""
    warnings.warn(f"{owner}.{old} is deprecated: its name is now {new}", DeprecationWarning,
                  stacklevel=stacklevel)


class Renamed:
    """An attribute retired: reading it warns and gives the attribute ``new`` (or, with
    ``convert``, ``convert(self)``)."""

    def __init__(self, new: str, convert: Optional[Callable[[Any], Any]] = None) -> None:
        self.new = new
        self.convert = convert
        self.old = new

    def __set_name__(self, owner: type, name: str) -> None:
        self.old = name

    def __get__(self, obj: Any, owner: Optional[type] = None) -> Any:
        if obj is None:
            return self
        warn_renamed(type(obj).__name__, self.old, self.new)
        return self.convert(obj) if self.convert is not None else getattr(obj, self.new)


def renamed_key(owner: str, name: str, retired: Dict[str, str]) -> str:
    """The key ``name`` of ``owner[name]``, with a warning when it is a retired one (``retired``
    maps it to its name now)."""
    if name in retired:
        warn_renamed(owner, f'["{name}"]', f'["{retired[name]}"]', stacklevel=4)
        return retired[name]
    return name
