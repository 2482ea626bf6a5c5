"""Type stubs of the compiled core (``stickslip._core``). Use the package's functions
(``stickslip.simulate`` and so on); the functions here may change."""

from __future__ import annotations

import os
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union, final

import numpy as np
import numpy.typing as npt

__all__ = [
    "ATTRACTOR_KINDS",
    "Experiment",
    "MOTION_CLASSES",
    "PARAMETER_LONG_NAMES",
    "__version__",
    "basins",
    "bifurcation",
    "boundary",
    "continuation",
    "grid",
    "lyapunov",
    "orbit",
    "simulate",
    "steady",
    "sweep",
    "theory",
]
__version__: str
MOTION_CLASSES: List[str]
ATTRACTOR_KINDS: List[str]
PARAMETER_LONG_NAMES: Dict[str, str]

_Value = Union[float, int, str, None]
_Progress = Optional[Callable[[int, int], Any]]
_FloatArray = npt.NDArray[np.float64]

@final
class Experiment:
    """One experiment: a dimensionless model, a circuit with PWL or Shockley diodes, or a
    mechanical oscillator; a drive; μs; an initial state. Immutable, comparable, picklable."""

    def __new__(
        cls,
        zeta: _Value = None,
        w: _Value = None,
        beta: _Value = None,
        phi: _Value = None,
        mu_s: _Value = None,
        y0: _Value = None,
        v0: _Value = None,
    ) -> Experiment: ...
    @classmethod
    def paper(cls, w: _Value = None, beta: _Value = None, **keys: _Value) -> Experiment: ...
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
        **keys: _Value,
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
        **keys: _Value,
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
        **keys: _Value,
    ) -> Experiment: ...
    @classmethod
    def from_toml(cls, path: Union[str, os.PathLike[str]]) -> Experiment: ...
    @classmethod
    def from_dict(cls, keys: Dict[str, _Value]) -> Experiment: ...
    @classmethod
    def from_json(cls, text: str) -> Experiment: ...
    def replace(self, **changes: _Value) -> Experiment: ...
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
