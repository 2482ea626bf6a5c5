//! The option table's data: the keys, their rows and how a front end spells them.

use serde::Serialize;

/// How a front end spells an option (or a key) in its messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Spelling {
    /// The command line: `--max-period` (and `invalid --max-period 65: …`).
    Flag,
    /// Python's keyword and the library's own messages: `max_period` (and
    /// `invalid max_period = 65: …`).
    Python,
    /// The lab's query key: `max-period` (and `invalid max-period = 65: …`).
    Query,
}

/// The computation an option belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum OptionGroup {
    /// A run from the initial state (`simulate`).
    Simulate,
    /// The steady-state search (`steady`, `sweep`, `phase-diagram`).
    Steady,
    /// A periodic orbit by Newton's method (`orbit`).
    Orbit,
    /// Lyapunov exponents (`lyapunov`).
    Lyapunov,
    /// A sweep of one parameter (`sweep`).
    Sweep,
    /// A map of two parameters (`phase-diagram`).
    Map,
    /// A bifurcation diagram (`bifurcation`).
    Bifurcation,
    /// Basins of attraction (`basins`).
    Basins,
    /// A branch of periodic orbits (`continue`).
    Continuation,
    /// A curve of the theory (`theory --curve`).
    Curve,
    /// A curve of special points in two parameters (`curve`).
    TwoParameter,
    /// The pool of threads of a parallel computation.
    Pool,
    /// The report of one steady state (`steady` on the command line, `/api/steady` in the
    /// lab; Python's `steady` takes the search's [`OptionKey::Harmonics`]).
    SteadyReport,
    /// Saving finished work as a long computation goes (`--checkpoint`).
    Checkpoint,
    /// A SPICE netlist of the circuit (`netlist`).
    Netlist,
    /// The lab server's own settings (`stickslip lab`).
    Lab,
}

/// What values an option takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum OptionKind {
    /// A whole number.
    Count,
    /// A real number.
    Number,
    /// On or off.
    Switch,
    /// A name (a file name, say).
    Text,
}

/// One end of a range.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Bound {
    /// The value.
    pub value: f64,
    /// Whether the value itself is allowed.
    pub inclusive: bool,
}

const fn incl(value: f64) -> Option<Bound> {
    Some(Bound {
        value,
        inclusive: true,
    })
}

const fn excl(value: f64) -> Option<Bound> {
    Some(Bound {
        value,
        inclusive: false,
    })
}

/// A rule beyond the range.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Rule {
    /// The range alone.
    Range,
    /// An even number.
    Even,
    /// A power of two.
    PowerOfTwo,
    /// 0 (off) or a value in the range.
    ZeroIsOff,
}

