"""Unchecked construction of navlib's frozen records.

A record (a frozen dataclass such as :class:`navlib.trajectory.Trajectory`) checks its fields in ``__post_init__``
when a user builds it. A builder function that has checked its arguments and computed the fields from them (e.g.
:func:`navlib.trajectory.from_profiles`) builds the record here instead, so that nothing is checked twice on one
call and a bad argument is refused by the builder, under the name the user gave it.
"""

from __future__ import annotations

import dataclasses
from typing import Any, TypeVar

_R = TypeVar("_R")


def unchecked(cls: type[_R], /, **fields: Any) -> _R:
    """``cls(**fields)`` without ``__post_init__``: the fields given are set as they are, the others to their defaults.

    ``fields`` must hold what the record's checks would return (e.g. float arrays of the documented shapes).
    """
    record = object.__new__(cls)
    known = dataclasses.fields(cls)  # type: ignore[arg-type]  # cls is a dataclass
    if unknown := fields.keys() - {f.name for f in known}:
        raise TypeError(f"{cls.__name__} has no fields {sorted(unknown)}")
    for f in known:
        if f.name in fields:
            value = fields[f.name]
        elif f.default is dataclasses.MISSING:
            value = f.default_factory()  # type: ignore[operator]  # the record's required fields are always given
        else:
            value = f.default
        object.__setattr__(record, f.name, value)
    return record
