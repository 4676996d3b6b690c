"""What a run and a sweep return: :class:`Result` (time histories as numpy arrays with their
units, metrics, located impacts, notes) and :class:`SweepResult` (one row per point)."""

from __future__ import annotations

import json
from typing import Any, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple

import numpy as np

__all__ = ["Result", "SweepResult"]

_META = (
    "units",
    "metrics",
    "metric_units",
    "impacts",
    "notes",
    "warnings",
    "initial_conditions",
    "parameters",
    "model",
    "source",
    "error",
    "wall_s",
)


#: The name results.csv (``clr run``) gives the time column, ``time`` here.
_CSV_TIME = "t"


def _pandas():
    try:
        import pandas  # noqa: WPS433 (optional dependency)
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError(
            "to_pandas() needs pandas: pip install pandas (or pip install ./python[pandas])"
        ) from e
    return pandas


class Result:
    """One run: the numbers of ``clr run``'s results.csv, metrics and impacts, in memory.

    - ``time``: output times (s); ``result["B.normal_force"]`` or ``result.columns[...]``: any
      column (float64 arrays of the same length); ``units[name]`` its unit. ``result[...]`` also
      takes the names of results.csv: ``result["t"]`` is ``time``, and a whole header
      (``result["crank.x [m]"]``) is its column; an unknown name raises ``KeyError`` with the
      closest names;
    - ``metrics`` (name → float) with ``metric_units``;
    - ``impacts``: the located impacts (list of dicts with the columns of impacts.csv:
      ``joint``, ``onset_s``, ``impact_velocity_m_per_s``, ``peak_force_N``, ...);
    - ``warnings``: the plausibility checks' findings (dicts of ``field`` and ``message``: an
      initial penetration, units that look wrong, energy created; also issued through Python's
      :mod:`warnings` as :class:`clr_sim.PlausibilityWarning`);
    - ``notes``: what the run changed or chose on its own; ``initial_conditions``: the
      assembly report (dict, as in summary.json); ``parameters``: the resolved parameters;
    - ``error``: ``None``, or the solver's message when the results stop early;
      ``wall_s``: wall time of the run (s).
    """

    def __init__(self, raw: Dict[str, Any]):
        raw = dict(raw)
        self.units: Dict[str, str] = dict(raw.pop("units"))
        self.metrics: Dict[str, float] = dict(raw.pop("metrics"))
        self.metric_units: Dict[str, str] = dict(raw.pop("metric_units"))
        self.impacts: List[Dict[str, Any]] = list(raw.pop("impacts"))
        self.notes: List[str] = list(raw.pop("notes"))
        self.warnings: List[Dict[str, str]] = [dict(w) for w in raw.pop("warnings", [])]
        self.initial_conditions: Any = json.loads(raw.pop("initial_conditions"))
        self.parameters: Any = json.loads(raw.pop("parameters"))
        self.model: str = raw.pop("model")
        self.source: str = raw.pop("source")
        self.error: Optional[str] = raw.pop("error")
        self.wall_s: Optional[float] = raw.pop("wall_s", None)
        self.columns: Dict[str, np.ndarray] = raw
        self.time: np.ndarray = raw["time"]

    def _key(self, name: Any) -> Optional[str]:
        """The column ``name`` stands for: a column name (``time``), the name results.csv gives
        it (``t`` for ``time``), or a whole results.csv header (``crank.x [m]``, ``t [s]``)."""
        if not isinstance(name, str):
            return None
        if name in self.columns:
            return name
        if name == _CSV_TIME:
            return "time"
        base, sep, unit = name.rpartition(" [")
        if sep and unit.endswith("]"):
            key = self._key(base)
            if key is not None and self.units.get(key) == unit[:-1]:
                return key
        return None

    def __getitem__(self, name: str) -> np.ndarray:
        key = self._key(name)
        if key is not None:
            return self.columns[key]
        import difflib

        names = [*self.columns, _CSV_TIME]
        close = difflib.get_close_matches(str(name), names, n=3, cutoff=0.5)
        if not close:
            close = [c for c in names if str(name).lower() in c.lower()][:3]
        hint = (
            f"; did you mean {', '.join(repr(c) for c in close)}?"
            if close
            else f"; the columns are {', '.join(repr(c) for c in names[:8])}"
            + (", ..." if len(names) > 8 else "")
            + " (column_names() lists them)"
        )
        raise KeyError(f"no column {name!r} in this result{hint}")

    def __contains__(self, name: str) -> bool:
        return self._key(name) is not None

    def csv_names(self) -> List[str]:
        """Every column as results.csv names it (``t`` first; the header adds `` [unit]``)."""
        return [_CSV_TIME if c == "time" else c for c in self.columns]

    def __len__(self) -> int:
        return len(self.time)

    @property
    def ok(self) -> bool:
        """True when the run reached its end time."""
        return self.error is None

    def column_names(self) -> List[str]:
        """Every column name, ``time`` first."""
        return list(self.columns)

    def to_dict(self) -> Dict[str, Any]:
        """The columns and every other attribute as one dict (the former ``run_model`` form)."""
        d: Dict[str, Any] = dict(self.columns)
        for k in _META:
            d[k] = getattr(self, k)
        return d

    def to_pandas(self):
        """The columns as a ``pandas.DataFrame`` indexed by ``time`` (s), units in
        ``df.attrs["units"]``; needs pandas."""
        pd = _pandas()
        df = pd.DataFrame({k: v for k, v in self.columns.items() if k != "time"}, index=self.time)
        df.index.name = "time"
        df.attrs["units"] = dict(self.units)
        df.attrs["model"] = self.model
        return df

    def impacts_frame(self):
        """The impact table as a ``pandas.DataFrame`` (one row per impact); needs pandas."""
        return _pandas().DataFrame(self.impacts)

    def __repr__(self) -> str:
        status = "ok" if self.ok else f"failed: {self.error}"
        span = f"t = {self.time[0]:g}…{self.time[-1]:g} s" if len(self.time) else "no rows"
        return (
            f"<clr_sim.Result {self.model!r}: {len(self.time)} rows, {span}, "
            f"{len(self.columns) - 1} columns, {len(self.metrics)} metrics, "
            f"{len(self.impacts)} impacts, {status}>"
        )


