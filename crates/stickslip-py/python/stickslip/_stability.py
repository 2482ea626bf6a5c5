"""A periodic orbit and its Floquet multipliers (:func:`orbit`; without a drive on a belt the
self-excited cycle or steady sliding), the largest Lyapunov exponent (:func:`lyapunov`)."""

from __future__ import annotations

import copy
from typing import Any, Dict, Optional, Tuple, Union

import numpy as np

from . import _checks, _core, _progress
from ._core import Experiment
from ._names import Renamed
from ._progress import Progress
from ._common import EVENT_DTYPE, _exponent, _with_model


#: The structured dtype of an orbit's stops.
STOP_DTYPE = np.dtype([("start", np.float64), ("duration", np.float64)])


class PeriodicOrbit:
    """A periodic orbit found by Newton's method, with its Floquet multipliers
    (``stickslip.orbit``).

    ``to_dict()`` is exactly the JSON of ``stickslip orbit --json`` for the same input.
    Everything is dimensionless (times in τ = ω0·t).

    Attributes:
        period: p in drive periods, as asked for (or found); least_period: the divisor of p
            after which the orbit repeats (Newton's method asked for p = 2 may land on an
            orbit of period 1).
        drive_period: T = 2π/w.
        state: (y, y') at the orbit's strobe (τ = 0 mod pT); stuck_at_strobe: bool.
        multipliers: complex128 array of the two Floquet multipliers, the larger modulus
            first (one is 0 when the orbit stops: a stop erases the velocity perturbation);
            moduli: their |μ|.
        stable: whether every perturbation decays (|μ1| < 1); stability: 'stable',
            'unstable' or 'neutral'.
        lambda1, lambda1_per_period: the largest Lyapunov exponent of the orbit, λ1 =
            ln|μ1|/(pT) per unit τ and ln|μ1|/p per drive period (-inf when both multipliers
            vanish; the names before, ``exponent_per_tau`` and ``exponent_per_period``, still
            work with a ``DeprecationWarning``).
        monodromy: 2×2 float64 array M = ∂P^p/∂(y, y').
        iterations: Newton steps; residuals: float64 array, max(|Δy|, |Δy'|) of P^p(x) − x
            at the guess and after every step.
        events: structured array (tau, y, kind) over one orbit period, times from the strobe;
            stops: structured array (start, duration); stops_per_period: stops longer than
            1e-8 drive periods per drive period.
        experiment: the experiment.
    """

    exponent_per_tau = Renamed("lambda1")
    exponent_per_period = Renamed("lambda1_per_period")

    def __init__(self, experiment: Experiment, report: Dict[str, Any]) -> None:
        self.experiment = experiment
        self._report = report
        r = report
        self.period: int = r["period"]
        self.least_period: int = r["least_period"]
        self.drive_period: float = r["drive_period"]
        self.state: Tuple[float, float] = (r["y"], r["v"])
        self.stuck_at_strobe: bool = r["stuck_at_strobe"]
        self.multipliers = np.array([complex(m["re"], m["im"]) for m in r["multipliers"]])
        self.moduli = np.asarray(r["moduli"], dtype=np.float64)
        self.stable: bool = r["stable"]
        self.stability: str = r["stability"]
        self.lambda1: float = _exponent(r["lambda1"])
        self.lambda1_per_period: float = _exponent(r["lambda1_per_period"])
        self.monodromy = np.asarray(r["monodromy"], dtype=np.float64)
        self.iterations: int = r["iterations"]
        self.residuals = np.asarray(r["residuals"], dtype=np.float64)
        self.stops_per_period: float = r["stops_per_period"]
        events = r["events"]
        self.events = np.empty(len(events), dtype=EVENT_DTYPE)
        self.events["tau"] = [e["tau"] for e in events]
        self.events["y"] = [e["y"] for e in events]
        self.events["kind"] = [e["kind"] for e in events]
        self.stops = np.array([(s["start"], s["duration"]) for s in r["stops"]],
                              dtype=STOP_DTYPE)

    def to_dict(self) -> Dict[str, Any]:
        """The report as ``stickslip orbit --json`` prints it (a new dict of plain values)."""
        return copy.deepcopy(self._report)

    def __repr__(self) -> str:
        mu = ", ".join(f"{m:.6g}" for m in self.multipliers)
        return (f"<stickslip.PeriodicOrbit period {self.period}: {self.stability}, "
                f"multipliers {mu}, {self.iterations} Newton steps>")


