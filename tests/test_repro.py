"""Tests of navlib.repro: claim checks, results.json and deterministic figures."""

import json
import math
import struct
import zlib
from pathlib import Path

import numpy as np
import pytest
from scipy import stats

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from navlib import repro  # noqa: E402

NB = "zz_test"


@pytest.fixture
def fake_root(tmp_path, monkeypatch):
    """A throw-away repository root; repro's module state and rcParams restored afterwards."""
    (tmp_path / "pyproject.toml").write_text("[project]\nname = 'x'\n")
    (tmp_path / "navlib").mkdir()
    monkeypatch.setenv("NAVLIB_ROOT", str(tmp_path))
    # Fresh module state, so no other test's notebook leaks in or out.
    monkeypatch.setattr(repro, "_state", repro._State())
    with matplotlib.rc_context():
        yield tmp_path
    plt.close("all")


def _results(root):
    return json.loads((root / "build" / NB / "results.json").read_text())


def test_root_from_env(fake_root):
    assert repro.root() == fake_root.resolve()
    assert repro.build_dir(NB) == fake_root.resolve() / "build" / NB
    assert (fake_root / "build" / NB).is_dir()


def test_setup_writes_empty_results(fake_root):
    repro.setup(NB)
    data = _results(fake_root)
    assert data == {"notebook": NB, "checks": []}
    with pytest.raises(ValueError, match="^notebook:"):
        repro.setup("a/b")


def test_passing_check_recorded(fake_root):
    repro.setup(NB)
    c = repro.check("P999-TEST/a", 1.04, 1.0, 0.05, "test source", paper_value="1.0 (printed)")
    assert isinstance(c, repro.Check) and c.passed
    rows = _results(fake_root)["checks"]
    assert len(rows) == 1
    row = rows[0]
    for key in ("name", "value", "expected", "tol", "passed", "source", "paper_value"):
        assert key in row, key
    assert row["name"] == "P999-TEST/a"
    assert row["value"] == pytest.approx(1.04)
    assert row["expected"] == 1.0 and row["tol"] == 0.05
    assert row["passed"] is True
    assert row["source"] == "test source"
    assert row["paper_value"] == "1.0 (printed)"
    assert [k.name for k in repro.results()] == ["P999-TEST/a"]


def test_failing_check_raises_and_is_recorded(fake_root):
    repro.setup(NB)
    repro.check("ok", 2.0, 2, 0.0, "src")  # |v - e| <= tol with tol 0 passes
    with pytest.raises(repro.ClaimCheckFailed, match="bad"):
        repro.check("bad", 1.2, 1.0, 0.1, "src")
    assert issubclass(repro.ClaimCheckFailed, AssertionError)
    rows = {r["name"]: r for r in _results(fake_root)["checks"]}
    assert rows["ok"]["passed"] is True
    assert rows["bad"]["passed"] is False and rows["bad"]["value"] == pytest.approx(1.2)
    assert rows["bad"]["paper_value"] is None
    # Re-checking a name replaces its row.
    repro.check("bad", 1.05, 1.0, 0.1, "src")
    rows = [r for r in _results(fake_root)["checks"] if r["name"] == "bad"]
    assert len(rows) == 1 and rows[0]["passed"] is True


def test_relative_tolerance(fake_root):
    repro.setup(NB)
    c = repro.check("rel-pass", 104.0, 100.0, 0.05, "src", rel=True)
    assert c.passed and c.tol == pytest.approx(5.0)  # recorded as the absolute tolerance
    with pytest.raises(repro.ClaimCheckFailed):
        repro.check("rel-fail", 106.0, 100.0, 0.05, "src", rel=True)
    with pytest.raises(repro.ClaimCheckFailed):
        repro.check("abs-fail", 104.0, 100.0, 0.05, "src")  # the same tol without rel fails
    # Negative expected values use |expected|.
    assert repro.check("rel-neg", -104.0, -100.0, 0.05, "src", rel=True).passed


def test_check_range(fake_root):
    repro.setup(NB)
    assert repro.check_range("ratio", 0.8, "src", upper=1.0).passed
    assert repro.check_range("lo", 3.0, "src", lower=2.0).passed
    assert repro.check_range("both", 2.0, "src", lower=2, upper=2).passed  # inclusive bounds
    with pytest.raises(repro.ClaimCheckFailed):
        repro.check_range("too-high", 1.2, "src", upper=1.0)
    with pytest.raises(repro.ClaimCheckFailed):
        repro.check_range("too-low", 1.0, "src", lower=2.0, upper=3.0)
    with pytest.raises(ValueError, match="lower"):
        repro.check_range("none", 1.0, "src")
    rows = {r["name"]: r for r in _results(fake_root)["checks"]}
    assert rows["ratio"]["lower"] is None and rows["ratio"]["upper"] == 1.0
    assert rows["too-low"]["passed"] is False and rows["too-low"]["lower"] == 2.0


