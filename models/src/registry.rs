//! Which cranes a tool knows, by name: a [`Registry`] lists them
//! ([`Registry::entries`]) and runs code on one of them by name
//! ([`Registry::visit`]), with its sizes `n, m, a` taken from the generated
//! model (no sizes written by hand). [`BuiltIn`] holds the built-in cranes
//! ([`CATALOG`], [`visit`]); a user's crate makes its own with the
//! [`registry!`](crate::registry!) macro, and `(Mine, BuiltIn)` is both.
//!
//! Adding a built-in crane: a module with its declaration and a
//! [`Crane`] description, and one line in the `built_in!`
//! call at the end of this file.
//!
//! ```
//! use crane_models::registry::{self, BuiltIn, Registry, Visit};
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
//! assert_eq!(BuiltIn.visit("navy-planar", Coordinates), Some(7));
//! assert_eq!(registry::visit("no-such-crane", Coordinates), None);
//! ```

use crane_runtime::CraneModel;

use crate::crane::Crane;

/// A crane of a registry, as `crane list` shows it.
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
    /// The entry of crane `C` (`Entry::of::<C, _, _, _>()` infers the sizes).
    pub const fn of<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>() -> Self {
        Entry {
            name: C::NAME,
            description: C::DESCRIPTION,
            n: N,
            m: M,
            a: A,
            reference: C::HAS_REFERENCE,
            minimal: <C::Model as CraneModel<N, M, A>>::HAS_MINIMAL_MAP,
        }
    }

    /// Degrees of freedom `f = n - m`.
    pub fn dof(&self) -> usize {
        self.n - self.m
    }
}

/// Code to run on one crane, whichever: [`Registry::visit`] calls
/// `visit::<C, N, M, A>()` with the crane's description and sizes.
pub trait Visit {
    /// What the visit returns.
    type Output;
    /// Run on crane `C` with `n = N`, `m = M`, `a = A`.
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output;
}

/// The cranes a tool knows: the command line, the FMU library and the
/// tests reach a crane by name through one of these. Made by
/// [`registry!`](crate::registry!) for a user's cranes; [`BuiltIn`] for the
/// built-in ones; a pair `(R1, R2)` knows both (a name of `R1` first).
pub trait Registry: Sync {
    /// The cranes, in the order `list` shows them.
    fn entries(&self) -> Vec<Entry>;
    /// Run `visitor` on the crane called `name`; `None` if there is none.
    fn visit<V: Visit>(&self, name: &str, visitor: V) -> Option<V::Output>;
}

/// The built-in cranes ([`CATALOG`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BuiltIn;

impl Registry for BuiltIn {
    fn entries(&self) -> Vec<Entry> {
        CATALOG.to_vec()
    }
    fn visit<V: Visit>(&self, name: &str, visitor: V) -> Option<V::Output> {
        visit(name, visitor)
    }
}

impl<R1: Registry, R2: Registry> Registry for (R1, R2) {
    fn entries(&self) -> Vec<Entry> {
        let mut entries = self.0.entries();
        for e in self.1.entries() {
            if entries.iter().all(|o| o.name != e.name) {
                entries.push(e);
            }
        }
        entries
    }
    fn visit<V: Visit>(&self, name: &str, visitor: V) -> Option<V::Output> {
        if self.0.entries().iter().any(|e| e.name == name) {
            self.0.visit(name, visitor)
        } else {
            self.1.visit(name, visitor)
        }
    }
}

/// `visitor.visit::<C, N, M, A>()` with the sizes inferred from `C`'s one
/// [`Crane`] implementation (for [`registry!`](crate::registry!)).
#[doc(hidden)]
pub fn visit_crane<C: Crane<N, M, A>, V: Visit, const N: usize, const M: usize, const A: usize>(
    visitor: V,
) -> V::Output {
    visitor.visit::<C, N, M, A>()
}

/// A user's registry: a unit struct that implements [`Registry`] for the
/// cranes listed (each a type implementing [`Crane`], the sizes inferred).
///
/// ```
/// use crane_models::registry::{BuiltIn, Registry};
/// use crane_models::{gantry_3d, navy_planar};
///
/// crane_models::registry! {
///     /// Two of the built-in cranes, as a user's crate would list its own.
///     pub struct Two { navy_planar::Description, gantry_3d::Description }
/// }
/// let names: Vec<_> = Two.entries().iter().map(|e| e.name).collect();
/// assert_eq!(names, ["navy-planar", "gantry-3d"]);
/// // with the built-ins after them, each name once
/// assert_eq!((Two, BuiltIn).entries().len(), BuiltIn.entries().len());
/// ```
#[macro_export]
macro_rules! registry {
    ($(#[$meta:meta])* $vis:vis struct $name:ident { $($crane:ty),+ $(,)? }) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
        $vis struct $name;

        impl $crate::registry::Registry for $name {
            fn entries(&self) -> ::std::vec::Vec<$crate::registry::Entry> {
                ::std::vec![$($crate::registry::Entry::of::<$crane, _, _, _>()),+]
            }
            fn visit<V: $crate::registry::Visit>(&self, name: &str, visitor: V) -> ::core::option::Option<V::Output> {
                $(
                    if name == $crate::registry::Entry::of::<$crane, _, _, _>().name {
                        return ::core::option::Option::Some($crate::registry::visit_crane::<$crane, V, _, _, _>(visitor));
                    }
                )+
                ::core::option::Option::None
            }
        }
    };
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

macro_rules! built_in {
    ($($module:ident :: $model:ident),* $(,)?) => {
        /// The built-in cranes, in the order `crane list` shows them.
        pub const CATALOG: &[Entry] = &[$(
            Entry::of::<
                crate::$module::Description,
                { crate::$module::$model::N },
                { crate::$module::$model::M },
                { crate::$module::$model::A },
            >(),
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

built_in! {
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

    crate::registry! {
        /// Two built-in cranes, in the other order, as a user's registry.
        struct Two { crate::tower_crane::Description, crate::navy_planar::Description }
    }

    /// A user's registry lists its cranes in its order and visits them by
    /// name with their sizes; a pair asks the first registry first and
    /// lists each name once.
    #[test]
    fn a_user_registry_and_a_pair_visit_by_name() {
        struct Sizes;
        impl Visit for Sizes {
            type Output = (usize, usize, usize, &'static str);
            fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
                (N, M, A, C::NAME)
            }
        }
        let names: Vec<_> = Two.entries().iter().map(|e| e.name).collect();
        assert_eq!(names, ["tower-crane", "navy-planar"]);
        assert_eq!(Two.visit("navy-planar", Sizes), Some((7, 3, 2, "navy-planar")));
        assert_eq!(Two.visit("gantry-3d", Sizes), None);
        let both = (Two, BuiltIn);
        let names: Vec<_> = both.entries().iter().map(|e| e.name).collect();
        assert_eq!(names.len(), CATALOG.len());
        assert_eq!(&names[..2], ["tower-crane", "navy-planar"]);
        assert_eq!(both.visit("gantry-3d", Sizes).map(|s| s.3), Some("gantry-3d"));
        assert_eq!(both.visit("no-such-crane", Sizes), None);
        assert_eq!(Entry::of::<crate::navy_planar::Description, _, _, _>(), CATALOG[0]);
    }
}
