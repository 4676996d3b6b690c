# Type stubs of the Rust extension module clr_sim._native (python/src/*.rs). The public API is the
# Python layer (clr, clr_sim.contact, clr_sim.model, clr_sim.result); these stubs let editors and type
# checkers follow it into the extension.
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

__version__: str

_F64 = npt.NDArray[np.float64]

class NormalLawCore:
    def __init__(
        self,
        elastic: str,
        params: Sequence[float],
        damping: str,
        c_e: float,
        min_impact_velocity: Optional[float] = None,
    ) -> None: ...
    @staticmethod
    def preset(
        name: str,
        c_e: float,
        bearing_youngs_modulus: float,
        bearing_poisson_ratio: float,
        journal_youngs_modulus: float,
        journal_poisson_ratio: float,
        bearing_radius: float,
        journal_radius: float,
        length: float,
        min_impact_velocity: Optional[float] = None,
    ) -> "NormalLawCore": ...
    def force(self, delta: _F64, delta_dot: _F64, delta_dot_minus: _F64) -> _F64: ...
    def elastic_force(self, delta: _F64) -> _F64: ...
    @property
    def chi(self) -> float: ...
    @property
    def c_e(self) -> float: ...
    @property
    def damping(self) -> str: ...
    @property
    def elastic(self) -> str: ...
    @property
    def min_impact_velocity(self) -> float: ...
    @property
    def effective_restitution(self) -> float: ...

class FrictionLawCore:
    def __init__(self, kind: str, params: Sequence[float]) -> None: ...
    def force(self, v_t: _F64, f_n: _F64) -> _F64: ...
    def coefficient(self, v_t: _F64) -> _F64: ...
    @property
    def mu_max(self) -> float: ...

class FilmLawCore:
    def __init__(
        self,
        bearing_radius: float,
        journal_radius: float,
        length: float,
        viscosity: float,
        model: str,
    ) -> None: ...
    def force(
        self, eps: _F64, eps_dot: _F64, gamma_dot: _F64, omega_sum: _F64
    ) -> Tuple[_F64, _F64]: ...

class RevoluteJointCore:
    def __init__(
        self,
        bearing_radius: float,
        journal_radius: float,
        bearing_centre: Tuple[float, float],
        journal_centre: Tuple[float, float],
    ) -> None: ...
    @property
    def clearance(self) -> float: ...
    def forces(
        self,
        normal: NormalLawCore,
        friction: Optional[FrictionLawCore],
        bearing: npt.NDArray[np.float64],
        journal: npt.NDArray[np.float64],
        impact_velocity: _F64,
    ) -> Dict[str, npt.NDArray[np.float64]]: ...

class JournalJointCore:
    def __init__(
        self,
        bearing_radius: float,
        bearing_length: float,
        journal_radius: float,
        journal_length: float,
        axial_clearance: Optional[float] = None,
        thrust_radius: Optional[float] = None,
    ) -> None: ...
    @property
    def clearance(self) -> float: ...
    def forces(
        self,
        radial: NormalLawCore,
        thrust: Optional[NormalLawCore],
        friction: Optional[FrictionLawCore],
        states: npt.NDArray[np.float64],
        impact_velocities: npt.NDArray[np.float64],
    ) -> Dict[str, npt.NDArray[np.float64]]: ...

def damping_chi(name: str, c_e: _F64) -> _F64: ...
def effective_restitution(chi: _F64) -> _F64: ...
def damping_names() -> List[str]: ...
def elastic_kinds() -> List[Tuple[str, List[str]]]: ...
def friction_kinds() -> List[Tuple[str, List[str]]]: ...
def preset_names() -> List[str]: ...

class JobCore:
    def feedback_columns(self) -> List[str]: ...
    def with_input_function(self, name: str, f: Any, errors: List[Any]) -> "JobCore": ...
    @staticmethod
    def from_target(
        target: str,
        set: Optional[Mapping[str, Any]] = None,
        t_end: Optional[float] = None,
        rtol: Optional[float] = None,
    ) -> "JobCore": ...
    @staticmethod
    def from_text(
        text: str,
        label: str,
        set: Optional[Mapping[str, Any]] = None,
        t_end: Optional[float] = None,
        rtol: Optional[float] = None,
    ) -> "JobCore": ...
    @staticmethod
    def from_dict(
        doc: Mapping[str, Any],
        label: str,
        set: Optional[Mapping[str, Any]] = None,
        t_end: Optional[float] = None,
        rtol: Optional[float] = None,
    ) -> "JobCore": ...
    @property
    def kind(self) -> str: ...
    @property
    def name(self) -> str: ...
    @property
    def notes(self) -> List[str]: ...
    def to_toml(self) -> str: ...
    def run(self, strict: bool = False) -> Dict[str, Any]: ...

class SweepRun:
    def __init__(
        self, job: JobCore, axes: Sequence[Tuple[str, Sequence[Any]]], jobs: Optional[int] = None
    ) -> None: ...
    @property
    def total(self) -> int: ...
    def done(self) -> int: ...
    def wait(self, timeout: float) -> bool: ...
    def cancel(self) -> None: ...
    def results(self) -> List[Tuple[int, List[Any], Optional[Dict[str, Any]]]]: ...

def list_models() -> List[Tuple[str, str]]: ...
def list_studies() -> List[Tuple[str, str, str]]: ...
def run_study(name: str, out: str) -> int: ...
def element_kinds(space: Optional[str] = None) -> List[Tuple[str, List[str]]]: ...
def kind_fields(
    section: str, kind: Optional[str] = None, space: Optional[str] = None
) -> List[str]: ...
def part(table: Dict[str, Any]) -> Dict[str, Any]: ...
def materials() -> List[Tuple[str, float, str]]: ...
def fmu_export(
    src: str,
    file: str,
    out: str,
    library: str,
    outputs: Optional[List[str]] = None,
    parameters: List[str] = ...,
    step_size: Optional[float] = None,
    fmi_version: int = 3,
) -> str: ...
