//! `GET /api/presets`: the page's presets.

use super::answer::{About, Drive};
use crate::query::{api_name, Query};
use serde::Serialize;
use stickslip::experiment::Key;
use stickslip::friction::{FrictionLaw, FrictionLawKind};
use stickslip::physical::{Circuit, Mechanics};
use stickslip::SystemKind;

/// The belt speed of the belt presets (dimensionless: 0.3 of the example's velocity unit
/// F0/k·ω0 = 0.1 m/s, so 3 cm/s) and their static ratio μs.
const BELT: (f64, f64) = (0.3, 1.5);

/// The laws of the belt presets, dimensionless: a Stribeck law falling over vs = 0.5 (Gaussian,
/// no viscous term), and a cubic law μs − s + 0.5·s³ (its least value 0.956 at s = 0.816).
/// Both fall at the belt speed fast enough to make steady sliding unstable (2ζ + μ'(vb) < 0):
/// the block sticks and slips on its own, without a drive.
const LAWS: [FrictionLaw; 2] = [
    FrictionLaw::Stribeck {
        vs: 0.5,
        delta: 2.0,
        eta: 0.0,
    },
    FrictionLaw::Cubic { k1: 1.0, k3: 0.5 },
];

/// The parameters of `law` for the example's mechanical oscillator, by the query keys of the
/// mechanical form (the physical twin of each dimensionless parameter, converted with the
/// example's scales; δ as it is).
fn law_values(law: &FrictionLaw) -> Vec<(String, f64)> {
    let scales = Mechanics::example().scales();
    law.parameters()
        .into_iter()
        .filter_map(|(name, x)| {
            let key = Key::ALL.into_iter().find(|k| k.name() == name)?;
            let physical = Key::ALL.into_iter().find(|k| k.image_key() == Some(key));
            Some(match physical {
                Some(p) => (api_name(p), x / p.image(1.0, &scales)?),
                None => (api_name(key), x),
            })
        })
        .collect()
}

/// The points of the paper's Fig. 3: (label, w = Ω/ω0, β), panels (1a)–(2c).
pub const FIG3_POINTS: [(&str, f64, f64); 6] = [
    ("1a", 0.29, 1.07),
    ("1b", 0.95, 1.07),
    ("1c", 1.43, 1.07),
    ("2a", 0.29, 2.14),
    ("2b", 0.95, 2.14),
    ("2c", 1.43, 2.14),
];

/// One preset of the page: values of its fields, by query key.
#[derive(Debug, Serialize)]
pub struct PresetRow {
    /// Identifier.
    pub id: String,
    /// What the page shows.
    pub label: String,
    /// `circuit` or `mechanics`.
    pub system: &'static str,
    /// Values by query key (numbers in SI units); `preset=paper` stands for the paper's parts.
    pub values: Vec<(String, f64)>,
    /// The friction law of a mechanical preset (its parameters are among `values`), sent as
    /// `friction-law`; `None` for a circuit.
    pub law: Option<FrictionLawKind>,
    /// Whether the preset is the paper's circuit (`preset=paper` describes it exactly).
    pub paper: bool,
}

/// The generator's setting of a preset: the drive in Hz and V (or N) of the experiment its
/// query describes (`preset=paper&w=0.95&beta=2.14`), as `/api/steady` answers it for that
/// query; `None` for a preset without a drive.
fn drive_of(query: &str) -> Option<Drive> {
    let mut q = Query::parse(Some(query)).ok()?;
    let e = q.experiment().ok()?;
    About::new(&e).drive
}

