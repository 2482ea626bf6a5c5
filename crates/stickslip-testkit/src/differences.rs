//! Derivatives by finite differences, for the tests that check the library's exact and
//! carried derivatives (strobe maps, their parameter derivatives, orbit sensitivities) against
//! the map itself.

use stickslip::State;

/// The derivative of `f` at `x` by central differences with steps h and h/2, extrapolated
/// (Richardson): (4 D(h/2) − D(h))/3 with D(h) = (f(x + h) − f(x − h))/2h, error O(h⁴) for a
/// smooth `f`.
pub fn richardson<const N: usize>(f: impl Fn(f64) -> [f64; N], x: f64, h: f64) -> [f64; N] {
    let central = |h: f64| {
        let (p, m) = (f(x + h), f(x - h));
        std::array::from_fn::<f64, N, _>(|i| (p[i] - m[i]) / (2.0 * h))
    };
    let (coarse, fine) = (central(h), central(h / 2.0));
    std::array::from_fn(|i| (4.0 * fine[i] - coarse[i]) / 3.0)
}

/// The Jacobian ∂map(x)/∂(y, y') at `x` by [`richardson`] with step `h` in y and in y':
/// `d[i][j]` is the derivative of component i by component j of the state.
pub fn state_jacobian(map: impl Fn(State) -> [f64; 2], x: State, h: f64) -> [[f64; 2]; 2] {
    let dy = richardson(|y| map(State { y, ..x }), x.y, h);
    let dv = richardson(|v| map(State { v, ..x }), x.v, h);
    [[dy[0], dv[0]], [dy[1], dv[1]]]
}
