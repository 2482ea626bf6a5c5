"""Type stubs of the compiled core (``stickslip._core``). Use the package's functions
(``stickslip.simulate`` and so on); the functions here may change."""

from __future__ import annotations

import os
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union, final

import numpy as np
import numpy.typing as npt
from typing_extensions import TypedDict, Unpack

__all__ = [
    "ATTRACTOR_KINDS",
    "BASIN_COLUMNS",
    "BIFURCATION_COLUMNS",
    "BIFURCATION_FIELDS",
    "BRANCH_COLUMNS",
    "EVENT_KINDS",
    "Experiment",
    "KEYS",
    "MAP_COLUMNS",
    "MAP_EXPONENT_COLUMNS",
    "OPTIONS",
    "MOTION_CLASSES",
    "PARAMETER_LONG_NAMES",
    "PHASE_LABELS",
    "SWEEP_COLUMNS",
    "SWEEP_FIELDS",
    "SWEEP_LEGS",
    "__version__",
    "basins",
    "bifurcation",
    "boundary",
    "check_option",
    "continuation",
    "curve",
    "fit",
    "grid",
    "lyapunov",
    "orbit",
    "read_amplitudes",
    "read_scope",
    "simulate",
    "steady",
    "steady_option_kinds",
    "sweep",
    "theory",
    "with_diode",
]
__version__: str
MOTION_CLASSES: List[str]
ATTRACTOR_KINDS: List[str]
PARAMETER_LONG_NAMES: Dict[str, str]
EVENT_KINDS: List[str]
PHASE_LABELS: Dict[int, str]
SWEEP_LEGS: List[str]
#: The library's report tables (``Table::columns()``): CSV columns and JSON fields.
MAP_COLUMNS: List[str]
MAP_EXPONENT_COLUMNS: List[str]
SWEEP_COLUMNS: List[str]
SWEEP_FIELDS: List[str]
BIFURCATION_COLUMNS: List[str]
BIFURCATION_FIELDS: List[str]
BASIN_COLUMNS: List[str]
BRANCH_COLUMNS: List[str]
#: The library's key table: one dict per key (name, name_aliases, unit, range, help, ...).
KEYS: List[Dict[str, Any]]
#: The library's option table: one dict per option (name, group, kind, range, help, ...).
OPTIONS: List[Dict[str, Any]]

_Value = Union[float, int, str, None]
_Progress = Optional[Callable[[int, int], Any]]
_FloatArray = npt.NDArray[np.float64]

# BEGIN keywords: generated from the library's key table by tests/test_keys.py (STICKSLIP_BLESS=1 rewrites)
class _PaperKeys(TypedDict, total=False):
    """The keys of Experiment.paper beside its own."""

    zeta: _Value  # damping ratio ζ
    phi: _Value  # drive phase φ (rad)
    mu_s: _Value  # static-to-kinetic friction ratio μs
    y0: _Value  # initial position y0
    v0: _Value  # initial velocity v0
    L: _Value  # inductance L (H)
    C: _Value  # capacitance C (F)
    R: _Value  # series resistance R without the diodes (Ω)
    U_t: _Value  # diode turn-on voltage U_t (V)
    R_D: _Value  # PWL diode resistance R_D (Ω)
    m: _Value  # mass m (kg)
    k: _Value  # spring constant k (N/m)
    gamma: _Value  # viscous damping γ (N·s/m)
    F0: _Value  # kinetic friction force F0 (N)
    U: _Value  # drive amplitude U (V) or F (N)
    F: _Value  # drive amplitude U (V) or F (N)
    f: _Value  # drive frequency f (Hz)
    omega: _Value  # drive angular frequency Ω (rad/s)
    uc0: _Value  # initial capacitor voltage u_C(0) (V) or position r(0) (m)
    i0: _Value  # initial current i(0) (A) or velocity ṙ(0) (m/s)
    Is: _Value  # Shockley saturation current I_s (A)
    n: _Value  # Shockley emission coefficient n
    Rs: _Value  # Shockley series resistance R_s (Ω)
    temperature: _Value  # diode temperature (°C)
    diode: Optional[str]  # diode law: pwl or shockley
    preset: Optional[str]  # built-in physical description
    vb: _Value  # belt speed vb (dimensionless, in units of y')
    friction_law: Optional[str]  # friction law of the slip speed: coulomb, stribeck or cubic
    vs: _Value  # Stribeck speed vs (dimensionless, as vb)
    delta: _Value  # Stribeck exponent δ
    eta: _Value  # viscous coefficient η of the Stribeck law (dimensionless)
    k1: _Value  # coefficient k1 of the cubic law (dimensionless)
    k3: _Value  # coefficient k3 of the cubic law (dimensionless)
    belt_speed: _Value  # belt speed (m/s)
    stribeck_speed: _Value  # Stribeck speed (m/s)
    viscous_friction: _Value  # viscous friction coefficient of the Stribeck law (N·s/m)
    cubic_k1: _Value  # linear coefficient of the cubic law (N·s/m)
    cubic_k3: _Value  # cubic coefficient of the cubic law (N·s³/m³)

