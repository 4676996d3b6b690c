//! `JournalJointCore`: the spatial journal-in-bearing clearance joint of clr-contact
//! (`clr_contact::journal`, docs/contact.md) evaluated over n states, for the Python wrapper
//! `clr_sim.JournalJoint`. The evaluation is the C ABI's (`clr_contact_capi::journal`).

use clr_contact::journal::{JournalClearance, JournalFriction, JournalLaws};
use clr_contact_capi::journal::{journal_forces, ClrJournalState};
use numpy::{IntoPyArray, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::{contact_error, err, matrix, FrictionLawCore, NormalLawCore};

/// Columns of a state row: bearing centre, axis, velocity, angular velocity, then the same four
/// for the journal (world frame, SI).
const STATE_COLUMNS: usize = 24;

/// A spatial revolute or cylindrical clearance joint (journal in bearing), validated.
#[pyclass(frozen, module = "clr_sim._native")]
pub(crate) struct JournalJointCore {
    joint: JournalClearance,
}

#[pymethods]
impl JournalJointCore {
    /// Bore radius and length, journal radius and length (m); with `axial_clearance` (m) a
    /// revolute joint with thrust faces of radius `thrust_radius` (m; None: the journal's),
    /// without it a cylindrical joint.
    #[new]
    #[pyo3(signature = (bearing_radius, bearing_length, journal_radius, journal_length, axial_clearance=None, thrust_radius=None))]
    fn new(
        bearing_radius: f64,
        bearing_length: f64,
        journal_radius: f64,
        journal_length: f64,
        axial_clearance: Option<f64>,
        thrust_radius: Option<f64>,
    ) -> PyResult<Self> {
        let joint = match axial_clearance {
            Some(ca) => JournalClearance::revolute(
                bearing_radius,
                bearing_length,
                journal_radius,
                journal_length,
                ca,
                thrust_radius,
            ),
            None if thrust_radius.is_some() => {
                return Err(contact_error(
                    "thrust_radius",
                    "a thrust radius needs thrust faces: give `axial_clearance` too (a joint \
                     without it is cylindrical)",
                ))
            }
            None => JournalClearance::cylindrical(
                bearing_radius,
                bearing_length,
                journal_radius,
                journal_length,
            ),
        }
        .map_err(err)?;
        Ok(Self { joint })
    }

    /// Radial clearance R_b − R_j (m).
    #[getter]
    fn clearance(&self) -> f64 {
        self.joint.clearance()
    }

    /// Forces for n states (`states` of shape (n, 24), `impact_velocities` (n, 4)); returns a
    /// dict of arrays (see the Python wrapper for the keys).
    fn forces<'py>(
        &self,
        py: Python<'py>,
        radial: &NormalLawCore,
        thrust: Option<&NormalLawCore>,
        friction: Option<&FrictionLawCore>,
        states: PyReadonlyArray2<'py, f64>,
        impact_velocities: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let friction = friction.map_or(JournalFriction::None, |f| JournalFriction::Law(f.law));
        let laws = JournalLaws::new(radial.law, thrust.map_or(radial.law, |t| t.law), friction)
            .map_err(err)?;
        let (s, v) = (states.as_array(), impact_velocities.as_array());
        if s.ncols() != STATE_COLUMNS || v.ncols() != 4 || s.nrows() != v.nrows() {
            return Err(contact_error(
                "states",
                &format!(
                    "`states` must have shape (n, 24) and `impact_velocities` (n, 4); got {:?} \
                     and {:?}",
                    s.shape(),
                    v.shape()
                ),
            ));
        }
        let n = s.nrows();
        let mut vectors = [const { Vec::new() }; 3];
        let mut groups = [const { Vec::new() }; 3];
        let mut scalars = [const { Vec::new() }; 3];
        for k in 0..n {
            let row = s.row(k);
            if let Some(x) = row.iter().chain(v.row(k).iter()).find(|x| !x.is_finite()) {
                return Err(contact_error(
                    &format!("states[{k}]"),
                    &format!("row {k} contains {x}; pass finite states and impact velocities"),
                ));
            }
            let at = |i: usize| [row[3 * i], row[3 * i + 1], row[3 * i + 2]];
            let state = ClrJournalState {
                bearing_centre: at(0),
                bearing_axis: at(1),
                bearing_velocity: at(2),
                bearing_angular_velocity: at(3),
                journal_centre: at(4),
                journal_axis: at(5),
                journal_velocity: at(6),
                journal_angular_velocity: at(7),
            };
            let v0 = [v[(k, 0)], v[(k, 1)], v[(k, 2)], v[(k, 3)]];
            let f = journal_forces(&self.joint, &laws, &state, &v0).map_err(err)?;
            for (col, x) in vectors
                .iter_mut()
                .zip([f.force, f.journal_moment, f.bearing_moment])
            {
                col.extend(x);
            }
            for (col, x) in groups
                .iter_mut()
                .zip([f.penetration, f.rate, f.normal_force])
            {
                col.extend(x);
            }
            for (col, x) in scalars
                .iter_mut()
                .zip([f.tilt, f.dissipated, f.elastic_energy])
            {
                col.push(x);
            }
        }
        let dict = PyDict::new(py);
        for (name, col) in ["force", "journal_moment", "bearing_moment"]
            .into_iter()
            .zip(vectors)
        {
            dict.set_item(name, matrix(py, n, 3, col)?)?;
        }
        for (name, col) in ["penetration", "rate", "normal_force"]
            .into_iter()
            .zip(groups)
        {
            dict.set_item(name, matrix(py, n, 4, col)?)?;
        }
        for (name, col) in ["tilt", "dissipated", "elastic_energy"]
            .into_iter()
            .zip(scalars)
        {
            dict.set_item(name, col.into_pyarray(py))?;
        }
        Ok(dict)
    }
}
