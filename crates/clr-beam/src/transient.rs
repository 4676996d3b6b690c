//! Transient response of a supported beam or frame as a first-order system for an ODE solver.
//!
//! With the free DOF u, M ü + C u̇ + K u = f(t) − K_fc u_c (u_c the prescribed values) becomes
//! y = (u, u̇), y' = (u̇, M⁻¹(f(t) − K_fc u_c) − M⁻¹K u − M⁻¹C u̇). M⁻¹K, M⁻¹C and M⁻¹ are formed
//! once (dense, O(n³)); each right-hand side costs O(n²) and allocates nothing. The Jacobian
//! [[0, I], [−M⁻¹K, −M⁻¹C]] is constant. The struct has the shape of clr-ode's `OdeSystem`
//! (`dim`, `rhs(&mut self, t, y, dydt)`, column-major `jacobian`) without depending on it.

use faer::linalg::solvers::{DenseSolveCore, Solve};
use faer::{Mat, Side};

use crate::error::BeamError;
use crate::model::{restrict, BeamModel, DofMap, Loads};

/// A time-dependent load: writes f(t) over the free DOF (N, N·m) into the zeroed buffer.
pub type LoadFn = Box<dyn FnMut(f64, &mut [f64]) + Send>;

/// M, C, K of a model on its free DOF as the first-order system y' = f(t, y), y = (u, u̇).
pub struct TransientSystem {
    n: usize,
    dofs: DofMap,
    minv: Mat<f64>,
    minv_k: Mat<f64>,
    minv_c: Mat<f64>,
    /// −K_fc u_c over the free DOF.
    f_prescribed: Vec<f64>,
    load: Option<LoadFn>,
    f: Vec<f64>,
}

impl std::fmt::Debug for TransientSystem {
    fn fmt(&self, fm: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        fm.debug_struct("TransientSystem")
            .field("free_dof", &self.n)
            .finish_non_exhaustive()
    }
}

impl TransientSystem {
    /// The system of `model` (its supports, mass kind and Rayleigh damping), unloaded.
    pub fn new(model: &BeamModel) -> Result<Self, BeamError> {
        let dofs = model.dof_map()?;
        let k = model.stiffness_dense()?;
        let m = model.mass_dense()?;
        let c = model.damping_dense()?;
        let kff = restrict(k.as_ref(), &dofs.free, &dofs.free);
        let mff = restrict(m.as_ref(), &dofs.free, &dofs.free);
        let cff = restrict(c.as_ref(), &dofs.free, &dofs.free);
        let llt = mff.llt(Side::Lower).map_err(|_| BeamError::SingularMass)?;
        let minv = llt.inverse();
        let mut minv_k = kff;
        llt.solve_in_place(minv_k.as_mut());
        let mut minv_c = cff;
        llt.solve_in_place(minv_c.as_mut());
        let n = dofs.free.len();
        let f_prescribed = dofs
            .free
            .iter()
            .map(|&i| {
                -dofs
                    .constrained
                    .iter()
                    .map(|&j| k[(i, j)] * model.prescribed()[j].unwrap_or(0.0))
                    .sum::<f64>()
            })
            .collect();
        Ok(Self {
            n,
            dofs,
            minv,
            minv_k,
            minv_c,
            f_prescribed,
            load: None,
            f: vec![0.0; n],
        })
    }

    /// Set a general load f(t) over the free DOF (see [`TransientSystem::free_index`]).
    pub fn with_load(mut self, load: LoadFn) -> Self {
        self.load = Some(load);
        self
    }

    /// Load with a fixed spatial pattern scaled in time: f(t) = g(t) · f₀, f₀ from `loads`
    /// on `model` (the same model this system was built from).
    pub fn with_load_pattern(
        self,
        model: &BeamModel,
        loads: &Loads,
        g: impl Fn(f64) -> f64 + Send + 'static,
    ) -> Result<Self, BeamError> {
        let full = loads.vector(model)?;
        let f0: Vec<f64> = self.dofs.free.iter().map(|&d| full[d]).collect();
        Ok(self.with_load(Box::new(move |t, f| {
            let s = g(t);
            for (fi, f0i) in f.iter_mut().zip(&f0) {
                *fi = s * f0i;
            }
        })))
    }

    /// Number of first-order states 2n (n free DOF).
    pub fn dim(&self) -> usize {
        2 * self.n
    }

    /// The free/constrained DOF partition.
    pub fn dofs(&self) -> &DofMap {
        &self.dofs
    }

    /// Index among the free DOF of full DOF `dof` (None when constrained). In y, the
    /// displacement of that DOF is `y[i]`, its velocity `y[n + i]`.
    pub fn free_index(&self, dof: usize) -> Option<usize> {
        self.dofs.free_index.get(dof).copied().flatten()
    }

    /// y' = f(t, y) (no allocation).
    pub fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
        let n = self.n;
        self.f.iter_mut().for_each(|x| *x = 0.0);
        if let Some(load) = self.load.as_mut() {
            load(t, &mut self.f);
        }
        for (a, b) in self.f.iter_mut().zip(&self.f_prescribed) {
            *a += b;
        }
        let (u, v) = y.split_at(n);
        let (du, dv) = dydt.split_at_mut(n);
        du.copy_from_slice(v);
        for (i, dvi) in dv.iter_mut().enumerate() {
            let mut acc = 0.0;
            for j in 0..n {
                acc += self.minv[(i, j)] * self.f[j]
                    - self.minv_k[(i, j)] * u[j]
                    - self.minv_c[(i, j)] * v[j];
            }
            *dvi = acc;
        }
    }

    /// The constant Jacobian ∂f/∂y, column-major 2n × 2n (entry (i, j) at `jac[i + j·2n]`),
    /// written over the whole slice.
    pub fn jacobian(&self, jac: &mut [f64]) {
        let n = self.n;
        let d = 2 * n;
        jac.iter_mut().for_each(|x| *x = 0.0);
        for i in 0..n {
            jac[i + (n + i) * d] = 1.0;
            for j in 0..n {
                jac[(n + i) + j * d] = -self.minv_k[(i, j)];
                jac[(n + i) + (n + j) * d] = -self.minv_c[(i, j)];
            }
        }
    }

    /// Full nodal displacements (3 per node) from a state y, prescribed values included.
    pub fn displacements(&self, model: &BeamModel, y: &[f64]) -> Vec<f64> {
        let mut u: Vec<f64> = model
            .prescribed()
            .iter()
            .map(|p| p.unwrap_or(0.0))
            .collect();
        for (i, &d) in self.dofs.free.iter().enumerate() {
            u[d] = y[i];
        }
        u
    }
}
