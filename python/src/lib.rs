//! The extension module `clr._native` of the Python package `clr`: the clr-contact laws (this
//! file), whole models ([`models`]) and sweeps ([`sweep`]).
//!
//! The native classes evaluate the laws in loops over contiguous 1-D `float64` numpy arrays of
//! equal length (2-D `(n, 6)` for body states); the Python package `clr_contact` wraps them with
//! numpy broadcasting, scalars in and floats out. Laws are built with the same kinds, names and
//! parameter orders as the C API (`clr_contact_capi::spec`), and every invalid parameter or
//! non-finite input raises `clr_contact.ContactError` (a `ValueError`) with a message that says
//! what to change. Formulas, units and sources are those of `clr-contact` (SI units).

use clr_contact::body::BodyState;
use clr_contact::elastic::Material;
use clr_contact::restitution::effective_restitution;
use clr_contact::{DampingFactor, FrictionLaw, JournalBearing, NormalLaw, RevoluteClearance};
use clr_contact_capi::ffi::revolute_forces;
use clr_contact_capi::spec::{ElasticKind, FrictionKind, Kind};
use clr_contact_capi::CapiError;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

mod convert;
mod errors;
mod fmu;
mod inertia;
mod journal;
mod models;
mod sweep;

/// An invalid law parameter (field `parameters`): `clr.errors.ContactError`.
fn err(e: impl Into<CapiError>) -> PyErr {
    contact_error("parameters", &e.into().to_string())
}

/// `clr.errors.ContactError` at the argument or parameter `field`.
fn contact_error(field: &str, message: &str) -> PyErr {
    Python::attach(|py| errors::contact_error(py, field, message))
}

/// Borrow a 1-D array as a slice and check that every entry is finite.
fn finite_slice<'a>(name: &'static str, a: &'a PyReadonlyArray1<'_, f64>) -> PyResult<&'a [f64]> {
    let s = a
        .as_slice()
        .map_err(|_| contact_error(name, &format!("`{name}` must be a contiguous array")))?;
    if let Some((i, v)) = s.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(contact_error(
            &format!("{name}[{i}]"),
            &format!("element {i} of `{name}` is {v}; pass finite numbers"),
        ));
    }
    Ok(s)
}

