//! Ground-fixed flexible beams: the free nodal coordinates of a clr-beam model appended to q.
//!
//! The beam's supports (clamps, pins, rollers set on the `clr_beam::BeamModel`) fix it to the
//! ground; its free DOF u (nodal displacements and rotations, small-deformation
//! Euler–Bernoulli frame elements) enter q after the rigid-body coordinates with the constant
//! mass matrix M_ff, stiffness K_ff and Rayleigh damping C_ff of clr-beam restricted to the free
//! DOF: M_ff ü = −K_ff u − C_ff u̇ + f(t).

use clr_beam::BeamModel;

use crate::error::MbdError;

/// A nodal load on a beam: `f(t) -> [F_x (N), F_y (N), M (N·m)]` at a node, global axes.
pub type NodalLoadFn = std::sync::Arc<dyn Fn(f64) -> [f64; 3] + Send + Sync>;

pub(crate) struct FlexBeam {
    pub(crate) name: String,
    /// Index of the first free DOF in q.
    pub(crate) offset: usize,
    /// Full DOF index of each free DOF.
    pub(crate) free: Vec<usize>,
    /// Number of DOF of the full beam model (3 per node).
    pub(crate) n_dof_full: usize,
    /// Undeformed node positions, m.
    pub(crate) nodes: Vec<[f64; 2]>,
    /// For each full DOF, its index among the free DOF.
    pub(crate) free_index: Vec<Option<usize>>,
    /// The path through all elements (for surface queries), when the model has one.
    pub(crate) path: Option<clr_beam::Path>,
    /// Free-DOF matrices, row-major nf × nf.
    pub(crate) m: Vec<f64>,
    pub(crate) k: Vec<f64>,
    pub(crate) c: Vec<f64>,
    /// Nodal loads: the free index of the node's three DOF (`None` when constrained) and f(t).
    pub(crate) loads: Vec<([Option<usize>; 3], NodalLoadFn)>,
}

impl FlexBeam {
    pub(crate) fn new(name: &str, model: &BeamModel) -> Result<Self, MbdError> {
        let err = |e: clr_beam::BeamError| MbdError::Beam {
            item: name.to_string(),
            message: e.to_string(),
        };
        let map = model.dof_map().map_err(err)?;
        let (m, k, c) = (
            model.mass_dense().map_err(err)?,
            model.stiffness_dense().map_err(err)?,
            model.damping_dense().map_err(err)?,
        );
        let nf = map.free.len();
        let mut out = FlexBeam {
            name: name.to_string(),
            offset: 0,
            free: map.free.clone(),
            n_dof_full: model.n_dof(),
            nodes: model.nodes().to_vec(),
            free_index: map.free_index.clone(),
            path: model.path().ok(),
            m: vec![0.0; nf * nf],
            k: vec![0.0; nf * nf],
            c: vec![0.0; nf * nf],
            loads: Vec::new(),
        };
        for (a, &da) in map.free.iter().enumerate() {
            for (b, &db) in map.free.iter().enumerate() {
                out.m[a * nf + b] = m[(da, db)];
                out.k[a * nf + b] = k[(da, db)];
                out.c[a * nf + b] = c[(da, db)];
            }
        }
        Ok(out)
    }

    /// Number of free DOF.
    pub(crate) fn n_free(&self) -> usize {
        self.free.len()
    }

    /// Column names of the free DOF: `beam.n<node>.<u|v|theta>`.
    pub(crate) fn dof_names(&self) -> Vec<String> {
        self.free
            .iter()
            .map(|d| format!("{}.n{}.{}", self.name, d / 3, ["u", "v", "theta"][d % 3]))
            .collect()
    }

    /// Add −K u − C u̇ + f(t) to `qf` (free ordering at `offset`) and return the dissipated power
    /// u̇ᵀ C u̇ (W).
    pub(crate) fn forces(&self, t: f64, q: &[f64], qd: &[f64], qf: &mut [f64]) -> f64 {
        let (o, nf) = (self.offset, self.n_free());
        let (u, ud) = (&q[o..o + nf], &qd[o..o + nf]);
        let mut p = 0.0;
        for a in 0..nf {
            let (kr, cr) = (&self.k[a * nf..(a + 1) * nf], &self.c[a * nf..(a + 1) * nf]);
            let mut ku = 0.0;
            let mut cu = 0.0;
            for b in 0..nf {
                ku += kr[b] * u[b];
                cu += cr[b] * ud[b];
            }
            qf[o + a] -= ku + cu;
            p += ud[a] * cu;
        }
        for (idx, f) in &self.loads {
            let v = f(t);
            for (i, fi) in idx.iter().zip(v) {
                if let Some(i) = i {
                    qf[o + i] += fi;
                }
            }
        }
        p
    }

    /// (kinetic ½u̇ᵀMu̇, elastic ½uᵀKu), J.
    pub(crate) fn energies(&self, q: &[f64], qd: &[f64]) -> (f64, f64) {
        let (o, nf) = (self.offset, self.n_free());
        let (u, ud) = (&q[o..o + nf], &qd[o..o + nf]);
        let (mut ek, mut ee) = (0.0, 0.0);
        for a in 0..nf {
            for b in 0..nf {
                ek += 0.5 * ud[a] * self.m[a * nf + b] * ud[b];
                ee += 0.5 * u[a] * self.k[a * nf + b] * u[b];
            }
        }
        (ek, ee)
    }
}