@pytest.mark.parametrize("value", [np.nan, np.inf])
def test_nonfinite_value_fails(fake_root, value):
    repro.setup(NB)
    with pytest.raises(repro.ClaimCheckFailed):
        repro.check("nan", value, 1.0, 1e9, "src")
    with pytest.raises(repro.ClaimCheckFailed):
        repro.check_range("nan-range", value, "src", lower=-math.inf)
    rows = _results(fake_root)["checks"]
    assert [r["passed"] for r in rows] == [False, False]


def test_check_bad_arguments(fake_root):
    repro.setup(NB)
    with pytest.raises(ValueError, match="^tol:"):
        repro.check("neg-tol", 1.0, 1.0, -0.1, "src")
    with pytest.raises(ValueError, match="^value:"):
        repro.check("vector", [1.0, 2.0], 1.0, 0.1, "src")
    # numpy scalars and 1-element arrays are accepted.
    assert repro.check("np", np.array([1.0]), np.float32(1.0), 0.0, "src").passed


def test_savefig_before_setup_raises(fake_root):
    fig, ax = plt.subplots()
    with pytest.raises(RuntimeError, match="setup"):
        repro.savefig(fig, "early")


def _png_chunks(data):
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, chunks = 8, []
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        ctype = data[pos + 4 : pos + 8]
        body = data[pos + 8 : pos + 8 + length]
        (crc,) = struct.unpack(">I", data[pos + 8 + length : pos + 12 + length])
        assert crc == zlib.crc32(ctype + body) & 0xFFFFFFFF
        chunks.append((ctype, body))
        pos += 12 + length
    return chunks


def _figure():
    fig, ax = plt.subplots()
    t = np.linspace(0, 10, 200)
    ax.plot(t, np.sin(t), label="sin")
    ax.set_title("deterministic")
    ax.legend()
    return fig


def test_savefig_deterministic(fake_root):
    repro.setup(NB)
    fig = _figure()
    p1 = repro.savefig(fig, "a")
    p2 = repro.savefig(fig, "b")
    p3 = repro.savefig(_figure(), "c")  # a fresh, identical figure
    assert p1 == fake_root.resolve() / "build" / NB / "figures" / "a.png"
    b1, b2, b3 = p1.read_bytes(), p2.read_bytes(), p3.read_bytes()
    assert b1 == b2 == b3
    chunks = _png_chunks(b1)
    types = [c[0] for c in chunks]
    assert types[0] == b"IHDR" and types[-1] == b"IEND"
    assert b"tIME" not in types  # no modification time
    text = b" ".join(body for ctype, body in chunks if ctype in (b"tEXt", b"zTXt", b"iTXt"))
    for key in (b"Software", b"Creation Time", b"Date", b"matplotlib", b"Matplotlib"):
        assert key not in text, key


def test_savefig_inline_shows_the_saved_png_and_closes(fake_root, monkeypatch):
    """Under the inline backend the cell shows the saved file, and the backend has nothing left to render."""
    display = pytest.importorskip("IPython.display")
    shown = []
    monkeypatch.setattr(display, "display", lambda obj: shown.append(obj))
    monkeypatch.setattr(matplotlib, "get_backend", lambda: "module://matplotlib_inline.backend_inline")
    repro.setup(NB)
    fig = _figure()
    path = repro.savefig(fig, "a")
    assert len(shown) == 1 and shown[0].data == path.read_bytes()
    assert not plt.fignum_exists(fig.number)


def test_explorer_redraws_its_one_figure_in_place(fake_root, monkeypatch):
    """Inline: the default figure is saved and shown once with a display id; a slider redraws that output
    (no second figure below the controls); float readouts show three significant digits."""
    display = pytest.importorskip("IPython.display")
    widgets = pytest.importorskip("ipywidgets")
    shown, updates = [], []

    class Handle:
        def update(self, obj):
            updates.append(obj)

    monkeypatch.setattr(display, "display", lambda obj, display_id=False: shown.append(obj) or (Handle() if display_id else None))
    monkeypatch.setattr(matplotlib, "get_backend", lambda: "module://matplotlib_inline.backend_inline")
    repro.setup(NB)
    plt.close("all")  # figures other tests left open
    drawn = []

    def draw(noise, label):
        drawn.append(noise)
        return _figure()

    slider = widgets.FloatLogSlider(value=0.0398107, min=-2, max=0)
    repro.explorer(draw, "explore", {"noise": slider, "label": "fixed"})
    saved = fake_root.resolve() / "build" / NB / "figures" / "explore.png"
    assert shown[0].data == saved.read_bytes() and isinstance(shown[1], widgets.VBox) and len(shown) == 2
    assert slider.readout_format == ".3g" and not plt.get_fignums()
    slider.value = 0.1
    assert drawn == [0.0398107, 0.1] and len(updates) == 1 and updates[0].format == "png" and len(shown) == 2
    assert not plt.get_fignums()