fn same_length(lengths: &[(&'static str, usize)]) -> PyResult<usize> {
    let n = lengths[0].1;
    match lengths.iter().find(|(_, m)| *m != n) {
        Some((name, m)) => Err(contact_error(
            name,
            &format!(
                "`{name}` has {m} elements but `{}` has {n}; pass arrays of the same length",
                lengths[0].0
            ),
        )),
        None => Ok(n),
    }
}

/// A normal-force law F_N = F_e(δ)(1 + χ δ̇/δ̇⁻) (N, m, m/s).
#[pyclass(frozen, module = "clr_sim._native")]
struct NormalLawCore {
    law: NormalLaw,
}

#[pymethods]
impl NormalLawCore {
    /// Build from an elastic kind name, its parameters (SI), a damping-factor name and c_e.
    #[new]
    #[pyo3(signature = (elastic, params, damping, c_e, min_impact_velocity=None))]
    fn new(
        elastic: &str,
        params: Vec<f64>,
        damping: &str,
        c_e: f64,
        min_impact_velocity: Option<f64>,
    ) -> PyResult<Self> {
        let elastic = ElasticKind::from_name(elastic)
            .and_then(|k| k.build(&params))
            .map_err(err)?;
        let damping = DampingFactor::from_name(damping).map_err(err)?;
        let mut law = NormalLaw::new(elastic, damping, c_e).map_err(err)?;
        if let Some(v) = min_impact_velocity {
            law = law.with_min_impact_velocity(v).map_err(err)?;
        }
        Ok(Self { law })
    }

    /// The flap paper's journal–bearing laws by label ("Hertz", "LN", "Gonthier", "Bai",
    /// "Wang", "Modified"), for a given geometry and materials.
    #[staticmethod]
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (name, c_e, bearing_youngs_modulus, bearing_poisson_ratio,
        journal_youngs_modulus, journal_poisson_ratio, bearing_radius, journal_radius, length,
        min_impact_velocity=None))]
    fn preset(
        name: &str,
        c_e: f64,
        bearing_youngs_modulus: f64,
        bearing_poisson_ratio: f64,
        journal_youngs_modulus: f64,
        journal_poisson_ratio: f64,
        bearing_radius: f64,
        journal_radius: f64,
        length: f64,
        min_impact_velocity: Option<f64>,
    ) -> PyResult<Self> {
        let jb = JournalBearing {
            bearing: Material {
                youngs_modulus: bearing_youngs_modulus,
                poisson_ratio: bearing_poisson_ratio,
            },
            journal: Material {
                youngs_modulus: journal_youngs_modulus,
                poisson_ratio: journal_poisson_ratio,
            },
            r_bearing: bearing_radius,
            r_journal: journal_radius,
            length,
        };
        let mut law = NormalLaw::preset(name, &jb, c_e).map_err(err)?;
        if let Some(v) = min_impact_velocity {
            law = law.with_min_impact_velocity(v).map_err(err)?;
        }
        Ok(Self { law })
    }

    /// F_N (N) elementwise for equal-length arrays δ (m), δ̇ (m/s), δ̇⁻ (m/s).
    fn force<'py>(
        &self,
        py: Python<'py>,
        delta: PyReadonlyArray1<'py, f64>,
        delta_dot: PyReadonlyArray1<'py, f64>,
        delta_dot_minus: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let d = finite_slice("delta", &delta)?;
        let dd = finite_slice("delta_dot", &delta_dot)?;
        let ddm = finite_slice("delta_dot_minus", &delta_dot_minus)?;
        same_length(&[
            ("delta", d.len()),
            ("delta_dot", dd.len()),
            ("delta_dot_minus", ddm.len()),
        ])?;
        let out: Vec<f64> = d
            .iter()
            .zip(dd)
            .zip(ddm)
            .map(|((&d, &dd), &ddm)| self.law.force(d, dd, ddm))
            .collect();
        Ok(out.into_pyarray(py))
    }

    /// F_e(δ) (N) elementwise for δ (m).
    fn elastic_force<'py>(
        &self,
        py: Python<'py>,
        delta: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let d = finite_slice("delta", &delta)?;
        let out: Vec<f64> = d.iter().map(|&d| self.law.elastic_force(d)).collect();
        Ok(out.into_pyarray(py))
    }

    /// Damping factor χ (–).
    #[getter]
    fn chi(&self) -> f64 {
        self.law.chi()
    }

    /// Input coefficient of restitution c_e (–).
    #[getter]
    fn c_e(&self) -> f64 {
        self.law.c_e()
    }

    /// Name of the damping factor.
    #[getter]
    fn damping(&self) -> &'static str {
        self.law.damping().name()
    }

    /// Name of the elastic part.
    #[getter]
    fn elastic(&self) -> &'static str {
        self.law.elastic().name()
    }

    /// Floor of δ̇⁻ (m/s).
    #[getter]
    fn min_impact_velocity(&self) -> f64 {
        self.law.min_impact_velocity()
    }

    /// Restitution produced in a free impact (exact relation, contact-laws.md §1.3).
    #[getter]
    fn effective_restitution(&self) -> f64 {
        self.law.effective_restitution()
    }
}

/// A stateless friction law F_T = μ(v_T) F_N.
#[pyclass(frozen, module = "clr_sim._native")]
struct FrictionLawCore {
    law: FrictionLaw,
}

#[pymethods]
impl FrictionLawCore {
    /// Build from a friction kind name and its parameters.
    #[new]
    fn new(kind: &str, params: Vec<f64>) -> PyResult<Self> {
        let law = FrictionKind::from_name(kind)
            .and_then(|k| k.build(&params))
            .map_err(err)?;
        Ok(Self { law })
    }

