//! `GET /api/presets`: the page's presets.

use super::answer::{About, Drive};
use crate::query::{api_name, Query};
use serde::Serialize;
use stickslip::physical::{Circuit, Mechanics};
use stickslip::SystemKind;

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
    use stickslip::experiment::{Key, KeyDefault, KeyGroup};
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
            (api_name(Key::W), 0.95),
            (api_name(Key::Beta), 2.14),
        ],
        paper: false,
    });
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
        preset.into_iter().chain(keys).collect::<Vec<_>>().join("&")
    };
    serde_json::json!({
        "presets": rows.iter().map(|r| serde_json::json!({
            "id": r.id,
            "label": r.label,
            "system": r.system,
            "paper": r.paper,
            "values": r.values.iter().map(|(k, v)| (k.clone(), serde_json::json!(v)))
                .collect::<serde_json::Map<_, _>>(),
            "drive": drive_of(&query(r)),
        })).collect::<Vec<_>>(),
        "shockley": shockley,
        "caps": super::keys::caps_json(),
    })
}