class SelfExcitedOrbit:
    """The orbit of a self-excited motion: a block on a moving belt without a drive
    (``beta=0``, ``vb != 0``), which settles on a cycle of its own period or on steady
    sliding (``stickslip.orbit``).

    ``to_dict()`` is exactly the JSON of ``stickslip orbit --json`` for the same input.
    Dimensionless: times in τ = ω0·t, rates per unit τ.

    Attributes:
        summary: the result in a few words (``self-excited cycle, period T τ (class)`` or
            ``self-excited: steady sliding at y = y_e (stability)``).
        motion_class: 'stick-slip-cycle', 'pure-slip-cycle' or 'steady-sliding' (the JSON's
            ``class``).
        cycle_period_tau: the cycle's period T in τ, found (not given); None for steady
            sliding. cycle_period_s: T/ω0 in seconds for a physical model, else None.
        section: where the cycle was recognised ('stick-onset', 'reversal',
            'turning-point'), None for steady sliding.
        release_y: the position where every stop of a stick-slip cycle ends,
            sgn(vb)·μs − 2ζ vb (with y' = vb); None without stops.
        multipliers: complex128 array of the cycle's two Floquet multipliers, the trivial one
            (1: the motion is autonomous) first; [1, 0] for a stick-slip cycle (every stop
            ends in the same state), [1, μ2] for a pure-slip cycle (μ2 the derivative of its
            Poincaré return map, from the solver's tangent dynamics); None for steady sliding.
        stability: 'stable', 'unstable' or 'neutral' (the cycle's from its nontrivial
            multiplier, or the equilibrium's), None when not known; stable: whether it is
            'stable'.
        y_max, y_min: the extremes of y over the cycle (the equilibrium for steady sliding).
        stick_fraction: the fraction of the period stuck to the belt.
        sliding_equilibrium: y_e = sgn(vb)·μ(|vb|), steady sliding's position (y' = 0);
            sliding_damping: 2ζ + μ'(|vb|), the damping of small oscillations about it;
            sliding_growth_rate, sliding_frequency: their rate and angular frequency per
            unit τ; sliding_eigenvalues: complex128 array of its linearisation's
            eigenvalues, the larger real part first; sliding_stability: 'stable',
            'unstable' or 'neutral' (whether or not the motion settled there).
        experiment: the experiment.
    """

    def __init__(self, experiment: Experiment, report: Dict[str, Any]) -> None:
        self.experiment = experiment
        self._report = report
        r = report
        self.summary: str = r["summary"]
        self.motion_class: str = r["class"]
        self.cycle_period_tau: Optional[float] = r["cycle_period_tau"]
        self.cycle_period_s: Optional[float] = r["cycle_period_s"]
        self.section: Optional[str] = r["section"]
        self.release_y: Optional[float] = r["release_y"]
        self.multipliers: Optional[np.ndarray] = (
            None if r["multipliers"] is None
            else np.array([complex(m["re"], m["im"]) for m in r["multipliers"]]))
        self.stability: Optional[str] = r["stability"]
        self.stable: bool = r["stability"] == "stable"
        self.y_max: float = r["y_max"]
        self.y_min: float = r["y_min"]
        self.stick_fraction: float = r["stick_fraction"]
        sliding = r["sliding"]
        self.sliding_equilibrium: float = sliding["equilibrium"]
        self.sliding_damping: float = sliding["damping"]
        self.sliding_growth_rate: float = sliding["growth_rate"]
        self.sliding_frequency: float = sliding["frequency"]
        self.sliding_eigenvalues = np.array(
            [complex(m["re"], m["im"]) for m in r["sliding_eigenvalues"]])
        self.sliding_stability: str = r["sliding_stability"]

    def to_dict(self) -> Dict[str, Any]:
        """The report as ``stickslip orbit --json`` prints it (a new dict of plain values)."""
        return copy.deepcopy(self._report)

    def __repr__(self) -> str:
        return f"<stickslip.SelfExcitedOrbit {self.summary}>"