    /// F_T (N) elementwise for equal-length arrays v_T (m/s) and F_N (N).
    fn force<'py>(
        &self,
        py: Python<'py>,
        v_t: PyReadonlyArray1<'py, f64>,
        f_n: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let v = finite_slice("v_t", &v_t)?;
        let f = finite_slice("f_n", &f_n)?;
        same_length(&[("v_t", v.len()), ("f_n", f.len())])?;
        let out: Vec<f64> = v
            .iter()
            .zip(f)
            .map(|(&v, &f)| self.law.force(v, f))
            .collect();
        Ok(out.into_pyarray(py))
    }

    /// Signed coefficient μ(v_T) (–) elementwise.
    fn coefficient<'py>(
        &self,
        py: Python<'py>,
        v_t: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let v = finite_slice("v_t", &v_t)?;
        let out: Vec<f64> = v.iter().map(|&v| self.law.signed_coefficient(v)).collect();
        Ok(out.into_pyarray(py))
    }

    /// Largest |μ| (–).
    #[getter]
    fn mu_max(&self) -> f64 {
        self.law.mu_max()
    }
}

/// Two float64 arrays (radial, tangential).
type ArrayPair<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// The oil film of a lubricated journal bearing (clr-contact `HydrodynamicBearing`).
#[pyclass(frozen, module = "clr_sim._native")]
struct FilmLawCore {
    bearing: clr_contact::lubrication::HydrodynamicBearing,
}

#[pymethods]
impl FilmLawCore {
    /// Bearing radius R, journal radius r, axial length L (m), viscosity μ (Pa·s) and the model
    /// `short` or `long`.
    #[new]
    fn new(
        bearing_radius: f64,
        journal_radius: f64,
        length: f64,
        viscosity: f64,
        model: &str,
    ) -> PyResult<Self> {
        use clr_contact::lubrication::BearingModel;
        let model = match model {
            "short" | "short_bearing" => BearingModel::ShortBearing,
            "long" | "long_bearing" => BearingModel::LongBearing,
            other => {
                return Err(contact_error(
                    "model",
                    &format!("unknown bearing model `{other}`; valid: short, long"),
                ))
            }
        };
        let bearing = clr_contact::lubrication::HydrodynamicBearing::new(
            bearing_radius,
            journal_radius,
            length,
            viscosity,
            model,
        )
        .map_err(err)?;
        Ok(Self { bearing })
    }

    /// Radial and tangential film force on the journal (N) elementwise for equal-length arrays
    /// ε ∈ [0, 1) (–), ε̇ (1/s), γ̇ (rad/s) and ω_i + ω_j (rad/s).
    fn force<'py>(
        &self,
        py: Python<'py>,
        eps: PyReadonlyArray1<'py, f64>,
        eps_dot: PyReadonlyArray1<'py, f64>,
        gamma_dot: PyReadonlyArray1<'py, f64>,
        omega_sum: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<ArrayPair<'py>> {
        let e = finite_slice("eps", &eps)?;
        let r = finite_slice("eps_dot", &eps_dot)?;
        let g = finite_slice("gamma_dot", &gamma_dot)?;
        let w = finite_slice("omega_sum", &omega_sum)?;
        let n = same_length(&[
            ("eps", e.len()),
            ("eps_dot", r.len()),
            ("gamma_dot", g.len()),
            ("omega_sum", w.len()),
        ])?;
        if let Some(i) = e.iter().position(|x| !(0.0..1.0).contains(x)) {
            return Err(contact_error(
                &format!("eps[{i}]"),
                &format!(
                    "ε = {} must be in [0, 1): the journal touches the bearing at ε = 1",
                    e[i]
                ),
            ));
        }
        let (mut fr, mut ft) = (Vec::with_capacity(n), Vec::with_capacity(n));
        for k in 0..n {
            let f = self.bearing.force(e[k], r[k], g[k], w[k]);
            fr.push(f.radial);
            ft.push(f.tangential);
        }
        Ok((fr.into_pyarray(py), ft.into_pyarray(py)))
    }
}