class _CircuitKeys(TypedDict, total=False):
    """The keys of Experiment.circuit beside its own."""

    zeta: _Value  # damping ratio ζ
    w: _Value  # drive frequency w = Ω/ω0
    beta: _Value  # drive amplitude β = U/U_t or F/F0
    phi: _Value  # drive phase φ (rad)
    mu_s: _Value  # static-to-kinetic friction ratio μs
    y0: _Value  # initial position y0
    v0: _Value  # initial velocity v0
    m: _Value  # mass m (kg)
    k: _Value  # spring constant k (N/m)
    gamma: _Value  # viscous damping γ (N·s/m)
    F0: _Value  # kinetic friction force F0 (N)
    F: _Value  # drive amplitude U (V) or F (N)
    omega: _Value  # drive angular frequency Ω (rad/s)
    uc0: _Value  # initial capacitor voltage u_C(0) (V) or position r(0) (m)
    i0: _Value  # initial current i(0) (A) or velocity ṙ(0) (m/s)
    Is: _Value  # Shockley saturation current I_s (A)
    n: _Value  # Shockley emission coefficient n
    Rs: _Value  # Shockley series resistance R_s (Ω)
    temperature: _Value  # diode temperature (°C)
    diode: Optional[str]  # diode law: pwl or shockley
    preset: Optional[str]  # built-in physical description
    vb: _Value  # belt speed vb (dimensionless, in units of y')
    friction_law: Optional[str]  # friction law of the slip speed: coulomb, stribeck or cubic
    vs: _Value  # Stribeck speed vs (dimensionless, as vb)
    delta: _Value  # Stribeck exponent δ
    eta: _Value  # viscous coefficient η of the Stribeck law (dimensionless)
    k1: _Value  # coefficient k1 of the cubic law (dimensionless)
    k3: _Value  # coefficient k3 of the cubic law (dimensionless)
    belt_speed: _Value  # belt speed (m/s)
    stribeck_speed: _Value  # Stribeck speed (m/s)
    viscous_friction: _Value  # viscous friction coefficient of the Stribeck law (N·s/m)
    cubic_k1: _Value  # linear coefficient of the cubic law (N·s/m)
    cubic_k3: _Value  # cubic coefficient of the cubic law (N·s³/m³)

