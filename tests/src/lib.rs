//! Cross-crate checks of the crane models: generated code against the
//! hand-written model, numerical solutions against the analytical references.

pub mod counting;
pub mod damped;
pub mod floor;
pub mod handwritten;
pub mod kit;
pub mod stages;

#[cfg(test)]
mod navy_planar_reference;

#[cfg(test)]
mod navy_planar_pulley_reference;