/// A planar revolute clearance joint (journal in bearing).
#[pyclass(frozen, module = "clr_sim._native")]
struct RevoluteJointCore {
    joint: RevoluteClearance,
}

fn states(name: &'static str, a: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<BodyState>> {
    let view = a.as_array();
    if view.ncols() != 6 {
        return Err(contact_error(
            name,
            &format!(
                "`{name}` must have shape (n, 6) = (x, y, theta, vx, vy, omega), got {:?}",
                view.shape()
            ),
        ));
    }
    view.rows()
        .into_iter()
        .enumerate()
        .map(|(i, r)| {
            if let Some(v) = r.iter().find(|v| !v.is_finite()) {
                return Err(contact_error(
                    &format!("{name}[{i}]"),
                    &format!("row {i} of `{name}` contains {v}; pass finite states"),
                ));
            }
            Ok(BodyState::new(
                [r[0], r[1]].into(),
                r[2],
                [r[3], r[4]].into(),
                r[5],
            ))
        })
        .collect()
}

#[pymethods]
impl RevoluteJointCore {
    /// Bearing radius R_i and journal radius R_j (m), local joint centres on each body (m).
    #[new]
    fn new(
        bearing_radius: f64,
        journal_radius: f64,
        bearing_centre: (f64, f64),
        journal_centre: (f64, f64),
    ) -> PyResult<Self> {
        let joint = RevoluteClearance::new(
            bearing_radius,
            journal_radius,
            [bearing_centre.0, bearing_centre.1].into(),
            [journal_centre.0, journal_centre.1].into(),
        )
        .map_err(err)?;
        Ok(Self { joint })
    }

    /// Radial clearance c = R_i − R_j (m).
    #[getter]
    fn clearance(&self) -> f64 {
        self.joint.clearance()
    }

    /// Forces for n states: `bearing`, `journal` of shape (n, 6), `impact_velocity` of length n.
    /// Returns a dict of arrays (see the Python wrapper for the keys).
    fn forces<'py>(
        &self,
        py: Python<'py>,
        normal: &NormalLawCore,
        friction: Option<&FrictionLawCore>,
        bearing: PyReadonlyArray2<'py, f64>,
        journal: PyReadonlyArray2<'py, f64>,
        impact_velocity: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let bi = states("bearing", &bearing)?;
        let bj = states("journal", &journal)?;
        let v0 = finite_slice("impact_velocity", &impact_velocity)?;
        let n = same_length(&[
            ("bearing", bi.len()),
            ("journal", bj.len()),
            ("impact_velocity", v0.len()),
        ])?;
        let mut scalars = [const { Vec::new() }; 5];
        let (mut nrm, mut fi, mut fj) = (
            Vec::with_capacity(2 * n),
            Vec::with_capacity(3 * n),
            Vec::with_capacity(3 * n),
        );
        for k in 0..n {
            let r = revolute_forces(
                &self.joint,
                &normal.law,
                friction.map(|f| &f.law),
                &bi[k],
                &bj[k],
                v0[k],
            );
            for (col, v) in scalars.iter_mut().zip([
                r.penetration,
                r.normal_velocity,
                r.tangential_velocity,
                r.normal_force,
                r.tangential_force,
            ]) {
                col.push(v);
            }
            nrm.extend([r.normal_x, r.normal_y]);
            fi.extend([r.bearing.fx, r.bearing.fy, r.bearing.moment]);
            fj.extend([r.journal.fx, r.journal.fy, r.journal.moment]);
        }
        let dict = PyDict::new(py);
        let names = [
            "penetration",
            "normal_velocity",
            "tangential_velocity",
            "normal_force",
            "tangential_force",
        ];
        for (name, col) in names.into_iter().zip(scalars) {
            dict.set_item(name, col.into_pyarray(py))?;
        }
        dict.set_item("normal", matrix(py, n, 2, nrm)?)?;
        dict.set_item("bearing", matrix(py, n, 3, fi)?)?;
        dict.set_item("journal", matrix(py, n, 3, fj)?)?;
        Ok(dict)
    }
}