/// An option of a computation (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[non_exhaustive]
pub enum OptionKey {
    /// Drive periods of a run from the initial state.
    SimulatePeriods,
    /// Samples per drive period of a run.
    SimulateSamples,
    /// Relative tolerance of the steady state's stroboscopic repetition.
    Tolerance,
    /// Drive periods run at most before calling the motion non-periodic.
    MaxPeriods,
    /// Longest period looked for by the steady state.
    MaxPeriod,
    /// Whether the stroboscopic map may be extrapolated (the flag says the opposite).
    Accelerate,
    /// Drive periods over which a motion that does not repeat is measured (0: not measured).
    LyapunovPeriods,
    /// Shortest stop that counts, as a fraction of the drive period.
    MinStopFraction,
    /// Drive harmonics reported.
    Harmonics,
    /// Samples per drive period of the spectrum.
    SpectrumSamples,
    /// Period of the orbit looked for.
    OrbitPeriod,
    /// Drive periods run before Newton's method starts.
    OrbitTransient,
    /// Drive periods run at most to find the steady state's period (orbit).
    OrbitMaxPeriods,
    /// Longest period looked for (orbit).
    OrbitMaxPeriod,
    /// Relative tolerance of Newton's method.
    NewtonTolerance,
    /// Most Newton steps.
    MaxIterations,
    /// Drive periods run before measuring the exponents.
    LyapunovTransient,
    /// Drive periods measured.
    LyapunovMeasured,
    /// Blocks the measured periods are cut into.
    Blocks,
    /// Standard errors that make an exponent significant.
    Significance,
    /// Measure all periods even when the verdict is decided sooner.
    Fixed,
    /// Values of a sweep.
    SweepSteps,
    /// Frequencies of a map.
    MapWSteps,
    /// Amplitudes of a map.
    MapBetaSteps,
    /// Values of a map's first key (`--x`).
    MapXSteps,
    /// Values of a map's second key (`--y`).
    MapYSteps,
    /// Lowest frequency w of a map.
    MapWMin,
    /// Highest frequency w of a map.
    MapWMax,
    /// Lowest amplitude β of a map.
    MapBetaMin,
    /// Highest amplitude β of a map.
    MapBetaMax,
    /// Values of a bifurcation diagram.
    BifurcationSteps,
    /// Strobe points recorded at each value of a bifurcation diagram.
    Points,
    /// Transient at each value of a bifurcation diagram.
    BifurcationTransient,
    /// Transient at the first value of a bifurcation diagram.
    FirstTransient,
    /// Longest period looked for in the recorded points of a bifurcation diagram.
    BifurcationMaxPeriod,
    /// Initial states along each axis of a basin map.
    BasinSteps,
    /// Drive periods run at most to find a period (basins).
    BasinMaxPeriods,
    /// Longest period looked for (basins).
    BasinMaxPeriod,
    /// Drive periods over which the exponent of a motion without a period is measured
    /// (basins).
    BasinLyapunovPeriods,
    /// Cells of the state-space grid along each axis (basins by recurrence).
    Resolution,
    /// Most points of a branch.
    MaxPoints,
    /// Largest step of arclength of a branch.
    MaxStep,
    /// Points of a theory curve.
    CurveSteps,
    /// Threads of a pool.
    Threads,
    /// Drive harmonics in the report of one steady state (at least 9, the paper's).
    ReportHarmonics,
    /// Least time between two saves of a checkpoint, in seconds.
    CheckpointEvery,
    /// Samples per drive period of the trace in the report of one steady state.
    TraceSamples,
    /// Value of the parameter where a branch starts.
    ContinuationFrom,
    /// Value of the parameter a branch is continued towards.
    ContinuationTo,
    /// Value of P the search for a curve's start heads for (the orbit settled on at the
    /// model's point is continued in P towards it).
    TwoParameterVaryTo,
    /// One end of the range of Q a curve of special points is followed over.
    TwoParameterFrom,
    /// The end of Q's range a curve of special points heads for.
    TwoParameterTo,
    /// Most points of a curve of special points.
    TwoParameterMaxPoints,
    /// Largest step of arclength of a curve of special points.
    TwoParameterMaxStep,
    /// The parameter a curve of special points is followed over (Q).
    TwoParameterOver,
    /// The parameter continued to find a curve's start, which then follows the curve (P).
    TwoParameterVary,
    /// Smallest frequency w of a theory curve.
    CurveWMin,
    /// Largest frequency w of a theory curve.
    CurveWMax,
    /// Drive periods of a netlist's transient analysis.
    NetlistPeriods,
    /// Output points per drive period of a netlist.
    NetlistPoints,
    /// Largest SPICE time step, as a fraction of the drive period.
    NetlistMaxStep,
    /// SPICE's relative tolerance.
    NetlistReltol,
    /// SPICE's absolute current tolerance (A).
    NetlistAbstol,
    /// SPICE's absolute voltage tolerance (V).
    NetlistVntol,
    /// File ngspice writes the analysis to.
    NetlistWrdata,
    /// The lab server's time limit of one request, in seconds.
    LabTimeLimit,
    /// The lab server's computations at once.
    LabJobs,
}

