//! The endpoints' work, each in two steps: `parse` reads the query (at once, on the server's
//! own threads: a bad query costs nothing) and `run` calls the library within a [`Budget`](crate::limit::Budget)
//! (on a worker thread). Answers are library results serialised as they are, with the
//! description of the experiment and its physical scales beside them.
//!
//! One file per endpoint; [`answer`] and [`request`] hold what they share, [`caps`] what one
//! request may ask for, [`upload`] what the endpoints that take a record (`POST /api/record`,
//! `POST /api/fit`) share.

pub mod answer;
pub mod caps;
mod curve;
mod fit;
mod keys;
mod map;
mod orbit;
mod presets;
mod record;
pub mod request;
mod simulate;
mod steady;
mod sweep;
mod theory;
pub mod upload;

pub use curve::*;
pub use fit::*;
pub use keys::*;
pub use map::*;
pub use orbit::*;
pub use presets::*;
pub use record::*;
pub use simulate::*;
pub use steady::*;
pub use sweep::*;
pub use theory::*;
