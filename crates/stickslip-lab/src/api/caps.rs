//! What one request may ask for at most: the library's profile of a server shared by several
//! users ([`Caps::shared_server`]), which `/api/keys` serves to the page.

use stickslip::limits::Caps;

/// The lab's caps.
pub const CAPS: Caps = Caps::shared_server();