/// One row of [`OptionKey::table`]: everything a front end needs to offer, parse, check and
/// document an option.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OptionInfo {
    /// The key (its variant name).
    pub key: OptionKey,
    /// The computation it belongs to.
    pub group: OptionGroup,
    /// Spelling on the command line (without dashes) and in the lab's query.
    pub flag: &'static str,
    /// Python keyword, and the name in the library's messages.
    pub name: &'static str,
    /// What values it takes.
    pub kind: OptionKind,
    /// Smallest value, if bounded below.
    pub min: Option<Bound>,
    /// Largest value, if bounded above.
    pub max: Option<Bound>,
    /// A rule beyond the range.
    pub rule: Rule,
    /// What is allowed, in words (the end of the error message).
    pub allowed: &'static str,
    /// The default, if it does not depend on the experiment.
    pub default: Option<f64>,
    /// One-line help (the command line's).
    pub help: &'static str,
}

macro_rules! rows {
    ($( $key:ident, $group:ident, $flag:literal, $name:literal, $kind:ident, $min:expr, $max:expr,
        $rule:ident, $allowed:literal, $default:expr, $help:literal; )*) => {
        impl OptionKey {
            /// Every option, in the order of the table.
            pub const ALL: &'static [OptionKey] = &[$(OptionKey::$key),*];

            /// The option's row of the table.
            pub fn info(self) -> OptionInfo {
                match self {
                    $(OptionKey::$key => OptionInfo {
                        key: OptionKey::$key,
                        group: OptionGroup::$group,
                        flag: $flag,
                        name: $name,
                        kind: OptionKind::$kind,
                        min: $min,
                        max: $max,
                        rule: Rule::$rule,
                        allowed: $allowed,
                        default: $default,
                        help: $help,
                    },)*
                }
            }
        }
    };
}

