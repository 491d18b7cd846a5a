"""Shared test configuration: ``tests/`` on the import path for ``helpers``; deterministic hypothesis.

Property tests draw their examples from a fixed seed (``derandomize=True``), so two runs of
``make test`` exercise the same cases and CI cannot fail by chance. To explore new random
examples locally: ``pytest --hypothesis-profile=explore tests/test_properties.py``.
"""

import pytest
from hypothesis import settings

settings.register_profile("navlib", derandomize=True, database=None)
settings.register_profile("explore", derandomize=False)
settings.load_profile("navlib")


@pytest.fixture
def ax():
    """A fresh 2-D matplotlib Axes on the Agg backend, closed afterwards (the chapters' drawing tests)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots()
    yield axes
    plt.close(fig)
