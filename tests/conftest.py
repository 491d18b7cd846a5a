"""Shared test configuration.

The reference vectors (published PROJ, NOAA WMM, WGS84 gravity, ISA/BMP180
values) live in ``../shared/vectors`` beside the repository. Locally, tests
that need them skip with a reason when the folder is absent; under CI
(``CI`` set) a missing folder is an error, so the cross-checks cannot be
skipped silently.
"""
import os
import pytest

from helpers import VECTORS


def pytest_sessionstart(session):
    if os.environ.get("CI") and not VECTORS.is_dir():
        raise pytest.UsageError(f"reference vectors not found at {VECTORS}; CI must run with shared/ beside the repo")