rows! {
    SimulatePeriods, Simulate, "periods", "periods", Number, excl(0.0), None, Range,
        "must be finite and > 0", Some(20.0),
        "Number of drive periods to simulate (> 0).";
    SimulateSamples, Simulate, "samples-per-period", "samples_per_period", Count, incl(1.0),
        incl(5e7), Range,
        "must be from 1 to 5e7 (and periods × samples_per_period at most 5e7)", Some(200.0),
        "Samples per drive period in the CSV (≥ 1).";
    Tolerance, Steady, "tolerance", "tolerance", Number, excl(0.0), excl(1.0), Range,
        "must be > 0 and < 1", None,
        "Relative tolerance of the once-per-period (stroboscopic) repetition [default: 1e-10 with the exact PWL solver, 1e-6 (its rtol) with the Shockley solver].";
    MaxPeriods, Steady, "max-periods", "max_periods", Count, incl(1.0), incl(1e8), Range,
        "must be from 1 to 1e8", Some(5000.0),
        "Drive periods run at most before calling the motion non-periodic.";
    MaxPeriod, Steady, "max-period", "max_period", Count, incl(1.0), incl(64.0), Range,
        "must be from 1 to 64", Some(16.0),
        "Longest period looked for, in drive periods (1 to 64).";
    Accelerate, Steady, "no-extrapolation", "accelerate", Switch, None, None, Range,
        "must be on or off", Some(1.0),
        "Never extrapolate the stroboscopic map to its fixed point nor settle it by Newton's method (slower; finds the same cycle).";
    LyapunovPeriods, Steady, "lyapunov-periods", "lyapunov_periods", Count, incl(20.0),
        incl(1e8), ZeroIsOff, "must be 0 (off) or from 20 to 1e8", Some(5000.0),
        "Drive periods over which a motion that does not repeat is measured by its largest Lyapunov exponent (exact PWL model; after 100 periods that align the tangent, in 20 blocks): chaotic when it is positive beyond 4 standard errors. 0: not measured.";
    MinStopFraction, Steady, "min-stop-fraction", "min_stop_fraction", Number, incl(0.0),
        excl(1.0), Range, "must be >= 0 and < 1", Some(1e-8),
        "Shortest stop that counts, as a fraction of the drive period.";
    Harmonics, Steady, "harmonics", "harmonics", Count, incl(1.0), incl(256.0), Range,
        "must be from 1 to 256", Some(16.0),
        "Number of drive harmonics reported.";
    SpectrumSamples, Steady, "spectrum-samples", "samples_per_period", Count, incl(16.0),
        incl(1048576.0), PowerOfTwo, "must be a power of two from 16 to 1048576", None,
        "Samples per drive period of the spectrum [default: chosen from the event log].";
    OrbitPeriod, Orbit, "period", "period", Count, incl(1.0), incl(1000.0), Range,
        "must be from 1 to 1000", None,
        "Period p of the orbit in drive periods (1 to 1000) [default: that of the steady state].";
    OrbitTransient, Orbit, "transient", "transient", Count, incl(0.0), incl(1e8), Range,
        "must be from 0 to 1e8", Some(0.0),
        "With --period: drive periods run from the initial state before Newton's method starts.";
    OrbitMaxPeriods, Orbit, "max-periods", "max_periods", Count, incl(1.0), incl(1e8), Range,
        "must be from 1 to 1e8", Some(5000.0),
        "Without --period: drive periods run at most to find the steady state's period.";
    OrbitMaxPeriod, Orbit, "max-period", "max_period", Count, incl(1.0), incl(64.0), Range,
        "must be from 1 to 64", Some(16.0),
        "Without --period: longest period looked for (1 to 64).";
    NewtonTolerance, Orbit, "newton-tolerance", "tolerance", Number, excl(0.0), excl(1e-3),
        Range, "must be > 0 and < 1e-3", Some(1e-12),
        "Relative tolerance of Newton's method on max(|Δy|, |Δy'|) of P^p(x) − x.";
    MaxIterations, Orbit, "max-iterations", "max_iterations", Count, incl(1.0), incl(1000.0),
        Range, "must be from 1 to 1000", Some(30.0),
        "Most Newton steps (1 to 1000).";
    LyapunovTransient, Lyapunov, "transient", "transient", Count, incl(0.0), incl(1e9), Range,
        "must be from 0 to 1e9", Some(1000.0),
        "Drive periods run before measuring (0 to 1e9).";
    LyapunovMeasured, Lyapunov, "periods", "periods", Count, incl(4.0), incl(1e9), Range,
        "must be from blocks to 1e9", Some(20000.0),
        "Drive periods measured (rounded down to a multiple of --blocks; up to 1e9).";
    Blocks, Lyapunov, "blocks", "blocks", Count, incl(4.0), incl(10000.0), Even,
        "must be even and from 4 to 10000", Some(20.0),
        "Blocks the measured periods are cut into for the error (even, 4 to 10000).";
    Significance, Lyapunov, "significance", "significance", Number, excl(0.0), None, Range,
        "must be finite and > 0", Some(4.0),
        "Standard errors k that make λ1 significantly positive or negative.";
    Fixed, Lyapunov, "fixed", "fixed", Switch, None, None, Range, "must be on or off",
        Some(0.0), "Measure all --periods, even when the verdict is decided sooner.";
    SweepSteps, Sweep, "steps", "steps", Count, incl(1.0), incl(100000.0), Range,
        "must be from 1 to 100000", None,
        "Number of values from --from to --to, both included (≥ 2, or 1 when they are equal).";
    MapWSteps, Map, "w-steps", "w_steps", Count, incl(1.0), incl(100000.0), Range,
        "must be from 1 to 100000", Some(100.0),
        "Number of frequencies from --w-min to --w-max, both included.";
    MapBetaSteps, Map, "beta-steps", "beta_steps", Count, incl(1.0), incl(100000.0), Range,
        "must be from 1 to 100000", Some(100.0),
        "Number of amplitudes from --beta-min to --beta-max, both included.";
    MapXSteps, Map, "x-steps", "x_steps", Count, incl(1.0), incl(100000.0), Range,
        "must be from 1 to 100000", Some(100.0),
        "Number of values of --x from --x-from to --x-to, both included.";
    MapYSteps, Map, "y-steps", "y_steps", Count, incl(1.0), incl(100000.0), Range,
        "must be from 1 to 100000", Some(100.0),
        "Number of values of --y from --y-from to --y-to, both included.";
    MapWMin, Map, "w-min", "w_min", Number, incl(1e-5), incl(1e5), Range,
        "must be finite and from 1e-5 to 1e5 (docs/limits.md)", Some(0.1),
        "Lowest drive frequency w.";
    MapWMax, Map, "w-max", "w_max", Number, incl(1e-5), incl(1e5), Range,
        "must be finite and from 1e-5 to 1e5 (docs/limits.md)", Some(2.5),
        "Highest drive frequency w (≥ --w-min).";
    MapBetaMin, Map, "beta-min", "beta_min", Number, incl(0.0), incl(1e9), Range,
        "must be finite and from 0 to 1e9 (docs/limits.md)", Some(0.5),
        "Lowest drive amplitude β.";
    MapBetaMax, Map, "beta-max", "beta_max", Number, incl(0.0), incl(1e9), Range,
        "must be finite and from 0 to 1e9 (docs/limits.md)", Some(4.0),
        "Highest drive amplitude β (≥ --beta-min).";
    BifurcationSteps, Bifurcation, "steps", "steps", Count, incl(1.0), incl(100000.0), Range,
        "must be from 1 to 100000", None,
        "Number of values from --from to --to, both included.";
    Points, Bifurcation, "points", "points", Count, incl(1.0), incl(1e6), Range,
        "must be from 1 to 1000000", Some(100.0),
        "Strobe points recorded at each value (drive periods).";
    BifurcationTransient, Bifurcation, "transient", "transient", Count, incl(0.0), incl(1e8),
        Range, "must be from 0 to 1e8 drive periods", Some(200.0),
        "Drive periods of transient at each value before recording.";
    FirstTransient, Bifurcation, "first-transient", "first_transient", Count, incl(0.0),
        incl(1e8), Range, "must be from 0 to 1e8 drive periods", Some(2000.0),
        "Drive periods of transient at the first value, from the initial state.";
    BifurcationMaxPeriod, Bifurcation, "max-period", "max_period", Count, incl(1.0),
        incl(1000.0), Range, "must be from 1 to 1000", Some(32.0),
        "Longest period looked for in the recorded points (drive periods).";
    BasinSteps, Basins, "steps", "steps", Count, incl(1.0), incl(2000.0), Range,
        "must be from 1 to 2000", Some(100.0),
        "Grid points along each axis (the map has --steps × --steps cells).";
    BasinMaxPeriods, Basins, "max-periods", "max_periods", Count, incl(1.0), incl(1e8), Range,
        "must be from 1 to 1e8", Some(1000.0),
        "Drive periods run at most to find a period.";
    BasinMaxPeriod, Basins, "max-period", "max_period", Count, incl(1.0), incl(64.0), Range,
        "must be from 1 to 64", Some(16.0),
        "Longest period looked for, in drive periods (1 to 64).";
    BasinLyapunovPeriods, Basins, "lyapunov-periods", "lyapunov_periods", Count, incl(8.0),
        incl(1e7), Range, "must be from 8 to 1e7", Some(1000.0),
        "Drive periods over which the exponent of a motion without a period is measured.";
    Resolution, Basins, "resolution", "resolution", Count, incl(16.0), incl(1e6), Range,
        "must be from 16 to 1e6", Some(1024.0),
        "Recurrence: cells of the state-space grid across the map's extent along each axis (16 to 1e6; at least 4 per grid spacing of the map are used).";
    MaxPoints, Continuation, "max-points", "max_points", Count, incl(2.0), incl(1e7), Range,
        "must be from 2 to 10000000", Some(5000.0),
        "Most points of the branch.";
    MaxStep, Continuation, "max-step", "max_step", Number, excl(0.0), incl(10.0), Range,
        "must be > 0 and <= 10", Some(0.1),
        "Largest step of arclength in (y, y', parameter).";
    CurveSteps, Curve, "steps", "steps", Count, incl(2.0), incl(100000.0), Range,
        "must be from 2 to 100000 (the number of points)", Some(200.0),
        "Number of points of the curve, both ends included: it has this many rows (2 to 100000) [default: 200]. (--steps counts points in every command.)";
    Threads, Pool, "threads", "threads", Count, incl(1.0), incl(1024.0), Range,
        "must be from 1 to 1024", None,
        "Threads of the pool [default: one per core].";
    ReportHarmonics, SteadyReport, "harmonics", "harmonics", Count, incl(9.0), incl(256.0),
        Range, "must be from 9 to 256", Some(16.0),
        "Number of drive harmonics reported (at least 9).";
    CheckpointEvery, Checkpoint, "checkpoint-every", "checkpoint_every", Number, incl(0.0),
        incl(86400.0), Range, "must be from 0 to 86400 seconds", Some(10.0),
        "Least time between two saves of the checkpoint, in seconds (0: after every finished row or step); a save also waits twenty times as long as the last one took.";
    TraceSamples, SteadyReport, "samples", "samples", Count, incl(16.0), incl(1048576.0),
        PowerOfTwo, "must be a power of two from 16 to 1048576", Some(512.0),
        "Samples per drive period of the steady cycle's trace.";
    ContinuationFrom, Continuation, "from", "start", Number, None, None, Range,
        "must be a finite value of the parameter", None,
        "Start value: the orbit the motion settles on here is continued.";
    ContinuationTo, Continuation, "to", "to", Number, None, None, Range,
        "must be a finite value of the parameter", None,
        "Value to continue towards (above or below --from); the branch stays between the two.";
    TwoParameterVaryTo, TwoParameter, "vary-to", "vary_to", Number, None, None, Range,
        "must be a finite value of the varied parameter, other than the model's", None,
        "Value of --vary that the search for the start heads for: the orbit the motion settles on at the model's point is continued in --vary towards it, up to its first special point of the followed kind.";
    TwoParameterFrom, TwoParameter, "from", "start", Number, None, None, Range,
        "must be a finite value of the parameter", None,
        "One end of the range of --over (the model's value of --over must lie between --from and --to; the curve goes both ways when it lies inside).";
    TwoParameterTo, TwoParameter, "to", "to", Number, None, None, Range,
        "must be a finite value of the parameter", None,
        "The end of the range of --over the curve heads for (above or below --from).";
    TwoParameterMaxPoints, TwoParameter, "max-points", "max_points", Count, incl(2.0),
        incl(1e7), Range, "must be from 2 to 10000000", Some(5000.0),
        "Most points of the curve, each way.";
    TwoParameterMaxStep, TwoParameter, "max-step", "max_step", Number, excl(0.0), incl(10.0),
        Range, "must be > 0 and <= 10", Some(0.1),
        "Largest step of arclength in (y, y', --over, --vary).";
    TwoParameterOver, TwoParameter, "over", "over", Text, None, None, Range,
        "must be a parameter other than the varied one", None,
        "The parameter the curve is followed over (Q).";
    TwoParameterVary, TwoParameter, "vary", "vary", Text, None, None, Range,
        "must be a parameter other than the one the curve is followed over", None,
        "The parameter continued to find the start, which then follows the curve (P).";
    CurveWMin, Curve, "w-min", "w_min", Number, incl(1e-5), incl(1e5), Range,
        "must be finite and from 1e-5 to 1e5 (docs/limits.md)", Some(0.2),
        "Smallest w of the curve (> 0) [default: 0.2].";
    CurveWMax, Curve, "w-max", "w_max", Number, incl(1e-5), incl(1e5), Range,
        "must be finite and from 1e-5 to 1e5 (docs/limits.md)", Some(3.0),
        "Largest w of the curve (> --w-min) [default: 3].";
    NetlistPeriods, Netlist, "periods", "periods", Number, excl(0.0), None, Range,
        "must be finite and > 0", Some(300.0),
        "Simulated time in drive periods (> 0).";
    NetlistPoints, Netlist, "points-per-period", "points_per_period", Count, incl(1.0),
        incl(4294967295.0), Range, "must be > 0", Some(200.0),
        "Output points per drive period (the .tran print step), ≥ 1.";
    NetlistMaxStep, Netlist, "max-step", "max_step_fraction", Number, excl(0.0), incl(1.0),
        Range, "must be > 0 and at most 1", Some(1e-3),
        "Largest SPICE time step as a fraction of the drive period, in (0, 1].";
    NetlistReltol, Netlist, "reltol", "reltol", Number, excl(0.0), None, Range,
        "must be finite and > 0", None,
        "SPICE relative tolerance (.options reltol) [default: SPICE's, 1e-3].";
    NetlistAbstol, Netlist, "abstol", "abstol", Number, excl(0.0), None, Range,
        "must be finite and > 0", None,
        "SPICE absolute current tolerance in A (.options abstol) [default: SPICE's, 1e-12].";
    NetlistVntol, Netlist, "vntol", "vntol", Number, excl(0.0), None, Range,
        "must be finite and > 0", None,
        "SPICE absolute voltage tolerance in V (.options vntol) [default: SPICE's, 1e-6].";
    NetlistWrdata, Netlist, "wrdata", "wrdata", Text, None, None, Range,
        "must be a file name without spaces, quotes or line breaks", None,
        "Add an ngspice .control block that runs the analysis and writes time, u_C and i to this file with wrdata (a name without spaces; relative to where ngspice runs).";
    LabTimeLimit, Lab, "time-limit", "time_limit", Number, incl(0.1), incl(600.0), Range,
        "must be from 0.1 to 600 (seconds)", Some(10.0),
        "Time limit of one request in seconds, waiting for a worker included (0.1 to 600).";
    LabJobs, Lab, "jobs", "jobs", Count, incl(1.0), incl(256.0), Range,
        "must be from 1 to 256", None,
        "Computations at once; further requests wait for a turn within their time limit [default: the number of cores].";
}