def test_savefig_other_backends_leave_the_figure_open(fake_root):
    repro.setup(NB)
    fig = _figure()
    repro.savefig(fig, "a")
    assert plt.fignum_exists(fig.number)


def test_outside_checkout_needs_an_output_directory(tmp_path, monkeypatch):
    """Outside a checkout repro refuses to guess (it would write beside the installed package)."""
    monkeypatch.delenv("NAVLIB_ROOT", raising=False)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(repro, "_state", repro._State())
    with pytest.raises(repro.NoOutputDirectory, match="NAVLIB_ROOT"):
        repro.root()
    with pytest.raises(repro.NoOutputDirectory, match="out_dir"):
        repro.setup(NB)
    assert not any(tmp_path.iterdir())


def test_explicit_output_directory(tmp_path, monkeypatch):
    monkeypatch.delenv("NAVLIB_ROOT", raising=False)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(repro, "_state", repro._State())
    with matplotlib.rc_context():
        repro.setup(NB, out_dir=tmp_path / "out")
        repro.check("x", 1.0, 1, 0.0, "test")
    assert json.loads((tmp_path / "out" / NB / "results.json").read_text())["checks"][0]["name"] == "x"
    with pytest.raises(ValueError, match="^out_dir"):
        repro.setup(NB, out_dir=3)


# ---------------------------------------------------------------- check_outside and verdicts

CLAIMS_CSV = """id,paper,item,quantity,paper_value,kind,erratum,note
P999-FIG1-RMSE,999,Fig. 1,RMSE (deg),4.77,simulation-stand-in,,
P999-EQ2-SIGN,999,Eq. (2),sign,+1,analytic,E999-01,
P999-TAB1-HW,999,Table 1,measured value (deg),2.72,hardware-only,,
P998-EQ1-X,998,Eq. (1),other paper's claim,,analytic,,
"""
ERRATA_CSV = """id,paper,item,printed,corrected,numeric,shown_by
E999-01,999,Eq. (2),+,-,yes,P999-EQ2-SIGN
E999-02,999,Eq. (3),a,b,yes,
"""


@pytest.fixture
def paper_root(fake_root):
    (fake_root / "data").mkdir()
    (fake_root / "data" / "claims.csv").write_text(CLAIMS_CSV, encoding="utf-8")
    (fake_root / "data" / "errata.csv").write_text(ERRATA_CSV, encoding="utf-8")
    repro.setup(NB, paper="999")
    return fake_root


def test_results_json_is_the_plain_json_layout(paper_root):
    """Rows are encoded once, when recorded; the file equals json.dumps of the whole record."""
    repro.mode(teaching=True, fast=False)
    repro.check("P999-FIG1-RMSE", 4.8, 4.77, 0.1, "Fig. 1", paper_value="4.77 °", unit="°", note='ü "q"\nx')
    repro.check_outside("P999-FIG1-RMSE/out", 5.0, "src", lower=1.0, upper=2.0)
    with pytest.warns(repro.ClaimCheckWarning):
        repro.check("extra-nan", np.nan, 0.0, 1.0, "src")
    repro.check("P999-FIG1-RMSE", 4.7, 4.77, 0.1, "Fig. 1")  # replaces the first one
    repro.verdict("P999-FIG1-RMSE", "reproduced")
    repro.verdict("P999-TAB1-HW", "not checkable here", reason="no hardware")
    text = (paper_root / "build" / NB / "results.json").read_text()
    plain = {
        "notebook": NB,
        "checks": [repro._row(c) for c in repro.results()],
        "mode": {"teaching": True, "fast": False},
        "paper": "999",
        "verdicts": [repro._verdict_row(v) for v in repro.verdicts()],  # real_data is written only when set
    }
    assert text == json.dumps(plain, indent=1, allow_nan=True) + "\n"
    assert [r["name"] for r in json.loads(text)["checks"]] == ["P999-FIG1-RMSE/out", "extra-nan", "P999-FIG1-RMSE"]
    assert len(json.loads(text)["verdicts"]) == 2


def test_a_real_data_verdict_is_a_second_verdict_of_any_papers_claim(fake_root):
    (fake_root / "data").mkdir()
    (fake_root / "data" / "claims.csv").write_text(CLAIMS_CSV, encoding="utf-8")
    (fake_root / "data" / "errata.csv").write_text(ERRATA_CSV, encoding="utf-8")
    repro.setup("07_real", paper=None)
    repro.check_range("P998-EQ1-X/real", 0.5, "a recording", upper=1.0)
    with pytest.raises(ValueError, match="real_data=True"):
        repro.verdict("P998-EQ1-X", "reproduced")
    repro.verdict("P998-EQ1-X", "reproduced", real_data=True)
    repro.check_range("P999-FIG1-RMSE/real", 0.5, "a recording", upper=1.0)
    repro.verdict("P999-FIG1-RMSE", "reproduced", real_data=True)
    with pytest.raises(ValueError, match="claim"):
        repro.verdict("P997-NONE", "reproduced", real_data=True)
    rows = json.loads((fake_root / "build" / "07_real" / "results.json").read_text())["verdicts"]
    assert [(r["claim"], r["real_data"]) for r in rows] == [("P998-EQ1-X", True), ("P999-FIG1-RMSE", True)]
    assert "(real data)" in repro.summary()["verdict"].iloc[0]


