//! How a crane is drawn (`snapshots.svg`): its fixed points and, for a state
//! `q`, the boom, the ropes, the main pulley and the load.

/// A point in space; planar cranes use `y = 0`.
pub type P3 = [f64; 3];

/// The crane in one state.
#[derive(Debug, Clone, PartialEq)]
pub struct Pose {
    /// The boom as a polyline (foot to tip).
    pub boom: Vec<P3>,
    /// Rope segments.
    pub ropes: Vec<[P3; 2]>,
    /// Main pulley (or trolley) B.
    pub pulley: P3,
    /// Load C.
    pub load: P3,
}

/// The crane's pose as a function of the coordinates `q`.
pub type PoseFn = Box<dyn Fn(&[f64]) -> Pose>;

/// How a model is drawn.
pub struct Drawing {
    /// 3D (cabinet projection) or planar (x, z).
    pub spatial: bool,
    /// Labelled points that do not move: (label, point).
    pub fixed: Vec<(&'static str, P3)>,
    /// The crane in state `q`.
    pub pose: PoseFn,
    /// What the ropes are, for the legend.
    pub ropes: &'static str,
}

/// `p` scaled by `f`.
pub fn scale(p: P3, f: f64) -> P3 {
    [p[0] * f, p[1] * f, p[2] * f]
}
