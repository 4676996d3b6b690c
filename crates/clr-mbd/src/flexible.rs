//! Ground-fixed flexible beams: the free nodal coordinates of a clr-beam model appended to q.
//!
//! The beam's supports (clamps, pins, rollers set on the `clr_beam::BeamModel`) fix it to the
//! ground; its free DOF u (nodal displacements and rotations, small-deformation
//! Euler–Bernoulli frame elements) enter q after the rigid-body coordinates with the constant
//! mass matrix M_ff, stiffness K_ff and Rayleigh damping C_ff of clr-beam restricted to the free
//! DOF: M_ff ü = −K_ff u − C_ff u̇ + f(t) + f_g.
//!
//! Gravity g acts on the beam's distributed mass ρA as the consistent nodal loads of a uniform
//! load ρA·g on every element, f_g = Σ_e ∫Nᵀ ρA g dx (transverse and axial components in the
//! element frame: clr-beam `Loads::self_weight`; Przemieniecki, *Theory of Matrix Structural
//! Analysis*, 1968, ch. 5). They are the exact gradient of the potential of the interpolated
//! field, V = −g·(S₀ + ∫ρA u dx) = −g·S₀ − f_gᵀu with S₀ = Σ ρA L r_centroid the undeformed
//! first mass moment, so the energy balance stays closed; being constant they add nothing to
//! the Jacobian.

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
    /// Free-DOF mass, stiffness and damping matrices (nf × nf, banded by the mesh: stored by
    /// rows of non-zeros so that a step costs O(elements), not O(elements²)).
    pub(crate) m: RowSparse,
    pub(crate) k: RowSparse,
    pub(crate) c: RowSparse,
    /// Nodal loads: the free index of the node's three DOF (`None` when constrained) and f(t).
    pub(crate) loads: Vec<([Option<usize>; 3], NodalLoadFn)>,
    /// Consistent nodal loads of the self weight per unit acceleration along x and along y
    /// (free ordering, kg: N per m/s²), and the undeformed first mass moment S₀ (kg·m).
    weight: [Vec<f64>; 2],
    mass_moment: [f64; 2],
    /// f_g for the model's gravity (free ordering, N and N·m; empty without gravity, so that a
    /// beam without gravity adds nothing, not even zeros) and its potential at u = 0, −g·S₀ (J).
    gravity_load: Vec<f64>,
    gravity_potential0: f64,
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
        let free =
            |a: &faer::Mat<f64>| RowSparse::from_fn(nf, |r, c| a[(map.free[r], map.free[c])]);
        let unit_weight = |g: [f64; 2]| -> Result<Vec<f64>, MbdError> {
            let full = clr_beam::Loads::new()
                .self_weight(model, g)
                .vector(model)
                .map_err(err)?;
            Ok(map.free.iter().map(|&d| full[d]).collect())
        };
        let mut mass_moment = [0.0; 2];
        for e in model.elements() {
            let [a, b] = e.nodes.map(|k| model.nodes()[k]);
            for (s, (xa, xb)) in mass_moment.iter_mut().zip(a.into_iter().zip(b)) {
                *s += e.rho_a * e.length * 0.5 * (xa + xb);
            }
        }
        let out = FlexBeam {
            name: name.to_string(),
            offset: 0,
            free: map.free.clone(),
            n_dof_full: model.n_dof(),
            nodes: model.nodes().to_vec(),
            free_index: map.free_index.clone(),
            path: model.path().ok(),
            m: free(&m),
            k: free(&k),
            c: free(&c),
            loads: Vec::new(),
            weight: [unit_weight([1.0, 0.0])?, unit_weight([0.0, 1.0])?],
            mass_moment,
            gravity_load: Vec::new(),
            gravity_potential0: 0.0,
        };
        Ok(out)
    }

    /// Set the gravitational acceleration `g` (m/s²) the beam's weight follows.
    pub(crate) fn set_gravity(&mut self, g: [f64; 2]) {
        self.gravity_load = if g == [0.0, 0.0] {
            Vec::new()
        } else {
            let [wx, wy] = &self.weight;
            wx.iter()
                .zip(wy)
                .map(|(x, y)| g[0] * x + g[1] * y)
                .collect()
        };
        self.gravity_potential0 = -(g[0] * self.mass_moment[0] + g[1] * self.mass_moment[1]);
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

    /// Add −K u − C u̇ + f(t) + f_g to `qf` (free ordering at `offset`) and return (the dissipated
    /// power u̇ᵀ C u̇, the power of the nodal loads f(t)ᵀu̇), W; the weight's power is in the
    /// potential energy ([`FlexBeam::energies`]). Load components on supported DOF do no work
    /// and are dropped.
    pub(crate) fn forces(&self, t: f64, q: &[f64], qd: &[f64], qf: &mut [f64]) -> (f64, f64) {
        let (o, nf) = (self.offset, self.n_free());
        let (u, ud) = (&q[o..o + nf], &qd[o..o + nf]);
        let mut p = 0.0;
        for a in 0..nf {
            let ku = self.k.row_dot(a, u);
            let cu = self.c.row_dot(a, ud);
            qf[o + a] -= ku + cu;
            p += ud[a] * cu;
        }
        for (a, fg) in self.gravity_load.iter().enumerate() {
            qf[o + a] += fg;
        }
        let mut p_in = 0.0;
        for (idx, f) in &self.loads {
            let v = f(t);
            for (i, fi) in idx.iter().zip(v) {
                if let Some(i) = i {
                    qf[o + i] += fi;
                    p_in += fi * ud[*i];
                }
            }
        }
        (p, p_in)
    }

    /// [kinetic ½u̇ᵀMu̇, gravitational −g·S₀ − f_gᵀu, elastic ½uᵀKu], J.
    pub(crate) fn energies(&self, q: &[f64], qd: &[f64]) -> [f64; 3] {
        let (o, nf) = (self.offset, self.n_free());
        let (u, ud) = (&q[o..o + nf], &qd[o..o + nf]);
        let (mut ek, mut ee) = (0.0, 0.0);
        for a in 0..nf {
            ek += 0.5 * ud[a] * self.m.row_dot(a, ud);
            ee += 0.5 * u[a] * self.k.row_dot(a, u);
        }
        let ep = self.gravity_potential0
            - (self.gravity_load.iter())
                .zip(u)
                .map(|(f, u)| f * u)
                .sum::<f64>();
        [ek, ep, ee]
    }
}