/// What an option allows, in an [`crate::Error::InvalidOption`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Allowed {
    /// The table's words ([`OptionKey::allowed`]).
    Table,
    /// Other words (a rule between options that the table cannot state).
    Text(&'static str),
    /// From the value of another option to a bound: `must be from blocks (20) to 1e9`.
    FromOption {
        /// The other option.
        other: OptionKey,
        /// Its value.
        value: f64,
        /// The upper bound, in words.
        to: &'static str,
    },
    /// At most `max` under a caps profile ([`crate::limits::Caps`]).
    Cap {
        /// Smallest value allowed.
        min: f64,
        /// Largest value the profile allows.
        max: f64,
    },
    /// Another value than that of another option: `must differ from --from`.
    Differs {
        /// The other option.
        other: OptionKey,
    },
    /// Only together with another option: `--transient needs --period (why)`.
    Needs {
        /// The other option.
        other: OptionKey,
        /// Why, in words.
        why: &'static str,
    },
    /// Not 0 (its "off") where the computation needs what the option turns on:
    /// `--lyapunov-periods must not be 0 (why)`.
    NotOff {
        /// Why, in words.
        why: &'static str,
    },
    /// Above the value of another option: `must be greater than --w-min (2)`.
    Above {
        /// The other option.
        other: OptionKey,
        /// Its value.
        value: f64,
    },
    /// Not below the value of another option (the upper end of a range):
    /// `must not be below --beta-min 0.5`.
    NotBelow {
        /// The other option.
        other: OptionKey,
        /// Its value.
        value: f64,
    },
}