def test_a_claim_keeps_its_simulation_verdict_beside_the_real_data_one(paper_root):
    repro.check("P999-FIG1-RMSE", 4.8, 4.77, 0.1, "Fig. 1")
    repro.verdict("P999-FIG1-RMSE", "reproduced")
    repro.verdict("P999-FIG1-RMSE", "reproduced", real_data=True)
    assert [v.real_data for v in repro.verdicts()] == [False, True]
    rows = json.loads((paper_root / "build" / NB / "results.json").read_text())["verdicts"]
    assert "real_data" not in rows[0] and rows[1]["real_data"] is True


def test_check_outside(fake_root):
    repro.setup(NB)
    assert repro.check_outside("out-high", 5.0, "src", lower=1.0, upper=2.0).passed
    assert repro.check_outside("out-low", 0.5, "src", lower=1.0, upper=2.0).passed
    assert repro.check_outside("above", 3.0, "src", upper=2.0).passed  # one bound: value > upper
    with pytest.raises(repro.ClaimCheckFailed, match="outside range"):
        repro.check_outside("inside", 1.5, "src", lower=1.0, upper=2.0)
    with pytest.raises(repro.ClaimCheckFailed):
        repro.check_outside("on-bound", 2.0, "src", lower=1.0, upper=2)  # the interval is closed
    with pytest.raises(repro.ClaimCheckFailed):
        repro.check_outside("nan", np.nan, "src", lower=1.0, upper=2.0)
    with pytest.raises(ValueError, match="lower"):
        repro.check_outside("none", 1.0, "src")
    rows = {r["name"]: r for r in _results(fake_root)["checks"]}
    assert rows["out-high"]["outside"] is True and rows["inside"]["passed"] is False
    assert "outside" not in rows  # ordinary checks carry no 'outside' key (old results keep their bytes)


def test_results_of_a_notebook_without_paper_keep_their_format(fake_root):
    repro.setup(NB)
    repro.check("x", 1.0, 1, 0.0, "src")
    repro.check_range("y", 1.0, "src", lower=0.0)
    data = _results(fake_root)
    assert list(data) == ["notebook", "checks"]
    assert all("outside" not in r for r in data["checks"])
    with pytest.raises(ValueError, match="^claim: .*without a paper"):
        repro.verdict("P999-FIG1-RMSE", "reproduced")


def test_verdict_reproduced_rests_on_its_checks(paper_root):
    repro.check("P999-FIG1-RMSE/a", 4.7123456, 4.77, 0.1, "src", unit="deg")
    repro.check("P999-FIG1-RMSE/b", 4.8, 4.77, 0.1, "src")
    repro.check("P999-FIG1-RMSEX", 1.0, 1, 0.0, "not a check of that claim")
    v = repro.verdict("P999-FIG1-RMSE", "reproduced")
    assert v.checks == ["P999-FIG1-RMSE/a", "P999-FIG1-RMSE/b"] and v.evidence == []
    assert v.ours == "4.7123 deg" and v.paper is None  # the ledger shows the catalogue's paper value
    data = _results(paper_root)
    assert data["paper"] == "999"
    assert data["verdicts"] == [
        {
            "claim": "P999-FIG1-RMSE",
            "verdict": "reproduced",
            "checks": v.checks,
            "evidence": [],
            "paper": None,
            "ours": "4.7123 deg",
            "reason": "",
            "erratum": "",
            "figure": "",
        }
    ]
    # one verdict per claim: a second call replaces the first
    repro.verdict("P999-FIG1-RMSE", "direction only", reason="stand-in")
    assert [x.verdict for x in repro.verdicts()] == ["direction only"]


