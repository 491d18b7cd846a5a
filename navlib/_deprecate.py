"""Renamed keyword arguments, kept one release as warning aliases (see CONTRIBUTING.md, "Deprecated names")."""
from __future__ import annotations

import functools
import warnings
from collections.abc import Callable


def renamed_keywords(**old_to_new: str) -> Callable:
    """Decorator: accept each old keyword with a ``DeprecationWarning`` and pass it on under its new name.

    Giving both the old and the new name is a ``ValueError`` naming the old one.
    """
    def decorate(func: Callable) -> Callable:
        @functools.wraps(func)
        def wrapper(*args, **kwargs):
            for old, new in old_to_new.items():
                if old in kwargs:
                    warnings.warn(f"{func.__name__}({old}=...) is deprecated and will be removed in navlib 0.3; "
                                  f"use {new}=", DeprecationWarning, stacklevel=2)
                    if new in kwargs:
                        raise ValueError(f"{old}: give the value once, as {new}")
                    kwargs[new] = kwargs.pop(old)
            return func(*args, **kwargs)
        return wrapper
    return decorate
