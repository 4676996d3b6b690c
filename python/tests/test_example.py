"""The documented examples (python/examples/, docs/python.md) run and write their figures."""

import importlib.util
import pathlib

import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parents[1] / "examples"
PNG = b"\x89PNG\r\n\x1a\n"


def _load(name):
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_every_example_is_tested():
    assert {p.stem for p in EXAMPLES.glob("*.py")} == {"restitution_curve", "clearance_sweep"}


def test_restitution_curve_example(tmp_path):
    out = tmp_path / "curve.png"
    _load("restitution_curve").main(str(out))
    assert out.read_bytes()[:8] == PNG


def test_clearance_sweep_example(tmp_path):
    """Larger clearances hit harder (Flores & Ambrósio 2004, Figs. 9–11: peak contact force
    grows with the clearance of the slider–crank joint)."""
    out = tmp_path / "sweep.png"
    sweep = _load("clearance_sweep").main(str(out), t_end=0.02)
    assert out.read_bytes()[:8] == PNG
    peaks = [r.metrics["B.peak_normal_force"] for r in sweep.results]
    assert len(peaks) == 3 and not sweep.failed
    assert peaks == sorted(peaks), peaks
    with pytest.raises(KeyError, match="did you mean"):
        sweep.results[0]["B.normal_forc"]
