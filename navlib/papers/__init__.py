"""Paper companions and the registry of the reproduced papers.

Each paper has one name, used for its notebook (``notebooks/NN_<name>.ipynb``), its
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

from .._validate import integer, text

__all__ = ["Paper", "PAPERS", "CONVENTIONS", "REAL_DATA", "REAL_REFERENCES", "CHAPTERS", "by_notebook"]


@dataclass(frozen=True)
class Paper:
    """One reproduced paper.

    name : the paper's one name: notebook ``NN_<name>``, module ``navlib.papers.<name>``.
    number : the notebook number NN.
    claims_id : the paper column of ``data/claims.csv`` and ``data/errata.csv`` (claim ids ``P<claims_id>-...``).
    citation : short citation shown in the README and the report.
    """

    name: str
    number: int
    claims_id: str
    citation: str

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.isidentifier():  # type: ignore[redundant-expr]  # the caller's argument, checked
            raise ValueError(f"name: expected the paper's module name (a Python identifier), got {self.name!r}")
        integer(self.number, "number", minimum=0)
        text(self.claims_id, "claims_id", empty=False)
        text(self.citation, "citation", empty=False)

    @property
    def notebook(self) -> str:
        """Notebook stem, e.g. ``01_north_finding``."""
        return f"{self.number:02d}_{self.name}"

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
    Paper("pedestrian_ins", 5, "004", "Wen, Xu & Yu 2016 — shoulder-mounted MEMS IMU indoor navigation"),
)


def by_notebook(stem: str) -> Paper | None:
    """The registered paper of a notebook stem, or None (notebook 00 has no paper)."""
    text(stem, "stem")
    return next((p for p in PAPERS if p.notebook == stem), None)