class _ShockleyKeys(TypedDict, total=False):
    """The keys of Experiment.shockley beside its own."""

    zeta: _Value  # damping ratio ζ
    w: _Value  # drive frequency w = Ω/ω0
    beta: _Value  # drive amplitude β = U/U_t or F/F0
    phi: _Value  # drive phase φ (rad)
    mu_s: _Value  # static-to-kinetic friction ratio μs
    y0: _Value  # initial position y0
    v0: _Value  # initial velocity v0
    R_D: _Value  # PWL diode resistance R_D (Ω)
    m: _Value  # mass m (kg)
    k: _Value  # spring constant k (N/m)
    gamma: _Value  # viscous damping γ (N·s/m)
    F0: _Value  # kinetic friction force F0 (N)
    F: _Value  # drive amplitude U (V) or F (N)
    omega: _Value  # drive angular frequency Ω (rad/s)
    uc0: _Value  # initial capacitor voltage u_C(0) (V) or position r(0) (m)
    i0: _Value  # initial current i(0) (A) or velocity ṙ(0) (m/s)
    diode: Optional[str]  # diode law: pwl or shockley
    preset: Optional[str]  # built-in physical description
    vb: _Value  # belt speed vb (dimensionless, in units of y')
    friction_law: Optional[str]  # friction law of the slip speed: coulomb, stribeck or cubic
    vs: _Value  # Stribeck speed vs (dimensionless, as vb)
    delta: _Value  # Stribeck exponent δ
    eta: _Value  # viscous coefficient η of the Stribeck law (dimensionless)
    k1: _Value  # coefficient k1 of the cubic law (dimensionless)
    k3: _Value  # coefficient k3 of the cubic law (dimensionless)
    belt_speed: _Value  # belt speed (m/s)
    stribeck_speed: _Value  # Stribeck speed (m/s)
    viscous_friction: _Value  # viscous friction coefficient of the Stribeck law (N·s/m)
    cubic_k1: _Value  # linear coefficient of the cubic law (N·s/m)
    cubic_k3: _Value  # cubic coefficient of the cubic law (N·s³/m³)

class _MechanicsKeys(TypedDict, total=False):
    """The keys of Experiment.mechanics beside its own."""

    zeta: _Value  # damping ratio ζ
    w: _Value  # drive frequency w = Ω/ω0
    beta: _Value  # drive amplitude β = U/U_t or F/F0
    phi: _Value  # drive phase φ (rad)
    mu_s: _Value  # static-to-kinetic friction ratio μs
    y0: _Value  # initial position y0
    v0: _Value  # initial velocity v0
    L: _Value  # inductance L (H)
    C: _Value  # capacitance C (F)
    R: _Value  # series resistance R without the diodes (Ω)
    U_t: _Value  # diode turn-on voltage U_t (V)
    R_D: _Value  # PWL diode resistance R_D (Ω)
    U: _Value  # drive amplitude U (V) or F (N)
    f: _Value  # drive frequency f (Hz)
    uc0: _Value  # initial capacitor voltage u_C(0) (V) or position r(0) (m)
    i0: _Value  # initial current i(0) (A) or velocity ṙ(0) (m/s)
    Is: _Value  # Shockley saturation current I_s (A)
    n: _Value  # Shockley emission coefficient n
    Rs: _Value  # Shockley series resistance R_s (Ω)
    temperature: _Value  # diode temperature (°C)
    diode: Optional[str]  # diode law: pwl or shockley
    preset: Optional[str]  # built-in physical description
    vb: _Value  # belt speed vb (dimensionless, in units of y')
    friction_law: Optional[str]  # friction law of the slip speed: coulomb, stribeck or cubic
    vs: _Value  # Stribeck speed vs (dimensionless, as vb)
    delta: _Value  # Stribeck exponent δ
    eta: _Value  # viscous coefficient η of the Stribeck law (dimensionless)
    k1: _Value  # coefficient k1 of the cubic law (dimensionless)
    k3: _Value  # coefficient k3 of the cubic law (dimensionless)
    belt_speed: _Value  # belt speed (m/s)
    stribeck_speed: _Value  # Stribeck speed (m/s)
    viscous_friction: _Value  # viscous friction coefficient of the Stribeck law (N·s/m)
    cubic_k1: _Value  # linear coefficient of the cubic law (N·s/m)
    cubic_k3: _Value  # cubic coefficient of the cubic law (N·s³/m³)