class LyapunovResult:
    """The Lyapunov exponents of a motion and what they say (``stickslip.lyapunov``).

    ``to_dict()`` is exactly the JSON of ``stickslip lyapunov --json`` for the same input.
    Rates are per unit τ = ω0·t (``*_per_period``: per drive period).

    Attributes:
        lambda1, lambda1_error: the largest exponent λ1 and its standard error (from the block
            means); lambda1_per_period, lambda1_error_per_period: the same per drive period.
        motion_class: 'periodic' when the motion has reached a periodic orbit or rest (its
            strobe repeats within 16 periods; ``period`` gives the period), else
            'chaotic' (λ1 > kσ), 'quasi-periodic' (|λ1| ≤ kσ), 'contracting'
            (λ1 < −kσ: settling onto a periodic attractor) or 'undecided' (the two halves of
            the measurement disagree), with k = ``significance`` (the JSON's ``class``);
            without a drive on a belt (beta = 0, vb != 0) 'limit-cycle' (|λ1| ≤ kσ, λ2 < −kσ)
            or 'equilibrium' (λ1 < −kσ: steady sliding).
        verdict: what λ1 alone says ('chaotic', 'quasi-periodic', 'contracting',
            'limit-cycle', 'equilibrium', 'undecided'); period: the period reached, or None.
        converged: whether the two halves agree.
        lambda2, lambda2_per_period: the second exponent (-inf once the motion stops: a stop
            erases the velocity perturbation; ``lambda2_reason`` says so; the JSON of
            ``to_dict()`` has null there); lambda2_error: its standard error.
        stops_per_period: stops longer than 1e-8 drive periods per drive period.
        block_means: float64 array of λ1 per block, in time order.
        transient_periods, periods, blocks, significance: how it was measured (``periods``:
            the drive periods measured, fewer than ``cap_periods`` when the verdict was
            decided early; ``sequential``: whether it could stop early).
        final_state: (y, y') at the end of the measurement (a strobe).
        experiment: the experiment.

    The names before (``lambda_per_tau``, ``error_per_tau``, ``lambda_per_period``,
    ``error_per_period``, ``lambda2_per_tau``, ``lambda2_error_per_tau``) still work, with a
    ``DeprecationWarning``.
    """

    lambda_per_tau = Renamed("lambda1")
    error_per_tau = Renamed("lambda1_error")
    lambda_per_period = Renamed("lambda1_per_period")
    error_per_period = Renamed("lambda1_error_per_period")
    lambda2_per_tau = Renamed("lambda2")
    lambda2_error_per_tau = Renamed("lambda2_error")

    def __init__(self, experiment: Experiment, report: Dict[str, Any]) -> None:
        self.experiment = experiment
        self._report = report
        r = report
        self.lambda1: float = r["lambda1"]
        self.lambda1_error: float = r["lambda1_error"]
        self.lambda1_per_period: float = r["lambda1_per_period"]
        self.lambda1_error_per_period: float = r["lambda1_error_per_period"]
        self.motion_class: str = r["class"]
        self.verdict: str = r["verdict"]
        self.period: Optional[int] = r["period"]
        self.converged: bool = r["converged"]
        minus_infinity = r["lambda2"] is None
        self.lambda2: float = float("-inf") if minus_infinity else float(r["lambda2"])
        self.lambda2_error: Optional[float] = r["lambda2_error"]
        self.lambda2_per_period: float = (float("-inf") if minus_infinity
                                          else float(r["lambda2_per_period"]))
        self.lambda2_reason: Optional[str] = r["lambda2_reason"]
        self.stops_per_period: float = r["stops_per_period"]
        self.block_means = np.asarray(r["block_means"], dtype=np.float64)
        self.transient_periods: int = r["transient_periods"]
        self.periods: int = r["periods"]
        self.cap_periods: int = r["cap_periods"]
        self.sequential: bool = r["sequential"]
        self.blocks: int = r["blocks"]
        self.significance: float = r["significance"]
        self.drive_period: float = r["drive_period"]
        self.final_state: Tuple[float, float] = (r["final_y"], r["final_v"])

    def to_dict(self) -> Dict[str, Any]:
        """The report as ``stickslip lyapunov --json`` prints it (a new dict of plain values)."""
        return copy.deepcopy(self._report)

    def __repr__(self) -> str:
        return (f"<stickslip.LyapunovResult {self.motion_class}: λ1 = {self.lambda1:+.4e} "
                f"± {self.lambda1_error:.1e} per unit τ over {self.periods} periods>")


