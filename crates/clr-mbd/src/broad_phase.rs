//! The model's broad phase over its shape pairs: every pair's two bounding circles in one compact
//! array, tested in a tight loop before the elements are visited, so that a pair far apart costs
//! a few loads and a square root per evaluation (the same test [`ShapePair`](crate::shape_pair::ShapePair) makes first, so
//! the results do not change). It sits above the assembly's contact elements
//! ([`crate::clearance`]) and reads the pairs among them.

use nalgebra::Vector2;

use crate::clearance::{Clearance, ClearanceKind};
use crate::runtime::{frame_position, Frame};

/// The model's broad phase over its shape pairs (module docs).
#[derive(Default)]
pub(crate) struct BroadPhase {
    pairs: Vec<Circles>,
    /// Per clearance element: true when it is a shape pair beyond its prediction distance at
    /// the state of the last [`BroadPhase::update`].
    pub(crate) apart: Vec<bool>,
}

/// The bounding circles of one pair (those of `Side::circle`).
struct Circles {
    clearance: usize,
    frames: [usize; 2],
    fixed: [Option<Vector2<f64>>; 2],
    radius: [f64; 2],
    margin: f64,
}

impl BroadPhase {
    /// The shape pairs among `clearances`.
    pub(crate) fn new(clearances: &[Clearance]) -> Self {
        let pairs = clearances
            .iter()
            .enumerate()
            .filter_map(|(k, c)| match &c.kind {
                ClearanceKind::Shapes(p) => Some(Circles {
                    clearance: k,
                    frames: [c.i, c.j],
                    fixed: [p.a.fixed, p.b.fixed],
                    radius: [
                        p.a.fixed.map_or(p.a.reach, |_| p.a.radius),
                        p.b.fixed.map_or(p.b.reach, |_| p.b.radius),
                    ],
                    margin: p.settings.prediction,
                }),
                _ => None,
            })
            .collect();
        Self {
            pairs,
            apart: vec![false; clearances.len()],
        }
    }

    /// Test every pair at the coordinates `q`.
    pub(crate) fn update(&mut self, frames: &[Frame], q: &[f64]) {
        for c in &self.pairs {
            let centre =
                |s: usize| c.fixed[s].unwrap_or_else(|| frame_position(frames, c.frames[s], q));
            let gap = (centre(1) - centre(0)).norm() - c.radius[0] - c.radius[1];
            self.apart[c.clearance] = gap > c.margin;
        }
    }
}
