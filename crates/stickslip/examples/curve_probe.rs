use stickslip::continuation::{curve, ContinuationOptions, CurveSpec, Follow};
use stickslip::{Experiment, Parameter, State};
fn main() {
    // probe FOLLOW VARY VARY_TO OVER FROM TO zeta|paper mu_s w beta [y0 v0] [max_step]
    let a: Vec<String> = std::env::args().collect();
    let f = |i: usize| a[i].parse::<f64>().unwrap();
    let follow = match a[1].as_str() { "grazing" => Follow::Grazing, "fold" => Follow::Fold, "pd" => Follow::PeriodDoubling, _ => Follow::NeimarkSacker };
    let vary: Parameter = a[2].parse().unwrap();
    let over: Parameter = a[4].parse().unwrap();
    let base = if a[7] == "paper" { Experiment::paper() } else { Experiment::dimensionless(f(7), 1.0, 1.0).unwrap() };
    let mut e = base.with_mu_s(f(8)).unwrap().with_w(f(9)).unwrap().with_beta(f(10)).unwrap();
    if a.len() > 12 { e = e.with_initial(State { y: f(11), v: f(12) }).unwrap(); }
    let max_step = if a.len() > 13 { f(13) } else { 0.1 };
    let spec = CurveSpec { follow, vary, vary_to: f(3), over, from: f(5), to: f(6) };
    let t = std::time::Instant::now();
    let c = curve(&e, &spec, &ContinuationOptions::default().with_max_step(max_step), &()).unwrap();
    let c = match c { Ok(c) => c, Err(no) => { println!("{no}"); return; } };
    println!("{} points in {:?}; border {:?}; period {}", c.points.len(), t.elapsed(), c.border, c.period);
    println!("begin {}\nend {}", c.begin, c.end);
    let n = c.points.len();
    for (i, p) in c.points.iter().enumerate() {
        if i % (n / 25).max(1) == 0 || i + 1 == n || i == c.start {
            let m = p.orbit.multipliers;
            println!("{i:4} {:.8} {:.8}  t{} s{}  mu ({:.4},{:.4}) ({:.4},{:.4}) {:?}", p.over, p.vary, p.turns, p.stops, m[0].re, m[0].im, m[1].re, m[1].im, p.stability);
        }
    }
    for x in &c.codim2 { println!("codim2 {:?} at ({:.10}, {:.10}) width {:e} after {} before t{}s{} after t{}s{}", x.kind, x.over, x.vary, x.width, x.after_point, x.before.turns, x.before.stops, x.after.turns, x.after.stops); }
    for s in &c.stability_changes { println!("stability {:?} -> {:?} at ({:.6}, {:.6})", s.from, s.to, s.over, s.vary); }
}
