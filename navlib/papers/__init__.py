"""Paper companions and the registry of the reproduced papers.

Each paper has one name, used for its notebook (``notebooks/NN_<name>.ipynb``; a paper taught in several
lessons adds ``NN_<name>_<part>.ipynb``, :attr:`Paper.parts`), its
companion module (``navlib.papers.<name>``) and its entry here; its claims and errata in
``data/claims.csv`` / ``data/errata.csv`` carry the paper's ``claims_id`` (``P000-...``).

A companion holds only what its paper names: its equations (also the misprinted ones,
to show the misprint), its scenario and the assembly of core filters it describes. It
imports core modules only -- never another companion -- and generic machinery goes to
core (see CONTRIBUTING.md). ``tools/reproduce.py``, ``tools/readme.py`` and the tests read
:data:`PAPERS`; a notebook that is not registered fails the tests.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated

from .._validate import Check, Text, boundary, fields_checked

__all__ = ["Paper", "PAPERS", "CONVENTIONS", "REAL_DATA", "REAL_REFERENCES", "CHAPTERS", "by_notebook"]


@dataclass(frozen=True)
class Paper:
    """One reproduced paper.

    Attributes
    ----------
    name : str
        The paper's one name: notebook ``NN_<name>``, module ``navlib.papers.<name>``.
    number : int
        The notebook number NN.
    claims_id : str
        The paper column of ``data/claims.csv`` and ``data/errata.csv`` (claim ids ``P<claims_id>-...``).
    citation : str
        Short citation shown in the README and the report.
    parts : tuple of str
        The further notebooks of a paper taught in more than one lesson, ``NN_<name>_<part>`` each; the paper's
        claims are split between its notebooks, each claim given its verdict in one of them.

    Examples
    --------
    >>> from navlib import papers
    >>> paper = papers.by_notebook("03_gauss_kruger_ekf")
    >>> paper.number, paper.claims_id, paper.name
    (3, '002', 'gauss_kruger_ekf')
    """

    name: str
    number: Annotated[int, Check("integer", minimum=0)]
    claims_id: Annotated[str, Check("text", empty=False)]
    citation: Annotated[str, Check("text", empty=False)]
    parts: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.isidentifier():  # type: ignore[redundant-expr]  # the caller's argument, checked
            raise ValueError(f"name: expected the paper's module name (a Python identifier), got {self.name!r}")
        fields_checked(self)
        if not isinstance(self.parts, tuple) or not all(isinstance(p, str) and p.isidentifier() for p in self.parts):  # type: ignore[redundant-expr]  # the caller's argument, checked
            raise ValueError(f"parts: expected a tuple of notebook suffixes such as ('floors',), got {self.parts!r}")

    @property
    def notebook(self) -> str:
        """Notebook stem, e.g. ``01_north_finding``."""
        return f"{self.number:02d}_{self.name}"

    @property
    def notebooks(self) -> tuple[str, ...]:
        """Every notebook stem of the paper, :attr:`notebook` first."""
        return (self.notebook, *(f"{self.notebook}_{part}" for part in self.parts))

    @property
    def module(self) -> str:
        """Companion module, e.g. ``navlib.papers.north_finding``."""
        return f"navlib.papers.{self.name}"


CONVENTIONS = "00_conventions_sensors"
"""Notebook 00: conventions and sensor-model validation (no paper)."""
REAL_DATA = "06_real_recordings"
"""Notebook 06: the methods on public real recordings (no paper)."""
REAL_REFERENCES = "07_real_references"
"""Notebook 07: attitude filters against an optical reference (BROAD benchmark; no paper)."""
CHAPTERS: dict[str, str] = {
    CONVENTIONS: "conventions, sensor models, strapdown error theory",
    REAL_DATA: "the methods on public real recordings (data/real/)",
    REAL_REFERENCES: "attitude filters against motion-capture references (BROAD)",
}
"""The notebooks that reproduce no paper, with their one-line titles."""

PAPERS: tuple[Paper, ...] = (
    Paper("north_finding", 1, "000", "Tan & Xie — single-axis optical gyro + MEMS IMU north finding"),
    Paper("rotation_bias", 2, "001", "Wu, Sun, Zhang & Chen 2014 — gyro bias estimation by rotating the IMU"),
    Paper("gauss_kruger_ekf", 3, "002", "Zhao, Nie, Fang & Wu 2023 — Gauss–Krüger projection + EKF INS/GPS"),
    Paper("mimu_mag_rtk", 4, "003", "Zhang, Wu & Yun 2023 — MIMU / magnetometer / dual-antenna RTK attitude"),
    Paper("pedestrian_ins", 5, "004", "Wen, Xu & Yu 2016 — shoulder-mounted MEMS IMU indoor navigation", parts=("floors",)),
)


@boundary
def by_notebook(stem: Text) -> Paper | None:
    """The registered paper of a notebook stem (any of its :attr:`Paper.notebooks`), or None (notebook 00 has no paper).

    Examples
    --------
    >>> from navlib import papers
    >>> papers.by_notebook("04_mimu_mag_rtk").citation[:13], papers.by_notebook("05_pedestrian_ins_floors").number
    ('Zhang, Wu & Y', 5)
    """
    return next((p for p in PAPERS if stem in p.notebooks), None)
