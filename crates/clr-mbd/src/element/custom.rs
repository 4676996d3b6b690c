//! User-defined loads as Rust closures: the explicit opt-in for what the data elements cannot
//! say (state-dependent forces). A description holding one compiles and runs but cannot be
//! written to a model file.

use std::fmt;

use super::{ground_load, Anchor, Compiler, Element};
use crate::error::MbdError;
use crate::runtime::{ForceEl, GROUND_ID};

/// A nodal load on a beam: `f(t) -> [F_x (N), F_y (N), M (N·m)]`, global axes.
pub use crate::flexible::NodalLoadFn as NodalFn;
pub use crate::runtime::{ForceFn, PairTorqueFn, TorqueFn};

/// What a custom load acts on.
#[derive(Clone)]
pub enum CustomLoad {
    /// A force at an anchor.
    Force(Anchor, ForceFn),
    /// A torque on a body.
    Torque(String, TorqueFn),
    /// A torque between two bodies (i, j).
    PairTorque(String, String, PairTorqueFn),
    /// A nodal load on a ground-fixed beam (beam, node).
    Nodal(String, usize, NodalFn),
}

/// A user-defined load (closure).
#[derive(Clone)]
pub struct CustomForce {
    /// Unique name.
    pub name: String,
    /// The load.
    pub load: CustomLoad,
}

impl fmt::Debug for CustomForce {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "CustomForce({}, <closure>)", self.name)
    }
}

impl PartialEq for CustomForce {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

impl Element for CustomForce {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let name = self.name.clone();
        let el = match &self.load {
            CustomLoad::Force(at, f) => {
                let (i, si) = c.anchor(&name, "at", at)?;
                if i == GROUND_ID {
                    return Err(ground_load(&name));
                }
                let f = f.clone();
                ForceEl::Force {
                    name,
                    i,
                    si,
                    state_free: false,
                    f,
                }
            }
            CustomLoad::Torque(body, f) => {
                let i = c.body(&name, "body", body)?;
                if i == GROUND_ID {
                    return Err(ground_load(&name));
                }
                let f = f.clone();
                ForceEl::Torque {
                    name,
                    i,
                    state_free: false,
                    f,
                }
            }
            CustomLoad::PairTorque(bi, bj, f) => {
                let i = c.body(&name, "body_i", bi)?;
                let j = c.body(&name, "body_j", bj)?;
                c.distinct(&name, i, j)?;
                let f = f.clone();
                ForceEl::PairTorque {
                    name,
                    i,
                    j,
                    state_free: false,
                    f,
                }
            }
            CustomLoad::Nodal(beam, node, f) => {
                return super::nodal_load::attach(c, &name, beam, *node, f.clone());
            }
        };
        c.forces.push(el);
        Ok(())
    }
    fn anchors(&self) -> Vec<&Anchor> {
        match &self.load {
            CustomLoad::Force(a, _) => vec![a],
            _ => Vec::new(),
        }
    }
    fn has_closure(&self) -> bool {
        true
    }
}