def test_verdict_refuses_what_it_cannot_rest_on(paper_root):
    with pytest.raises(ValueError, match="^claim:"):
        repro.verdict("P999-NOPE", "reproduced")
    with pytest.raises(ValueError, match="^claim:"):
        repro.verdict("P998-EQ1-X", "reproduced")  # another paper's claim
    with pytest.raises(ValueError, match="^verdict:"):
        repro.verdict("P999-FIG1-RMSE", "partially reproduced")
    with pytest.raises(ValueError, match="^checks: .*at least one"):
        repro.verdict("P999-FIG1-RMSE", "reproduced")  # no check recorded
    with pytest.raises(ValueError, match="^checks: .*not recorded"):
        repro.verdict("P999-FIG1-RMSE", "reproduced", checks=["P999-FIG1-RMSE/typo"])
    with pytest.raises(repro.ClaimCheckFailed):
        repro.check("P999-FIG1-RMSE/bad", 9.0, 4.77, 0.1, "src")
    with pytest.raises(ValueError, match="^checks: .*failed"):
        repro.verdict("P999-FIG1-RMSE", "reproduced")
    with pytest.raises(ValueError, match="^figure:"):
        repro.check("P999-EQ2-SIGN/corrected", 1.0, 1, 0.0, "src")
        repro.verdict("P999-EQ2-SIGN", "reproduced", figure="never_saved")


def test_verdict_differs_needs_numbers_reason_and_an_asserted_difference(paper_root):
    repro.check("P999-FIG1-RMSE/rms", 0.34, 0.33, 0.05, "our stand-in against its theory", unit="deg")
    with pytest.raises(ValueError, match="^evidence:"):
        repro.verdict("P999-FIG1-RMSE", "differs", paper=4.77, ours=0.34, reason="hardware")
    repro.check_outside("P999-FIG1-RMSE/differs", 0.34, "paper 4.77 +- 3 sd", lower=3.0, upper=6.5, unit="deg")
    with pytest.raises(ValueError, match="^paper, ours:"):
        repro.verdict("P999-FIG1-RMSE", "differs", reason="hardware")
    with pytest.raises(ValueError, match="^reason:"):
        repro.verdict("P999-FIG1-RMSE", "differs", paper=4.77, ours=0.34)
    v = repro.verdict("P999-FIG1-RMSE", "differs", paper=4.77, ours=0.34, unit="°", reason="hardware errors")
    assert v.evidence == ["P999-FIG1-RMSE/differs"] and (v.paper, v.ours) == ("4.77 °", "0.34 °")
    with pytest.raises(ValueError, match="^evidence:"):
        repro.verdict("P999-FIG1-RMSE", "refuted", paper=4.77, ours=0.34, reason="x", evidence=["P999-EQ2-SIGN/x"])


def test_verdict_with_correction_names_a_listed_erratum_and_a_failing_printed_form(paper_root):
    repro.check("P999-EQ2-SIGN/corrected", 1.0, 1, 1e-9, "erratum E999-01")
    with pytest.raises(ValueError, match="^evidence:"):
        repro.verdict("P999-EQ2-SIGN", "reproduced with correction", erratum="E999-01")
    repro.check_outside("P999-EQ2-SIGN/printed", -1.0, "printed sign", lower=1 - 1e-9, upper=1 + 1e-9)
    with pytest.raises(ValueError, match="^erratum:"):
        repro.verdict("P999-EQ2-SIGN", "reproduced with correction")
    with pytest.raises(ValueError, match="^erratum:"):
        repro.verdict("P999-EQ2-SIGN", "reproduced with correction", erratum="E999-02")  # not listed for the claim
    v = repro.verdict("P999-EQ2-SIGN", "reproduced with correction", erratum="E999-01")
    assert v.evidence == ["P999-EQ2-SIGN/printed"] and len(v.checks) == 2
    with pytest.raises(ValueError, match="^checks: .*corrected form"):  # the printed failure alone is not enough
        repro.verdict("P999-EQ2-SIGN", "reproduced with correction", erratum="E999-01", checks=["P999-EQ2-SIGN/printed"])


def test_verdict_not_checkable_here(paper_root):
    with pytest.raises(ValueError, match="^reason:"):
        repro.verdict("P999-TAB1-HW", "not checkable here")
    v = repro.verdict("P999-TAB1-HW", "not checkable here", reason="needs the authors' recordings")
    assert v.checks == [] and v.ours is None
    repro.check("P999-EQ2-SIGN/residual", 3e-16, 0.0, 1e-12, "src", unit="rad")
    assert repro.verdict("P999-EQ2-SIGN", "reproduced").ours == "max error 3e-16 rad"  # a residual is shown as one


def test_not_checkable_here_only_where_the_catalogue_kind_says_why(paper_root):
    with pytest.raises(ValueError, match="^verdict: P999-EQ2-SIGN is of kind 'analytic'.*hardware-only, datasheet"):
        repro.verdict("P999-EQ2-SIGN", "not checkable here", reason="too hard")
    repro.check("P999-TAB1-HW/sim", 2.7, 2.72, 0.1, "a simulation of the hardware value")
    with pytest.raises(ValueError, match="^verdict: P999-TAB1-HW is of kind 'hardware-only'"):
        repro.verdict("P999-TAB1-HW", "reproduced")


