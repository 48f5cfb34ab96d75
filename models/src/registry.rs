//! The built-in cranes, one line each: [`CATALOG`] for listing and
//! [`visit`] for running code on a crane by name, with its sizes `n, m, a`
//! taken from the generated model (no sizes written by hand).
//!
//! Adding a built-in crane: a module with its declaration and a
//! [`Crane`] description, and one line in the `registry!`
//! call at the end of this file.
//!
//! ```
//! use crane_models::registry::{self, Visit};
//! use crane_models::Crane;
//!
//! /// Counts a crane's coordinates.
//! struct Coordinates;
//! impl Visit for Coordinates {
//!     type Output = usize;
//!     fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> usize {
//!         N
//!     }
//! }
//! assert_eq!(registry::visit("navy-planar", Coordinates), Some(7));
//! assert_eq!(registry::visit("no-such-crane", Coordinates), None);
//! ```

use crate::crane::Crane;

/// A built-in crane, as `crane list` shows it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Entry {
    /// Name on the command line.
    pub name: &'static str,
    /// One line on what it is.
    pub description: &'static str,
    /// Redundant coordinates `n`.
    pub n: usize,
    /// Holonomic constraints `m`.
    pub m: usize,
    /// Inputs = load coordinates `a`.
    pub a: usize,
    /// Whether an analytical reference exists.
    pub reference: bool,
    /// Whether a minimal-coordinate map exists.
    pub minimal: bool,
}

impl Entry {
    /// Degrees of freedom `f = n - m`.
    pub fn dof(&self) -> usize {
        self.n - self.m
    }
}

/// Code to run on one crane, whichever: [`visit`] calls
/// `visit::<C, N, M, A>()` with the crane's description and sizes.
pub trait Visit {
    /// What the visit returns.
    type Output;
    /// Run on crane `C` with `n = N`, `m = M`, `a = A`.
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output;
}

/// An associated item of a built-in crane's description: `described!(module,
/// Model, ITEM)` is `<module::Description as Crane<N, M, A>>::ITEM` with the
/// sizes of `module::Model`.
macro_rules! described {
    ($module:ident, $model:ident, $item:ident) => {
        <crate::$module::Description as Crane<
            { crate::$module::$model::N },
            { crate::$module::$model::M },
            { crate::$module::$model::A },
        >>::$item
    };
}

macro_rules! registry {
    ($($module:ident :: $model:ident),* $(,)?) => {
        /// The built-in cranes, in the order `crane list` shows them.
        pub const CATALOG: &[Entry] = &[$(
            Entry {
                name: described!($module, $model, NAME),
                description: described!($module, $model, DESCRIPTION),
                n: crate::$module::$model::N,
                m: crate::$module::$model::M,
                a: crate::$module::$model::A,
                reference: described!($module, $model, HAS_REFERENCE),
                minimal: described!($module, $model, HAS_MINIMAL_MAP),
            },
        )*];

        /// Run `visitor` on the built-in crane called `name`; `None` if there is none.
        pub fn visit<V: Visit>(name: &str, visitor: V) -> Option<V::Output> {
            $(
                if name == described!($module, $model, NAME) {
                    return Some(visitor.visit::<
                        crate::$module::Description,
                        { crate::$module::$model::N },
                        { crate::$module::$model::M },
                        { crate::$module::$model::A },
                    >());
                }
            )*
            None
        }
    };
}

registry! {
    navy_planar::NavyPlanar,
    navy_planar_pulley::NavyPlanarPulley,
    navy_3d::Navy3d,
    navy_3d_pulley::Navy3dPulley,
    gantry_3d::Gantry3d,
    tower_crane::TowerCrane,
    coupled_trolley::CoupledTrolley,
    double_pendulum::DoublePendulum,
    elastic_drive::ElasticDrive,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Names are unique and every entry is reachable by name with its sizes.
    #[test]
    fn every_entry_visits_with_its_sizes() {
        struct Sizes;
        impl Visit for Sizes {
            type Output = (usize, usize, usize, &'static str);
            fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
                (N, M, A, C::NAME)
            }
        }
        for (i, e) in CATALOG.iter().enumerate() {
            assert!(CATALOG[..i].iter().all(|o| o.name != e.name), "duplicate {}", e.name);
            assert_eq!(visit(e.name, Sizes), Some((e.n, e.m, e.a, e.name)));
        }
        assert_eq!(CATALOG.len(), 9);
    }
}
