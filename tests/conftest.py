"""Shared test configuration: ``tests/`` on the import path for ``helpers``; deterministic hypothesis.

Property tests draw their examples from a fixed seed (``derandomize=True``), so two runs of
``make test`` exercise the same cases and CI cannot fail by chance. To explore new random
examples locally: ``pytest --hypothesis-profile=explore tests/test_properties.py``.
"""
from hypothesis import settings

settings.register_profile("navlib", derandomize=True, database=None)
settings.register_profile("explore", derandomize=False)
settings.load_profile("navlib")