class _ExperimentKeys(TypedDict, total=False):
    """Every experiment key."""

    zeta: _Value  # damping ratio ζ
    w: _Value  # drive frequency w = Ω/ω0
    beta: _Value  # drive amplitude β = U/U_t or F/F0
    phi: _Value  # drive phase φ (rad)
    mu_s: _Value  # static-to-kinetic friction ratio μs
    y0: _Value  # initial position y0
    v0: _Value  # initial velocity v0
    L: _Value  # inductance L (H)
    C: _Value  # capacitance C (F)
    R: _Value  # series resistance R without the diodes (Ω)
    U_t: _Value  # diode turn-on voltage U_t (V)
    R_D: _Value  # PWL diode resistance R_D (Ω)
    m: _Value  # mass m (kg)
    k: _Value  # spring constant k (N/m)
    gamma: _Value  # viscous damping γ (N·s/m)
    F0: _Value  # kinetic friction force F0 (N)
    U: _Value  # drive amplitude U (V) or F (N)
    F: _Value  # drive amplitude U (V) or F (N)
    f: _Value  # drive frequency f (Hz)
    omega: _Value  # drive angular frequency Ω (rad/s)
    uc0: _Value  # initial capacitor voltage u_C(0) (V) or position r(0) (m)
    i0: _Value  # initial current i(0) (A) or velocity ṙ(0) (m/s)
    Is: _Value  # Shockley saturation current I_s (A)
    n: _Value  # Shockley emission coefficient n
    Rs: _Value  # Shockley series resistance R_s (Ω)
    temperature: _Value  # diode temperature (°C)
    diode: Optional[str]  # diode law: pwl or shockley
    preset: Optional[str]  # built-in physical description
    vb: _Value  # belt speed vb (dimensionless, in units of y')
    friction_law: Optional[str]  # friction law of the slip speed: coulomb, stribeck or cubic
    vs: _Value  # Stribeck speed vs (dimensionless, as vb)
    delta: _Value  # Stribeck exponent δ
    eta: _Value  # viscous coefficient η of the Stribeck law (dimensionless)
    k1: _Value  # coefficient k1 of the cubic law (dimensionless)
    k3: _Value  # coefficient k3 of the cubic law (dimensionless)
    belt_speed: _Value  # belt speed (m/s)
    stribeck_speed: _Value  # Stribeck speed (m/s)
    viscous_friction: _Value  # viscous friction coefficient of the Stribeck law (N·s/m)
    cubic_k1: _Value  # linear coefficient of the cubic law (N·s/m)
    cubic_k3: _Value  # cubic coefficient of the cubic law (N·s³/m³)

# END keywords

@final
class Experiment:
    """One experiment: a dimensionless model, a circuit with PWL or Shockley diodes, or a
    mechanical oscillator; a drive; μs; an initial state. Immutable, comparable, picklable."""

    def __new__(
        cls,
        zeta: _Value = None,
        w: _Value = None,
        beta: _Value = None,
        phi: _Value = 0,
        mu_s: _Value = 1,
        y0: _Value = 0,
        v0: _Value = 0,
        vb: _Value = 0,
    ) -> Experiment: ...
    @classmethod
    def paper(
        cls, w: _Value = None, beta: _Value = None, **keys: Unpack[_PaperKeys]
    ) -> Experiment: ...
    @classmethod
    def circuit(
        cls,
        L: _Value = None,
        C: _Value = None,
        R: _Value = None,
        U_t: _Value = None,
        R_D: _Value = None,
        U: _Value = None,
        f: _Value = None,
        **keys: Unpack[_CircuitKeys],
    ) -> Experiment: ...
    @classmethod
    def shockley(
        cls,
        L: _Value = None,
        C: _Value = None,
        R: _Value = None,
        U_t: _Value = None,
        U: _Value = None,
        f: _Value = None,
        Is: _Value = None,
        n: _Value = None,
        Rs: _Value = None,
        temperature: _Value = None,
        **keys: Unpack[_ShockleyKeys],
    ) -> Experiment: ...
    @classmethod
    def mechanics(
        cls,
        m: _Value = None,
        k: _Value = None,
        gamma: _Value = None,
        F0: _Value = None,
        F: _Value = None,
        omega: _Value = None,
        **keys: Unpack[_MechanicsKeys],
    ) -> Experiment: ...
    @classmethod
    def from_toml(cls, path: Union[str, os.PathLike[str]]) -> Experiment: ...
    @classmethod
    def from_dict(cls, keys: Dict[str, _Value]) -> Experiment: ...
    @classmethod
    def from_json(cls, text: str) -> Experiment: ...
    def replace(self, **changes: Unpack[_ExperimentKeys]) -> Experiment: ...
    def to_dict(self) -> Dict[str, Union[float, str]]: ...
    def to_json(self) -> str: ...
    def convert(self) -> Dict[str, float]: ...
    def scales(self) -> Optional[Dict[str, Union[float, str]]]: ...
    @property
    def zeta(self) -> float: ...
    @property
    def w(self) -> Optional[float]: ...
    @property
    def beta(self) -> Optional[float]: ...
    @property
    def phi(self) -> float: ...
    @property
    def mu_s(self) -> float: ...
    @property
    def y0(self) -> float: ...
    @property
    def v0(self) -> float: ...
    @property
    def model(self) -> str: ...
    @property
    def system(self) -> str: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...
    def __reduce__(self) -> Tuple[Any, Tuple[str]]: ...