/// A square matrix stored by rows of non-zeros (compressed sparse rows).
#[derive(Debug, Clone, Default)]
pub(crate) struct RowSparse {
    ptr: Vec<usize>,
    col: Vec<usize>,
    val: Vec<f64>,
}

impl RowSparse {
    /// The non-zeros of the n × n matrix with entries `f(row, col)`.
    pub(crate) fn from_fn(n: usize, f: impl Fn(usize, usize) -> f64) -> Self {
        let mut out = RowSparse {
            ptr: vec![0],
            ..Default::default()
        };
        for r in 0..n {
            for c in 0..n {
                let v = f(r, c);
                if v != 0.0 {
                    out.col.push(c);
                    out.val.push(v);
                }
            }
            out.ptr.push(out.col.len());
        }
        out
    }

    /// Σ_c A[r, c] x[c].
    #[inline]
    pub(crate) fn row_dot(&self, r: usize, x: &[f64]) -> f64 {
        let (a, b) = (self.ptr[r], self.ptr[r + 1]);
        self.col[a..b]
            .iter()
            .zip(&self.val[a..b])
            .map(|(&c, v)| v * x[c])
            .sum()
    }

    /// Entry (r, c) (zero outside the pattern).
    pub(crate) fn get(&self, r: usize, c: usize) -> f64 {
        let (a, b) = (self.ptr[r], self.ptr[r + 1]);
        self.col[a..b]
            .binary_search(&c)
            .map_or(0.0, |k| self.val[a + k])
    }

    /// The non-zeros as (row, col, value).
    pub(crate) fn entries(&self) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
        (0..self.ptr.len() - 1).flat_map(move |r| {
            (self.ptr[r]..self.ptr[r + 1]).map(move |k| (r, self.col[k], self.val[k]))
        })
    }
}
