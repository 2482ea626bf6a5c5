//! `GET /api/keys`: what the page takes from the server rather than writing it down itself:
//! the library's table of model keys, the caps of one request, and the speed below
//! which the mechanical view draws the block stuck.

use super::caps::CAPS;
use super::fit::default_free;
use stickslip::experiment::{DiodeModel, Key, KeyForm, KeyGroup};
use stickslip::fit::FitParameter;
use stickslip::steady::STATIC_GAIN;
use stickslip::SystemKind;

/// |v| (dimensionless velocity y') at or below which the page draws the block stuck: the
/// exact PWL solver holds v = 0 exactly while stuck; the stiff Shockley solver's current
/// through the blocking diodes leaves a small v (below 1e-3 on the paper's circuit).
pub const STUCK_VELOCITY: [(&str, f64); 2] = [("pwl", 1e-9), ("shockley", 1e-3)];

/// The caps of one request, by the names of their JSON fields.
pub fn caps_json() -> serde_json::Value {
    serde_json::to_value(CAPS).unwrap_or_default()
}

/// The fieldset of the page's form a key's field goes in, by the systems it is shown for
/// (the fieldset's `data-for-system`): the circuit's parts for both diode laws, the PWL
/// diodes' resistance, the Shockley diodes' parameters, the mechanical oscillator's parts and
/// μs; `None` for a key the form does not take as a field of its own (ζ follows from the
/// parts; the drive, the initial state, the diode law and the preset have their own
/// controls).
pub fn fieldset(key: Key) -> Option<&'static str> {
    if key == Key::DiodeResistance {
        Some("pwl")
    } else if key.is_circuit_part() {
        Some("pwl shockley")
    } else if key.group() == KeyGroup::Diode && key.form() != KeyForm::Choice {
        Some("shockley")
    } else if key.is_mechanics_part() || key == Key::MuS || mechanical_friction(key) {
        Some("mechanics")
    } else {
        None
    }
}

/// A friction key the mechanical oscillator's form takes: the belt, the law and its
/// parameters as the mechanical twin gives them, in physical units where the table has a
/// physical key for the value (`belt-speed` in m/s, not `vb`), as they are (`friction-law`,
/// `delta`) where it has none.
fn mechanical_friction(key: Key) -> bool {
    key.group() == KeyGroup::Friction && !Key::ALL.into_iter().any(|k| k.image_key() == Some(key))
}

/// A unit as the page writes it ([`Key::shown_unit`]: `Ω` for `ohm`, `N·s/m`); for μs,
/// which has none, its bound (`≥ 1`).
fn shown_unit(key: Key) -> String {
    match key.shown_unit() {
        Some(unit) => unit.to_string(),
        None if key == Key::MuS => format!("≥ {}", key.range().min),
        None => String::new(),
    }
}

/// The page's form, in the key table's order (a physical key at its dimensionless image's
/// place): for each field its key's `flag` (the input's
/// id and name), `fieldset` ([`fieldset`]), `part` (a circuit's part: the input carries
/// `data-part`), the `unit` it shows, its initial `value` (μs: 1, the paper's; a friction
/// key's default: the law `coulomb`, δ = 2; the others are filled from the presets), `choices` (the names a choice
/// takes: the field is a list of them), `law` (the friction law whose parameter it is
/// ([`Key::law`]): shown and sent only while that law is chosen) and `chooses_law` (the field
/// that chooses it).
fn form() -> Vec<serde_json::Value> {
    // A physical key stands where its dimensionless image stands in the table: the belt's
    // speed, the law, then the law's parameters (the Stribeck speed, δ, the viscous term).
    let place = |key: Key| {
        let of = key.image_key().unwrap_or(key);
        Key::ALL.iter().position(|&k| k == of).unwrap_or(usize::MAX)
    };
    let mut keys = Key::ALL.to_vec();
    keys.sort_by_key(|&k| place(k));
    keys.into_iter()
        .filter_map(|key| {
            let fieldset = fieldset(key)?;
            let initial = key == Key::MuS || key.group() == KeyGroup::Friction;
            Some(serde_json::json!({
                "flag": key.flag(),
                "fieldset": fieldset,
                "part": key.is_circuit_part(),
                "unit": shown_unit(key),
                "value": initial
                    .then(|| key.default_value().map(|d| d.to_string()))
                    .flatten(),
                "choices": key.choices(),
                "law": key.law().map(|law| law.label()),
                "chooses_law": key == Key::FrictionLaw,
            }))
        })
        .collect()
}

/// What a fit of a circuit may free (`parameters`, [`FitParameter::CIRCUIT`]), those of each
/// diode law (`by_law`: `pwl` and `shockley`, [`FitParameter::of`]), and those of each law it
/// frees when nothing is ticked, the boxes ticked at first (`free`: `pwl` and `shockley`, the
/// library's default free sets, [`default_free`], as `stickslip fit` frees them).
fn fit() -> serde_json::Value {
    let labels = |list: &[FitParameter]| list.iter().map(|p| p.label()).collect::<Vec<_>>();
    let by_law = |of: fn(DiodeModel) -> Vec<FitParameter>| {
        DiodeModel::ALL
            .iter()
            .map(|&law| (law.label().to_string(), serde_json::json!(labels(&of(law)))))
            .collect::<serde_json::Map<_, _>>()
    };
    serde_json::json!({
        "parameters": labels(&FitParameter::CIRCUIT),
        "by_law": by_law(|law| FitParameter::of(SystemKind::Circuit, law)),
        "free": by_law(default_free),
    })
}

/// The answer of `/api/keys`: `keys` (the library's key table, [`Key::table`]: each model
/// key's query name `flag`, its `name`, `symbol`, group, unit, range, help and default),
/// `form` (the fields of the page's form, [`fieldset`]), `fit` (the parameters a fit of a
/// circuit may free, those of each diode law, and those it frees by default), `caps` (as `/api/presets` has them),
/// `stuck_velocity` (by diode law) and `static_gain` (the library's rule for `static`,
/// [`STATIC_GAIN`]: a gain at most this).
pub fn keys() -> serde_json::Value {
    serde_json::json!({
        "keys": Key::table(),
        "form": form(),
        "fit": fit(),
        "caps": caps_json(),
        "stuck_velocity": STUCK_VELOCITY
            .iter()
            .map(|&(model, v)| (model.to_string(), serde_json::json!(v)))
            .collect::<serde_json::Map<_, _>>(),
        "static_gain": STATIC_GAIN,
    })
}
