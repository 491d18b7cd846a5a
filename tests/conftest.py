"""Shared test configuration: ``tests/`` on the import path for ``helpers``."""