def test_verdict_before_setup(fake_root):
    with pytest.raises(RuntimeError, match="setup"):
        repro.verdict("P999-FIG1-RMSE", "reproduced")
    with pytest.raises(ValueError, match="^paper:"):
        repro.setup(NB, paper=0)


def test_a_value_that_is_its_own_target_is_refused(fake_root):
    """The run-time half of tests/test_check_values.py: the very object passed as the target."""
    repro.setup(NB)
    x = np.float64(0.25)
    with pytest.raises(ValueError, match="^value: is the very object passed as expected"):
        repro.check("self", x, x, 0.1, "src")
    with pytest.raises(ValueError, match="^value: .* as paper_value"):
        repro.check("self-paper", x, 0.25, 0.1, "src", paper_value=x)
    with pytest.raises(ValueError, match="^value: .* as lower"):
        repro.check_range("self-lower", x, "src", lower=x)
    with pytest.raises(ValueError, match="^value: .* as upper"):
        repro.check_outside("self-upper", x, "src", lower=-1.0, upper=x)
    assert repro.check("equal, not the same", np.float64(0.25), x, 0.0, "src").passed  # equal values are not refused
    n = int(np.sum(np.zeros(3) > 1))
    assert repro.check_range("count", n, "src", lower=0, upper=0).passed  # small ints are shared: not refused
    refused = True
    # a literal chosen by a computed condition is the target's own object in CPython (one constant per code object)
    assert repro.check("outcome", 0.0 if refused else 1.0, 0.0, 0.0, "src").passed
    assert [c.name for c in repro.results()] == ["equal, not the same", "count", "outcome"]


def test_a_check_on_printed_numbers_is_recorded_as_such(fake_root):
    repro.setup(NB)
    tab = np.array([12.5, 20.3, 35.6])
    repro.check("P999-TAB1-MAX", tab.max(), 35.6, 0.0, "text vs Table 1", on_printed=True)
    repro.check_range("P999-TAB1-GROWS", np.diff(tab).min(), "Table 1", lower=0.0, on_printed=True)
    repro.check("P999-SIM", 1.0, 1.01, 0.1, "simulation")
    rows = {r["name"]: r for r in _results(fake_root)["checks"]}
    assert rows["P999-TAB1-MAX"]["on_printed"] is True and rows["P999-TAB1-GROWS"]["on_printed"] is True
    assert "on_printed" not in rows["P999-SIM"]  # written only when set
    with pytest.raises(ValueError, match="^on_printed:"):
        repro.check("bad-flag", 1.0, 1.01, 0.1, "src", on_printed="yes")


def test_a_verdict_resting_only_on_printed_arithmetic_is_no_reproduction(paper_root):
    repro.check("P999-EQ2-SIGN/table-sum", 12.0, 12.0, 0.05, "the table's column adds up to its printed total", on_printed=True)
    with pytest.raises(ValueError, match="^checks: a verdict of 'reproduced' rests on a computation"):
        repro.verdict("P999-EQ2-SIGN", "reproduced")
    repro.check("P999-TAB1-HW/table-sum", 12.0, 12.0, 0.05, "the table's column adds up to its printed total", on_printed=True)
    v = repro.verdict("P999-TAB1-HW", "not checkable here", paper="12", reason="hardware only")
    assert v.ours is None  # a printed-arithmetic value is not shown as ours
    repro.check("P999-EQ2-SIGN/simulated", 3e-16, 0.0, 1e-12, "src", unit="rad")
    assert repro.verdict("P999-EQ2-SIGN", "reproduced").checks == ["P999-EQ2-SIGN/table-sum", "P999-EQ2-SIGN/simulated"]


def test_checks_record_silently_and_summary_shows_each_once(paper_root, capsys):
    repro.check("P999-FIG1-RMSE", 4.70, 4.77, 0.1, "Fig. 1", unit="deg")
    repro.check_range("P999-FIG1-RMSE/bound", 0.5, "Fig. 1", upper=1.0)
    repro.verdict("P999-FIG1-RMSE", "reproduced")
    repro.verdict("P999-TAB1-HW", "not checkable here", reason="needs the hardware")
    assert capsys.readouterr().out == ""
    table = repro.summary()
    assert list(table.index) == ["P999-FIG1-RMSE", "P999-FIG1-RMSE/bound", "P999-TAB1-HW (claim)"]
    assert list(table.columns) == ["paper", "ours", "tolerance", "result", "verdict"]
    assert table.loc["P999-FIG1-RMSE", "ours"] == "4.7 deg"
    assert table.loc["P999-FIG1-RMSE", "tolerance"] == "target 4.77 ± 0.1"
    assert table.loc["P999-FIG1-RMSE/bound", "verdict"] == "reproduced"
    assert table.loc["P999-TAB1-HW (claim)", "verdict"] == "not checkable here"
    assert repro.summary().empty  # nothing new since the last table
    repro.check("P999-EQ2-SIGN", -1.0, -1.0, 0.0, "Eq. (2)")
    assert list(repro.summary().index) == ["P999-EQ2-SIGN"]