def orbit(experiment: Experiment, period: Optional[int] = None, *, transient: int = 0,
          tolerance: float = 1e-12, max_iterations: int = 30, progress: Progress = None,
          **options: Any) -> Union[PeriodicOrbit, SelfExcitedOrbit]:
    """A periodic orbit by Newton's method on the p-fold strobe map (the state once every p
    drive periods), with its Jacobian: its Floquet multipliers say whether it is stable and
    how fast perturbations grow or decay (as ``stickslip orbit``). With the PWL law the
    Jacobian is exact; with Shockley diodes it is the derivative of the stiff solver's
    computed map (the variational equations on the solver's own steps).

    Without a drive on a belt (``beta=0``, ``vb != 0``) the motion is self-excited: the
    result is a ``SelfExcitedOrbit``, the cycle the motion from the initial state settles on
    (its own period in τ and seconds, class, multipliers, extremes, stick fraction) or
    steady sliding with the eigenvalues of its linearisation. ``period`` and ``transient``
    count drive periods and do not apply there (a period is refused).

    Args:
        experiment: a ``stickslip.Experiment`` with its drive given (PWL or Shockley diodes,
            or Coulomb friction).
        period: p in drive periods (1 to 1000). None (the default): the motion from the
            initial state is run to its steady state, which gives p and the guess.
        transient: with a period, drive periods run from the initial state before Newton's
            method starts (0 to 1e8; 0: from the initial state y0, v0 itself, which can aim
            at an unstable orbit).
        tolerance: relative tolerance of Newton's method (default 1e-12).
        max_iterations: most Newton steps (1 to 1000; default 30).
        progress: True for a progress bar (tqdm), a callable ``progress(done, total)``
            (drive periods of the transient) or a tqdm bar's ``update``.
        **options: of the steady-state search without a period: max_periods (5000),
            max_period (16), tolerance is Newton's (above).

    Returns:
        A ``PeriodicOrbit`` (a ``SelfExcitedOrbit`` without a drive on a belt);
        ``to_dict()`` equals ``stickslip orbit --json``.

    Raises:
        ValueError: bad input, no period found, Newton's method failing,
            with the library's message. KeyboardInterrupt: Ctrl-C stops a long transient.

    Example:
        >>> o = stickslip.orbit(stickslip.Experiment.paper(w=0.7, beta=1.2))
        >>> o.period, o.stable, round(float(o.moduli[0]), 6), o.stops_per_period
        (1, True, 0.626452, 2.0)
        >>> u = stickslip.orbit(stickslip.Experiment(zeta=0, mu_s=3, w=0.33, beta=9),
        ...                     period=1, transient=2000)
        >>> u.stability, round(u.lambda1, 5)
        ('unstable', 0.01747)
        >>> c = stickslip.orbit(stickslip.Experiment(zeta=0.05, mu_s=1.5, vb=0.3))
        >>> c.motion_class, round(c.cycle_period_tau, 9), c.multipliers.real.tolist()
        ('stick-slip-cycle', 7.182830239, [1.0, 0.0])
    """
    experiment = _with_model(experiment, None)
    unknown = set(options) - {"max_periods", "max_period"}
    if unknown:
        raise TypeError(f"orbit() got an unknown option {sorted(unknown)[0]!r}: the options are "
                        "max_periods, max_period")
    options = _checks.steady_options(options, False, "orbit")
    if period is not None:
        period = _checks.integer("period", period, "orbit")
    transient = _checks.integer("transient", transient, "orbit")
    tolerance = _checks.number("tolerance", tolerance)
    max_iterations = _checks.integer("max_iterations", max_iterations, "orbit")
    with _progress.reporter(progress, "orbit", "periods") as callback:
        report = _core.orbit(experiment, period, transient, options, tolerance, max_iterations,
                             callback)
    if "cycle_period_tau" in report:
        return SelfExcitedOrbit(experiment, report)
    return PeriodicOrbit(experiment, report)


