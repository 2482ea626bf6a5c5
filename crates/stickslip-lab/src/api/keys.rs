//! `GET /api/keys`: what the page takes from the server rather than writing it down itself:
//! the library's table of model keys, the caps of one request, and the speed below
//! which the mechanical view draws the block stuck.

use super::caps::CAPS;
use stickslip::experiment::Key;

/// |v| (dimensionless velocity y') at or below which the page draws the block stuck: the
/// exact PWL solver holds v = 0 exactly while stuck; the stiff Shockley solver's current
/// through the blocking diodes leaves a small v (below 1e-3 on the paper's circuit).
pub const STUCK_VELOCITY: [(&str, f64); 2] = [("pwl", 1e-9), ("shockley", 1e-3)];

/// The caps of one request, by the names of their JSON fields.
pub fn caps_json() -> serde_json::Value {
    serde_json::to_value(CAPS).unwrap_or_default()
}

/// The answer of `/api/keys`: `keys` (the library's key table, [`Key::table`]: each model
/// key's query name `flag`, its `name`, group, unit, range, help and default), `caps` (as
/// `/api/presets` has them) and `stuck_velocity` (by diode law).
pub fn keys() -> serde_json::Value {
    serde_json::json!({
        "keys": Key::table(),
        "caps": caps_json(),
        "stuck_velocity": STUCK_VELOCITY
            .iter()
            .map(|&(model, v)| (model.to_string(), serde_json::json!(v)))
            .collect::<serde_json::Map<_, _>>(),
    })
}
