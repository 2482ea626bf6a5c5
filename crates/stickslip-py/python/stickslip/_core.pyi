"""Type stubs of the compiled core (``stickslip._core``). Use the package's functions
(``stickslip.simulate`` and so on); the functions here may change."""

from __future__ import annotations

import os
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str
MOTION_CLASSES: List[str]
PARAMETER_LONG_NAMES: Dict[str, str]

Value = Union[float, int, str, None]
Progress = Optional[Callable[[int, int], Any]]
FloatArray = npt.NDArray[np.float64]

class Experiment:
    """One experiment: a dimensionless model, a circuit with PWL or Shockley diodes, or a
    mechanical oscillator; a drive; μs; an initial state. Immutable, comparable, picklable."""

    def __init__(
        self,
        zeta: Value = None,
        w: Value = None,
        beta: Value = None,
        phi: Value = None,
        mu_s: Value = None,
        y0: Value = None,
        v0: Value = None,
    ) -> None: ...
    @classmethod
    def paper(cls, w: Value = None, beta: Value = None, **keys: Value) -> Experiment: ...
    @classmethod
    def circuit(
        cls,
        L: Value = None,
        C: Value = None,
        R: Value = None,
        U_t: Value = None,
        R_D: Value = None,
        U: Value = None,
        f: Value = None,
        **keys: Value,
    ) -> Experiment: ...
    @classmethod
    def shockley(
        cls,
        L: Value = None,
        C: Value = None,
        R: Value = None,
        U_t: Value = None,
        U: Value = None,
        f: Value = None,
        Is: Value = None,
        n: Value = None,
        Rs: Value = None,
        temperature: Value = None,
        **keys: Value,
    ) -> Experiment: ...
    @classmethod
    def mechanics(
        cls,
        m: Value = None,
        k: Value = None,
        gamma: Value = None,
        F0: Value = None,
        F: Value = None,
        omega: Value = None,
        **keys: Value,
    ) -> Experiment: ...
    @classmethod
    def from_toml(cls, path: Union[str, os.PathLike[str]]) -> Experiment: ...
    @classmethod
    def from_dict(cls, keys: Dict[str, Value]) -> Experiment: ...
    @classmethod
    def from_json(cls, text: str) -> Experiment: ...
    def replace(self, **changes: Value) -> Experiment: ...
    def to_dict(self) -> Dict[str, Union[float, str]]: ...
    def to_json(self) -> str: ...
    def convert(self) -> Dict[str, float]: ...
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
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...
    def __reduce__(self) -> Tuple[Any, Tuple[str]]: ...

def simulate(
    experiment: Experiment, periods: float, samples_per_period: int, progress: Progress = None
) -> Dict[str, Any]: ...
def steady(experiment: Experiment, options: Optional[Dict[str, Any]] = None) -> Dict[str, Any]: ...
def theory(experiment: Experiment) -> Dict[str, Any]: ...
def boundary(
    zeta: FloatArray, w: FloatArray, mu_s: FloatArray
) -> Tuple[FloatArray, FloatArray]: ...
def sweep(
    experiment: Experiment,
    over: str,
    values: FloatArray,
    direction: str,
    options: Optional[Dict[str, Any]] = None,
    progress: Progress = None,
) -> Dict[str, Any]: ...
def grid(
    experiment: Experiment,
    first: str,
    first_values: FloatArray,
    second: str,
    second_values: FloatArray,
    options: Optional[Dict[str, Any]] = None,
    threads: Optional[int] = None,
    block: Optional[Tuple[int, int, int, int]] = None,
    fixed: Optional[Sequence[Tuple[str, float]]] = None,
    progress: Progress = None,
) -> Dict[str, Any]: ...
