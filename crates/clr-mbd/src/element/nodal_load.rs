//! Nodal load on a ground-fixed beam: F_x(t), F_y(t) (N) and M(t) (N·m) in global axes at a
//! node; components on constrained DOF are taken by the supports.

use serde::{Deserialize, Serialize};

use super::applied_force::zero;
use super::{Compiler, Element};
use crate::error::MbdError;
use crate::flexible::NodalLoadFn;
use crate::input::TimeFnSlot;
use crate::timefn::TimeFn;

/// `type = "nodal_load"`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodalLoad {
    /// Unique name.
    pub name: String,
    /// The beam (`[[beam]]`).
    pub beam: String,
    /// Node index.
    pub node: usize,
    /// x force, N (default 0).
    #[serde(default = "zero")]
    pub fx: TimeFn,
    /// y force, N (default 0).
    #[serde(default = "zero")]
    pub fy: TimeFn,
    /// Moment, N·m (default 0).
    #[serde(default = "zero")]
    pub moment: TimeFn,
}

/// Attach `f` to node `node` of ground-fixed beam `beam`.
pub(crate) fn attach(
    c: &mut Compiler,
    name: &str,
    beam: &str,
    node: usize,
    f: NodalLoadFn,
) -> Result<(), MbdError> {
    let Some(fb) = c.beams.iter_mut().find(|b| b.name == beam) else {
        let known: Vec<&str> = c.beams.iter().map(|b| b.name.as_str()).collect();
        return Err(MbdError::UnknownBody {
            item: format!("{name}.beam"),
            body: beam.to_string(),
            known: known.join(", "),
        });
    };
    if 3 * node + 2 >= fb.n_dof_full {
        return Err(MbdError::InvalidParameter {
            item: name.to_string(),
            what: "node index",
            value: node as f64,
            requirement: "must be a node of the beam model",
        });
    }
    let idx = [0, 1, 2].map(|c| fb.free.iter().position(|&d| d == 3 * node + c));
    fb.loads.push((idx, f));
    Ok(())
}

impl Element for NodalLoad {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        for (f, k) in [(&self.fx, "fx"), (&self.fy, "fy"), (&self.moment, "moment")] {
            f.validate(&format!("{}.{k}", self.name))?;
        }
        let [fx, fy, m] = [self.fx.clone(), self.fy.clone(), self.moment.clone()];
        attach(
            c,
            &self.name,
            &self.beam,
            self.node,
            std::sync::Arc::new(move |t| [fx.eval(t)[0], fy.eval(t)[0], m.eval(t)[0]]),
        )
    }
    fn time_fns(&mut self) -> Vec<TimeFnSlot<'_>> {
        vec![
            TimeFnSlot {
                field: "fx",
                unit: "N",
                motion: false,
                f: &mut self.fx,
            },
            TimeFnSlot {
                field: "fy",
                unit: "N",
                motion: false,
                f: &mut self.fy,
            },
            TimeFnSlot {
                field: "moment",
                unit: "N·m",
                motion: false,
                f: &mut self.moment,
            },
        ]
    }
}