def test_summary_shows_every_row_and_the_digits_its_tolerance_resolves(paper_root):
    for k in range(80):  # more rows than pandas shows by default (60)
        repro.check(f"P999-FIG1-RMSE/h{k:02d}", 196.25 + k, 196.25 + k, 1e-9, "Fig. 1", unit="deg")
    table = repro.summary()
    assert table.loc["P999-FIG1-RMSE/h00", "ours"] == "196.25 deg"  # not 196.2 against a 1e-9 tolerance
    shown = table._repr_html_()
    assert all(f"P999-FIG1-RMSE/h{k:02d}" in shown for k in range(80)) and "…" not in shown
    assert shown.count("<tr") == 81  # one header row ("check" in its corner) and 80 checks


def test_teaching_mode_warns_instead_of_raising(paper_root):
    repro.mode(teaching=True, fast=True)
    with pytest.warns(repro.ClaimCheckWarning, match="P999-FIG1-RMSE: reproduced 9"):
        c = repro.check("P999-FIG1-RMSE", 9.0, 4.77, 0.1, "Fig. 1")
    assert not c.passed
    with pytest.warns(repro.ClaimCheckWarning, match="not recorded"):
        assert repro.verdict("P999-FIG1-RMSE", "reproduced") is None
    assert repro.summary().loc["P999-FIG1-RMSE", "result"] == "FAIL"
    data = json.loads((paper_root / "build" / NB / "results.json").read_text())
    assert data["mode"] == {"teaching": True, "fast": True} and data["verdicts"] == []
    repro.mode(teaching=False, fast=False)
    with pytest.raises(repro.ClaimCheckFailed):
        repro.check("P999-FIG1-RMSE", 9.0, 4.77, 0.1, "Fig. 1")


def test_setup_resets_the_switches(paper_root):
    repro.mode(teaching=True, fast=False)
    repro.setup(NB, paper="999")
    with pytest.raises(repro.ClaimCheckFailed):
        repro.check("P999-FIG1-RMSE", 9.0, 4.77, 0.1, "Fig. 1")
    assert "mode" not in json.loads((paper_root / "build" / NB / "results.json").read_text())


@pytest.mark.parametrize("raw, expected", [("1", True), ("yes", True), (" ON ", True), ("0", False), ("", False), ("off", False)])
def test_env_flag(monkeypatch, raw, expected):
    monkeypatch.setenv("NAVLIB_TEST_FLAG", raw)
    assert repro.env_flag("NAVLIB_TEST_FLAG") is expected
    monkeypatch.delenv("NAVLIB_TEST_FLAG")
    assert repro.env_flag("NAVLIB_TEST_FLAG", default=True) is True
    monkeypatch.setenv("NAVLIB_TEST_FLAG", "maybe")
    with pytest.raises(ValueError, match="NAVLIB_TEST_FLAG"):
        repro.env_flag("NAVLIB_TEST_FLAG")


def test_build_dir_from_the_environment(fake_root, tmp_path, monkeypatch):
    monkeypatch.setenv("NAVLIB_BUILD_DIR", str(tmp_path / "elsewhere"))
    repro.setup(NB)
    assert (tmp_path / "elsewhere" / NB / "results.json").is_file()


def test_caption_and_answer_render_markdown():
    assert repro.caption("**Figure 1**: 1.25°")._repr_markdown_() == "**Figure 1**: 1.25°"
    shown = repro.answer("It grows 1.7 times.")._repr_markdown_()
    assert shown.startswith("<details><summary>Answer</summary>") and "It grows 1.7 times." in shown


def test_exercise_waits_for_the_stub_then_compares_with_navlib():
    reference = lambda x: np.sin(x)  # noqa: E731 -- a one-line stand-in for a navlib function

    def stub(x):
        return None  # your code here

    def wrong(x):
        return x

    def right(x):
        return np.sin(x)

    cases = [(0.1,), (1.0,)]
    assert repro.exercise(stub, reference, cases).passed is None
    missed = repro.exercise(wrong, reference, cases)
    assert missed.passed is False and "wrong(0.1)" in missed._repr_markdown_()
    assert repro.exercise(right, reference, cases).passed is True
    with pytest.raises(ValueError, match="functions"):
        repro.exercise(None, reference, cases)


STUDY_CSV = (
    "# a seed study\nseed,check,value,target\n"
    "3001,X/pred,1.10,1.0\n3002,X/pred,0.95,1.0\n3003,X/pred,1.02,1.0\n"
    "3001,X/plain,5.0,\n3002,X/plain,6.0,\n3003,X/plain,7.0,\n"
)


