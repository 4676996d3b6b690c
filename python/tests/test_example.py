"""The documented example (docs/python.md) runs and writes its figure."""

import importlib.util
import pathlib

EXAMPLE = pathlib.Path(__file__).resolve().parents[1] / "examples" / "restitution_curve.py"


def test_restitution_curve_example(tmp_path):
    spec = importlib.util.spec_from_file_location("restitution_curve", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    out = tmp_path / "curve.png"
    module.main(str(out))
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
