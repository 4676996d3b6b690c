//! The data of LuGre friction in clearance joints (module docs of [`crate::lugre`]): the law of
//! a joint and where its bristle states sit, and the bristle states of a model. Below the
//! clearance joints and the assembly, which hold them.

use clr_contact::{FrictionLaw, LuGre};

use crate::desc::laws::ContactFriction;

/// The LuGre law of a clearance joint and where its bristle states sit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LuGreContact {
    pub(crate) law: LuGre,
    /// Index of the element's first bristle state in [`Bristles::z`] (set by
    /// `crate::lugre::assign_bristles`).
    pub(crate) first: usize,
}

impl LuGreContact {
    /// The stateless law and the LuGre part of a clearance joint's friction: a stateless law
    /// alone, or no stateless friction plus the LuGre law.
    pub(crate) fn split(f: ContactFriction) -> (FrictionLaw, Option<Self>) {
        match f {
            ContactFriction::Static(l) => (l, None),
            ContactFriction::LuGre(law) => (
                FrictionLaw::coulomb(0.0, 1.0).expect("μ = 0 with v_reg = 1 m/s is valid"),
                Some(Self { law, first: 0 }),
            ),
        }
    }
}

/// Bristle states of every LuGre contact point of a model and their rates at the last
/// evaluation.
#[derive(Debug, Clone, Default)]
pub(crate) struct Bristles {
    /// Deflections z (m), loaded from the state before each evaluation.
    pub(crate) z: Vec<f64>,
    /// Rates ż (m/s) of the last evaluation (0 at open points).
    pub(crate) z_dot: Vec<f64>,
    /// Per clearance element: its `lugre_z` output (the F_N-weighted mean deflection of its
    /// loaded points, so that σ₀·mean·ΣF_N = Σσ₀z_kF_N,k; the plain mean when none is loaded), m.
    pub(crate) mean: Vec<f64>,
}

impl Bristles {
    /// Number of bristle states.
    pub(crate) fn len(&self) -> usize {
        self.z.len()
    }
}