fn matrix(py: Python<'_>, n: usize, m: usize, v: Vec<f64>) -> PyResult<Bound<'_, PyArray2<f64>>> {
    let a = Array2::from_shape_vec((n, m), v).map_err(|e| {
        pyo3::exceptions::PyRuntimeError::new_err(format!("internal shape error: {e}; report this"))
    })?;
    Ok(a.into_pyarray(py))
}

/// χ(c_e) (–) of the damping factor `name`, elementwise over c_e.
#[pyfunction]
fn damping_chi<'py>(
    py: Python<'py>,
    name: &str,
    c_e: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let d = DampingFactor::from_name(name).map_err(err)?;
    let c = finite_slice("c_e", &c_e)?;
    let out = c
        .iter()
        .map(|&c| d.chi(c).map_err(err))
        .collect::<PyResult<Vec<f64>>>()?;
    Ok(out.into_pyarray(py))
}

/// Restitution e_eff(χ) (–) of a multiplicative law, elementwise over χ ≥ 0.
#[pyfunction(name = "effective_restitution")]
fn effective_restitution_py<'py>(
    py: Python<'py>,
    chi: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let c = finite_slice("chi", &chi)?;
    let out = c
        .iter()
        .map(|&x| effective_restitution(x).map_err(err))
        .collect::<PyResult<Vec<f64>>>()?;
    Ok(out.into_pyarray(py))
}

/// Names of the damping factors.
#[pyfunction]
fn damping_names() -> Vec<&'static str> {
    DampingFactor::ALL.iter().map(|d| d.name()).collect()
}

/// (name, parameter names) of every elastic kind.
#[pyfunction]
fn elastic_kinds() -> Vec<(&'static str, Vec<&'static str>)> {
    kinds::<ElasticKind>()
}

/// (name, parameter names) of every friction kind.
#[pyfunction]
fn friction_kinds() -> Vec<(&'static str, Vec<&'static str>)> {
    kinds::<FrictionKind>()
}

fn kinds<K: Kind>() -> Vec<(&'static str, Vec<&'static str>)> {
    K::ALL
        .iter()
        .map(|k| (k.name(), k.parameters().to_vec()))
        .collect()
}

/// Labels accepted by `NormalLaw.preset`.
#[pyfunction]
fn preset_names() -> Vec<&'static str> {
    clr_contact::normal::FLAP_PRESETS.to_vec()
}

#[pymodule]
#[pyo3(name = "_native")]
fn native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<NormalLawCore>()?;
    m.add_class::<FrictionLawCore>()?;
    m.add_class::<RevoluteJointCore>()?;
    m.add_class::<journal::JournalJointCore>()?;
    m.add_class::<FilmLawCore>()?;
    m.add_function(wrap_pyfunction!(damping_chi, m)?)?;
    m.add_function(wrap_pyfunction!(effective_restitution_py, m)?)?;
    m.add_function(wrap_pyfunction!(damping_names, m)?)?;
    m.add_function(wrap_pyfunction!(elastic_kinds, m)?)?;
    m.add_function(wrap_pyfunction!(friction_kinds, m)?)?;
    m.add_function(wrap_pyfunction!(preset_names, m)?)?;
    m.add_class::<models::JobCore>()?;
    m.add_class::<sweep::SweepRun>()?;
    m.add_function(wrap_pyfunction!(models::list_models, m)?)?;
    m.add_function(wrap_pyfunction!(models::list_studies, m)?)?;
    m.add_function(wrap_pyfunction!(models::run_study, m)?)?;
    m.add_function(wrap_pyfunction!(models::element_kinds, m)?)?;
    m.add_function(wrap_pyfunction!(models::kind_fields, m)?)?;
    m.add_function(wrap_pyfunction!(fmu::fmu_export, m)?)?;
    inertia::register(m)?;
    Ok(())
}
