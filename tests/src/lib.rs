//! Cross-crate checks of the crane models: generated code against the
//! hand-written model, numerical solutions against the analytical references.

pub mod handwritten;

#[cfg(test)]
mod navy_planar_reference;

#[cfg(test)]
mod navy_planar_pulley_reference;