class SweepResult:
    """A sweep: for each point (in ``clr sweep``'s order, the last parameter varying fastest)
    its index, the value of every varied parameter and its :class:`Result` (``None`` for a
    point skipped by an interrupt).

    ``table()`` is ``clr sweep``'s sweep.csv as columns: ``point``, the varied parameters,
    ``status`` (``ok``/``failed``/``skipped``), ``wall_s`` and every metric.
    """

    def __init__(self, names: Sequence[str], rows: Sequence[Tuple[int, list, Optional[Result]]]):
        self.names: List[str] = list(names)
        self.points: List[Tuple[int, list, Optional[Result]]] = list(rows)

    def __len__(self) -> int:
        return len(self.points)

    def __iter__(self) -> Iterator[Tuple[int, list, Optional[Result]]]:
        return iter(self.points)

    def __getitem__(self, k: int) -> Tuple[int, list, Optional[Result]]:
        return self.points[k]

    @property
    def results(self) -> List[Optional[Result]]:
        """The :class:`Result` of every point, in point order."""
        return [r for _, _, r in self.points]

    @property
    def failed(self) -> List[int]:
        """Indices of the points whose integration failed."""
        return [k for k, _, r in self.points if r is not None and not r.ok]

    def metric_names(self) -> List[str]:
        """Every metric of any point, in first-seen order."""
        names: Dict[str, None] = {}
        for _, _, r in self.points:
            if r is not None:
                names.update(dict.fromkeys(r.metrics))
        return list(names)

    def table(self) -> Dict[str, Any]:
        """Column name → list (numbers as numpy arrays): ``point``, each varied parameter,
        ``status``, ``wall_s`` and each metric (NaN where a point lacks it)."""
        rows = self.points
        out: Dict[str, Any] = {"point": np.array([k for k, _, _ in rows])}
        for j, n in enumerate(self.names):
            col = [v[j] for _, v, _ in rows]
            is_num = all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in col)
            out[n] = np.array(col, dtype=float) if is_num else col
        out["status"] = [
            "skipped" if r is None else ("ok" if r.ok else "failed") for _, _, r in rows
        ]
        out["wall_s"] = np.array([np.nan if r is None else r.wall_s for _, _, r in rows])
        for m in self.metric_names():
            out[m] = np.array(
                [np.nan if r is None else r.metrics.get(m, np.nan) for _, _, r in rows]
            )
        return out

    def to_pandas(self):
        """:meth:`table` as a ``pandas.DataFrame`` indexed by point; metric units in
        ``df.attrs["units"]``; needs pandas."""
        df = _pandas().DataFrame(self.table()).set_index("point")
        units: Dict[str, str] = {"wall_s": "s"}
        for _, _, r in self.points:
            if r is not None:
                units.update(r.metric_units)
        df.attrs["units"] = units
        return df

    def __repr__(self) -> str:
        return (
            f"<clr_sim.SweepResult {len(self.points)} points over {', '.join(self.names)}; "
            f"{len(self.failed)} failed>"
        )


def _rows(raw: Sequence[Tuple[int, list, Optional[Mapping[str, Any]]]]):
    return [(k, list(v), None if o is None else Result(dict(o))) for k, v, o in raw]