def test_a_studied_tolerance_is_k_times_the_rms_over_the_seeds(fake_root):
    (fake_root / "data" / "seed_studies").mkdir(parents=True)
    (fake_root / "data" / "seed_studies" / "nb.csv").write_text(STUDY_CSV, encoding="utf-8")
    repro.setup(NB)
    pred = repro.seed_spread("nb", "X/pred")
    assert pred.seeds == (3001, 3002, 3003)
    assert pred.rms == pytest.approx(np.sqrt((0.1**2 + 0.05**2 + 0.02**2) / 3))
    assert pred.mean == pytest.approx(0.07 / 3)
    c = repro.check_study("X/pred", 1.0 + 0.9 * pred.tol, 1.0, "nb", "prediction")
    assert c.passed and c.tol == pytest.approx(repro.study_k(3) * pred.rms) and c.study == {"name": "nb", "target": 1.0}
    with pytest.raises(repro.ClaimCheckFailed):  # two-sided: too small fails as well
        repro.check_study("X/pred", 1.0 - 1.1 * pred.tol, 1.0, "nb", "prediction")
    plain = repro.seed_spread("nb", "X/plain", about_mean=True)
    assert (plain.mean, plain.sd, plain.rms) == pytest.approx((6.0, 1.0, 1.0))
    assert plain.tol == pytest.approx(repro.study_k(3, about_mean=True) * 1.0)
    assert repro.check_study("X/plain", 6.0 + 0.99 * plain.tol, None, "nb", "regression").passed
    with pytest.raises(repro.ClaimCheckFailed):
        repro.check_study("X/plain", 6.0 - 1.01 * plain.tol, None, "nb", "regression")


def test_the_family_wise_level_is_the_sidak_share_of_the_sweep_budget():
    # any failure of a correct ledger on a sweep of SWEEP_SEEDS_BUDGET seeds: at most SWEEP_ALPHA
    trials = repro.SWEEP_SEEDS_BUDGET * repro.SEED_DEPENDENT_CHECKS
    assert 1 - (1 - repro.CHECK_ALPHA) ** trials == pytest.approx(repro.SWEEP_ALPHA)
    assert 2 * stats.norm.sf(repro.Z) == pytest.approx(repro.CHECK_ALPHA)
    # a study's band: a t prediction interval, wider than Z for few seeds and Z in the limit
    ks = [repro.study_k(n) for n in (6, 12, 24, 48)]
    assert ks == sorted(ks, reverse=True) and ks[-1] > repro.Z
    assert repro.study_k(100_000) == pytest.approx(repro.Z, rel=1e-3)
    assert repro.study_k(100_000, about_mean=True) == pytest.approx(repro.Z, rel=1e-3)
    assert repro.study_k(12, about_mean=True) == pytest.approx(stats.t.isf(repro.CHECK_ALPHA / 2, 11) * np.sqrt(13 / 12))
    assert repro.study_k(1) == pytest.approx(stats.t.isf(repro.CHECK_ALPHA / 2, 1))  # a standard error from 2 values
    with pytest.raises(ValueError, match="at least 2 values"):
        repro.study_k(1, about_mean=True)


def test_the_last_sweep_has_no_more_seed_dependent_checks_than_the_level_assumes():
    # build/seeds.json of the last `make seeds` (tools/reproduce.py --seeds): a check whose value differs between seeds
    sweep = Path(__file__).resolve().parents[1] / "build" / "seeds.json"
    if not sweep.is_file() or len(json.loads(sweep.read_text())["seeds"]) < 2:
        pytest.skip("no seed sweep of two or more seeds in build/ (make seeds)")
    notebooks = json.loads(sweep.read_text())["notebooks"].values()
    varying = [n for t in notebooks for n, c in t["checks"].items() if len({repr(v) for v in c["values"]}) > 1]
    assert len(varying) <= repro.SEED_DEPENDENT_CHECKS, "raise SEED_DEPENDENT_CHECKS (and Z with it): data/seed_studies/README.md"


def test_a_check_without_its_study_row_fails(fake_root):
    repro.setup(NB)
    with pytest.raises(repro.ClaimCheckFailed, match="no seed study row"):
        repro.check_study("X/none", 1.0, 1.0, "nb", "prediction")
    repro.mode(teaching=True, fast=False)
    with pytest.warns(repro.ClaimCheckWarning):
        c = repro.check_study("X/none", 1.0, 1.0, "nb", "prediction")
    assert not c.passed and c.value == 1.0 and c.study == {"name": "nb", "target": 1.0}


def test_verdict_words_follow_the_catalogue_kind(paper_root):
    repro.check("P999-FIG1-RMSE", 4.8, 4.77, 0.1, "Fig. 1")
    with pytest.raises(ValueError, match="extension"):
        repro.verdict("P999-FIG1-RMSE", "extension", reason="own")
    with pytest.raises(ValueError, match="paper, ours"):
        repro.verdict("P999-FIG1-RMSE", "undecided at this scale", reason="straddles the cut")