def lyapunov(experiment: Experiment, *, transient: int = 1000, periods: int = 20000,
             blocks: int = 20, significance: float = 4.0,
             progress: Progress = None, fixed: bool = False) -> LyapunovResult:
    """The Lyapunov exponents of the motion from the initial state, by the tangent dynamics
    (as ``stickslip lyapunov``): the PWL law's exact ones, or with Shockley diodes those of
    the stiff solver's computed solution.

    The 2×2 Jacobian of the exact flow is carried along the trajectory; after ``transient``
    drive periods the largest exponent λ1 is averaged over at most ``periods`` more, cut into
    ``blocks`` blocks whose spread gives its standard error σ. Two motions that start δ
    apart are about e^(λ1 τ)·δ apart later (τ = ω0·t). The measurement stops at the first of
    its looks (after about periods/32, /16, …, /2 and all of them) where the halves agree and
    |λ1| > kσ (docs/stability.md gives the rule and its significance).

    Args:
        experiment: a ``stickslip.Experiment`` with its drive given (either diode law).
        transient: drive periods run before measuring (0 to 1e9; default 1000).
        periods: drive periods measured (``blocks`` to 1e9; default 20000; rounded down to a
            multiple of ``blocks``).
        blocks: even, from 4 to 10000 (default 20).
        significance: k, the standard errors that make λ1 significant (default 4).
        progress: True for a progress bar (tqdm), a callable ``progress(done, total)``
            (drive periods) or a tqdm bar's ``update``.
        fixed: measure all ``periods`` even when the verdict is decided sooner (default
            False; as ``--fixed``).

    Returns:
        A ``LyapunovResult``; ``to_dict()`` equals ``stickslip lyapunov --json``.

    Raises:
        ValueError: bad input, with the library's message.
        KeyboardInterrupt: Ctrl-C stops a long measurement.

    Example:
        >>> c = stickslip.lyapunov(stickslip.Experiment(zeta=0, mu_s=3, w=0.33, beta=9),
        ...                        transient=500, periods=2000)
        >>> c.motion_class, c.lambda1 > 4 * c.lambda1_error, c.lambda2
        ('chaotic', True, -inf)
    """
    experiment = _with_model(experiment, None)
    blocks = _checks.integer("blocks", blocks, "lyapunov")
    transient = _checks.integer("transient", transient, "lyapunov")
    periods = _checks.integer("periods", periods)
    significance = _checks.number("significance", significance)
    with _progress.reporter(progress, "lyapunov", "periods") as callback:
        report = _core.lyapunov(experiment, transient, periods, blocks, significance, callback,
                                bool(fixed))
    return LyapunovResult(experiment, report)
