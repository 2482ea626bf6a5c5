//! The Shockley diode-pair model and its stiff solver.