def with_diode(experiment: Experiment, model: str) -> Experiment: ...
def check_option(group: str, name: str, value: Union[int, float]) -> None: ...
def steady_option_kinds(spectrum: bool) -> Dict[str, str]: ...
def simulate(
    experiment: Experiment, periods: float, samples_per_period: int, progress: _Progress = None
) -> Dict[str, Any]: ...
def steady(experiment: Experiment, options: Optional[Dict[str, Any]] = None) -> Dict[str, Any]: ...
def theory(experiment: Experiment) -> Dict[str, Any]: ...
def boundary(
    zeta: _FloatArray, w: _FloatArray, mu_s: _FloatArray
) -> Tuple[_FloatArray, _FloatArray]: ...
def sweep(
    experiment: Experiment,
    over: str,
    values: _FloatArray,
    direction: str,
    options: Optional[Dict[str, Any]] = None,
    progress: _Progress = None,
) -> Dict[str, Any]: ...
def grid(
    experiment: Experiment,
    first: str,
    first_values: _FloatArray,
    second: str,
    second_values: _FloatArray,
    options: Optional[Dict[str, Any]] = None,
    threads: Optional[int] = None,
    block: Optional[Tuple[int, int, int, int]] = None,
    fixed: Optional[Sequence[Tuple[str, float]]] = None,
    progress: _Progress = None,
    lyapunov: bool = False,
) -> Dict[str, Any]: ...
def orbit(
    experiment: Experiment,
    period: Optional[int] = None,
    transient: int = 0,
    options: Optional[Dict[str, Any]] = None,
    tolerance: float = 1e-12,
    max_iterations: int = 30,
    progress: _Progress = None,
) -> Dict[str, Any]: ...
def lyapunov(
    experiment: Experiment,
    transient: int = 1000,
    periods: int = 20000,
    blocks: int = 20,
    significance: float = 4.0,
    progress: _Progress = None,
    fixed: bool = False,
) -> Dict[str, Any]: ...
def bifurcation(
    experiment: Experiment,
    over: str,
    values: _FloatArray,
    direction: str,
    points: int,
    transient: int,
    first_transient: int,
    max_period: int,
    progress: _Progress = None,
) -> Dict[str, Any]: ...
def basins(
    experiment: Experiment,
    y0: Tuple[float, float],
    v0: Tuple[float, float],
    steps: Tuple[int, int],
    phase: Optional[float],
    max_periods: int,
    max_period: int,
    lyapunov_periods: int,
    threads: Optional[int] = None,
    progress: _Progress = None,
    method: str = "recurrence",
) -> Dict[str, Any]: ...
def continuation(
    experiment: Experiment,
    over: str,
    start: float,
    to: float,
    max_points: int,
    max_step: float,
    progress: _Progress = None,
) -> Dict[str, Any]: ...
def curve(
    experiment: Experiment,
    follow_kind: str,
    vary: str,
    vary_to: float,
    over: str,
    start: float,
    to: float,
    max_points: int,
    max_step: float,
    progress: _Progress = None,
) -> Dict[str, Any]: ...
def read_scope(
    paths: List[str], drive: Optional[str] = None, response: Optional[str] = None
) -> Dict[str, Any]: ...
def read_amplitudes(path: str) -> Dict[str, Any]: ...
def fit(
    experiment: Experiment,
    records: List[Tuple[List[str], Optional[str], Optional[str]]],
    table: Optional[str],
    free: Optional[List[str]],
    per_record: bool,
    progress: _Progress = None,
    from_rest: Optional[float] = None,
    belt_speeds: Optional[List[Optional[float]]] = None,
) -> List[Dict[str, Any]]: ...