/// `GET /api/presets`: the paper's circuit, its Fig. 3 points, the 1N4148 Shockley
/// parameters (the defaults of the key table's diode group) and a mechanical oscillator with
/// the paper's damping ratio. A preset with a drive point (w, β) also carries the generator's
/// setting it stands for (`drive`: `f_Hz` and `amplitude` in V or N): the page sets its
/// generator to it once, and changing a part afterwards leaves the generator where it is.
pub fn presets() -> serde_json::Value {
    use stickslip::experiment::{KeyDefault, KeyGroup};
    use stickslip::physical::Diode;
    let paper = Circuit::paper();
    let (turn_on, rd) = match paper.diode {
        Diode::Pwl(d) => (d.turn_on, d.resistance),
        Diode::Shockley(d) => (d.reference_voltage, 0.0),
    };
    let parts = vec![
        (api_name(Key::Inductance), paper.inductance),
        (api_name(Key::Capacitance), paper.capacitance),
        (api_name(Key::Resistance), paper.resistance),
        (api_name(Key::TurnOn), turn_on),
        (api_name(Key::DiodeResistance), rd),
    ];
    let mut rows = vec![PresetRow {
        id: "paper".into(),
        label: "the paper's circuit (L = 11.5 mH, C = 20 nF, R = 68 Ω, U_t = 0.7 V, R_D = 3 Ω)"
            .into(),
        system: SystemKind::Circuit.label(),
        values: parts.clone(),
        law: None,
        paper: true,
    }];
    for (panel, w, beta) in FIG3_POINTS {
        let mut values = parts.clone();
        values.push((api_name(Key::W), w));
        values.push((api_name(Key::Beta), beta));
        rows.push(PresetRow {
            id: format!("fig3-{panel}"),
            label: format!("paper, Fig. 3 ({panel}): Ω/ω0 = {w}, β = {beta}"),
            system: SystemKind::Circuit.label(),
            values,
            law: None,
            paper: true,
        });
    }
    // A mass on a spring with dry friction, ζ = 0.94/(2·√(200·0.5)) = 0.047 as the paper's.
    let example = Mechanics::example();
    rows.push(PresetRow {
        id: SystemKind::Mechanics.label().into(),
        label: format!(
            "a mass on a spring with dry friction (m = {} kg, k = {} N/m, γ = {} N·s/m, F0 = {} N)",
            example.mass, example.stiffness, example.damping, example.friction
        ),
        system: SystemKind::Mechanics.label(),
        values: vec![
            (api_name(Key::Mass), example.mass),
            (api_name(Key::Stiffness), example.stiffness),
            (api_name(Key::Damping), example.damping),
            (api_name(Key::Friction), example.friction),
            (api_name(Key::MuS), 1.0),
            (api_name(Key::BeltSpeed), 0.0),
            (api_name(Key::W), 0.95),
            (api_name(Key::Beta), 2.14),
        ],
        law: Some(FrictionLawKind::Coulomb),
        paper: false,
    });
    // The same block on a belt at 3 cm/s, without a drive: a stick-slip cycle of its own
    // with each falling law.
    let scales = example.scales();
    for law in LAWS {
        let kind = law.kind();
        let mut values = vec![
            (api_name(Key::Mass), example.mass),
            (api_name(Key::Stiffness), example.stiffness),
            (api_name(Key::Damping), example.damping),
            (api_name(Key::Friction), example.friction),
            (api_name(Key::MuS), BELT.1),
            (
                api_name(Key::BeltSpeed),
                BELT.0 / Key::BeltSpeed.image(1.0, &scales).unwrap_or(1.0),
            ),
        ];
        values.extend(law_values(&law));
        values.push((api_name(Key::W), 1.0));
        values.push((api_name(Key::Beta), 0.0));
        rows.push(PresetRow {
            id: format!("belt-{}", kind.label()),
            label: format!(
                "the block on a belt at {} m/s, {} friction (no drive: stick-slip of its own)",
                BELT.0 / Key::BeltSpeed.image(1.0, &scales).unwrap_or(1.0),
                kind.label()
            ),
            system: SystemKind::Mechanics.label(),
            values,
            law: Some(kind),
            paper: false,
        });
    }
    // The Shockley diodes' values the page starts from: every number of the diode group at
    // its default (the 1N4148's), from the key table.
    let shockley: serde_json::Map<_, _> = Key::ALL
        .into_iter()
        .filter(|k| k.group() == KeyGroup::Diode)
        .filter_map(|k| match k.default_value()? {
            KeyDefault::Number(x) => Some((api_name(k), serde_json::json!(x))),
            KeyDefault::Name(_) => None,
        })
        .collect();
    let query = |r: &PresetRow| -> String {
        let values = r
            .values
            .iter()
            .filter(|(k, _)| !r.paper || k == "w" || k == "beta");
        let keys = values.map(|(k, v)| format!("{k}={v}"));
        let preset = r.paper.then(|| "preset=paper".to_string());
        let law = r
            .law
            .map(|law| format!("{}={}", api_name(Key::FrictionLaw), law.label()));
        preset
            .into_iter()
            .chain(keys)
            .chain(law)
            .collect::<Vec<_>>()
            .join("&")
    };
    // The parameters of each law, to start its fields from when it is chosen.
    let laws: serde_json::Map<_, _> = LAWS
        .iter()
        .map(|law| {
            let values = law_values(law)
                .into_iter()
                .map(|(k, v)| (k, serde_json::json!(v)));
            (law.kind().label().to_string(), values.collect())
        })
        .collect();
    serde_json::json!({
        "presets": rows.iter().map(|r| serde_json::json!({
            "id": r.id,
            "label": r.label,
            "system": r.system,
            "paper": r.paper,
            "values": r.values.iter().map(|(k, v)| (k.clone(), serde_json::json!(v)))
                .chain(r.law.map(|law| (api_name(Key::FrictionLaw), serde_json::json!(law.label()))))
                .collect::<serde_json::Map<_, _>>(),
            "drive": drive_of(&query(r)),
        })).collect::<Vec<_>>(),
        "shockley": shockley,
        "laws": laws,
        "caps": super::keys::caps_json(),
    })
}
