//! Modal analysis: the lowest solutions of the generalized symmetric eigenproblem
//! K φ = ω² M φ on the free DOF.
//!
//! Method (dense, shift-invert): with a shift σ > 0, factor K + σM = L Lᵀ (Cholesky), form the
//! standard symmetric matrix B = L⁻¹ M L⁻ᵀ, whose eigenvalues μ = 1/(ω² + σ) are largest for the
//! lowest modes, and solve it with faer's self-adjoint eigendecomposition; φ = L⁻ᵀ y / √μ is
//! mass normalized (φᵀ M φ = 1). The inverted form keeps the lowest eigenvalues accurate to
//! round-off relative to themselves (Bathe, *Finite Element Procedures*, 2nd ed. 2014, §11.2),
//! and the shift makes free–free models (singular K) solvable.
//!
//! The shift is σ = λ_ref = min EI / (max ρA · L_tot⁴) with L_tot the summed element length, a
//! lower scale of the structure's elastic ω² (a free–free beam of length L_tot has
//! ω₁² = 500.6 λ_ref). An eigenvalue with |ω²| ≤ [`ZERO_MODE_TOL`] · λ_ref is a rigid-body mode
//! and is reported as exactly ω = 0.
//!
//! Two solvers ([`EigenMethod`]): the dense one above, O(n³) in the number of free DOF n, and a
//! sparse shift-invert subspace iteration ([`subspace_modes`]) with the same shift, O(n) per
//! iteration for beams and frames; [`EigenMethod::Auto`] picks dense up to
//! [`AUTO_DENSE_LIMIT`] free DOF. Round-off limits the relative accuracy of the lowest
//! frequencies of fine meshes to about 1e-8 (λ_max/λ₁ grows as the element count to the fourth).

use faer::linalg::solvers::Solve;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, MatRef, Par, Side};

use crate::error::BeamError;
use crate::model::{restrict, BeamModel, DofMap};

/// Relative threshold (to λ_ref) below which |ω²| counts as a rigid-body mode (ω = 0).
pub const ZERO_MODE_TOL: f64 = 1e-6;

/// The lowest natural modes of a model.
#[derive(Debug, Clone)]
pub struct Modes {
    /// Circular frequencies ω (rad/s), ascending; exactly 0 for rigid-body modes.
    pub omega: Vec<f64>,
    /// Mode shapes, full DOF ordering (3 per node) × modes, mass normalized (φᵀMφ = 1, units
    /// m/√kg and rad/√kg); zero at constrained DOF.
    pub shapes: Mat<f64>,
    /// Number of rigid-body (zero-frequency) modes among the returned ones.
    pub rigid_body_modes: usize,
    /// The free/constrained DOF partition used.
    pub dofs: DofMap,
}

impl Modes {
    /// Frequencies f = ω/2π (Hz).
    pub fn frequencies_hz(&self) -> Vec<f64> {
        self.omega
            .iter()
            .map(|w| w / (2.0 * std::f64::consts::PI))
            .collect()
    }
}

impl BeamModel {
    /// Reference eigenvalue scale λ_ref = min EI / (max ρA · L_tot⁴) (1/s²) used for the shift
    /// and the rigid-body threshold of the eigen solver.
    pub fn lambda_ref(&self) -> f64 {
        let ei = self
            .elements()
            .iter()
            .map(|e| e.ei)
            .fold(f64::INFINITY, f64::min);
        let ra = self.elements().iter().map(|e| e.rho_a).fold(0.0, f64::max);
        let l: f64 = self.elements().iter().map(|e| e.length).sum();
        ei / (ra * l.powi(4))
    }

    /// The lowest `n` modes of the model with its supports (prescribed DOF held at zero),
    /// with [`EigenMethod::Auto`]. Errors: `n` = 0, more modes than free DOF, indefinite
    /// stiffness (compression beyond buckling), non-positive-definite mass.
    pub fn modes(&self, n: usize) -> Result<Modes, BeamError> {
        self.modes_with(n, EigenMethod::Auto)
    }

    /// The lowest `n` modes with a chosen eigen solver.
    pub fn modes_with(&self, n: usize, method: EigenMethod) -> Result<Modes, BeamError> {
        let dofs = self.dof_map()?;
        let nf = dofs.free.len();
        let dense = match method {
            EigenMethod::Dense => true,
            EigenMethod::Subspace => false,
            EigenMethod::Auto => nf <= AUTO_DENSE_LIMIT || 2 * n + 8 >= nf,
        };
        let (lambda, phi) = if dense {
            let k = self.stiffness_dense()?;
            let m = self.mass_dense()?;
            let kff = restrict(k.as_ref(), &dofs.free, &dofs.free);
            let mff = restrict(m.as_ref(), &dofs.free, &dofs.free);
            lowest_modes(kff.as_ref(), mff.as_ref(), n, self.lambda_ref())?
        } else {
            let (k, m) = self.free_sparse(&dofs)?;
            subspace_modes(k.as_ref(), m.as_ref(), n, self.lambda_ref())?
        };
        let mut shapes = Mat::<f64>::zeros(self.n_dof(), n);
        for j in 0..n {
            for (i, &d) in dofs.free.iter().enumerate() {
                shapes[(d, j)] = phi[(i, j)];
            }
        }
        let omega: Vec<f64> = lambda.iter().map(|l| l.sqrt()).collect();
        let rigid_body_modes = omega.iter().filter(|w| **w == 0.0).count();
        Ok(Modes {
            omega,
            shapes,
            rigid_body_modes,
            dofs,
        })
    }
}

/// Free-DOF count up to which [`EigenMethod::Auto`] uses the dense solver.
pub const AUTO_DENSE_LIMIT: usize = 200;

/// Eigen solver of [`BeamModel::modes_with`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EigenMethod {
    /// Dense shift-invert with a full symmetric eigendecomposition ([`lowest_modes`]):
    /// O(n³), all modes exact to round-off.
    Dense,
    /// Sparse shift-invert subspace iteration ([`subspace_modes`]): O(n) per iteration for
    /// beams and frames (banded matrices).
    Subspace,
    /// Dense up to [`AUTO_DENSE_LIMIT`] free DOF (or when the subspace would be nearly the
    /// whole space), subspace iteration above.
    #[default]
    Auto,
}

/// Lowest `n` eigenpairs of K φ = λ M φ for sparse K (positive semi-definite) and M (positive
/// definite) by shift-invert subspace iteration with Rayleigh–Ritz projection (Bathe,
/// *Finite Element Procedures*, 2nd ed. 2014, §11.6): q = max(2n, n + 8) vectors, the
/// shifted matrix A = K + σM (σ = `lambda_ref`, see the module docs) factored once by sparse
/// Cholesky; per iteration Y = M X, X̄ = A⁻¹ Y, the projected pencil (X̄ᵀY, X̄ᵀMX̄) is solved
/// densely and X = X̄ Q. Converged when the n lowest Ritz values of A change by less than
/// 1e-12 relative between iterations (at most 300 iterations). Same outputs as
/// [`lowest_modes`].
pub fn subspace_modes(
    k: faer::sparse::SparseColMatRef<'_, usize, f64>,
    m: faer::sparse::SparseColMatRef<'_, usize, f64>,
    n: usize,
    lambda_ref: f64,
) -> Result<(Vec<f64>, Mat<f64>), BeamError> {
    let dim = k.nrows();
    check_count(n, dim)?;
    let q = (2 * n).max(n + 8).min(dim);
    let sigma = lambda_ref;
    let a = sparse_add(k, m, sigma)?;
    let llt = a
        .sp_cholesky(Side::Lower)
        .map_err(|_| BeamError::Indefinite { lambda: -sigma })?;
    // Deterministic start: diagonal of M, then a fixed pseudo-random sequence (LCG).
    let mut seed: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut x = Mat::<f64>::from_fn(dim, q, |i, j| {
        if j == 0 {
            1.0 + (i % 3) as f64
        } else {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        }
    });
    let mut previous: Vec<f64> = vec![f64::INFINITY; n];
    for _ in 0..300 {
        let y = m * &x;
        let mut xb = y.clone();
        llt.solve_in_place(xb.as_mut());
        let ab = xb.transpose() * &y;
        let mxb = m * &xb;
        let mb = xb.transpose() * &mxb;
        let ab = Mat::from_fn(q, q, |i, j| 0.5 * (ab[(i, j)] + ab[(j, i)]));
        let mb = Mat::from_fn(q, q, |i, j| 0.5 * (mb[(i, j)] + mb[(j, i)]));
        // Ritz values of A (≥ σ), by the dense solver on the small pencil.
        let (ritz, qv) = lowest_modes(ab.as_ref(), mb.as_ref(), q, sigma)?;
        x = &xb * &qv;
        let converged = ritz
            .iter()
            .zip(&previous)
            .take(n)
            .all(|(r, p)| (r - p).abs() <= 1e-12 * r.abs());
        previous = ritz[..n].to_vec();
        if converged {
            let mut lambda = Vec::with_capacity(n);
            for &r in &previous {
                lambda.push(classify(r - sigma, lambda_ref)?);
            }
            let mut phi = x.subcols(0, n).to_owned();
            fix_signs(&mut phi);
            return Ok((lambda, phi));
        }
    }
    Err(BeamError::Eigen(
        "subspace iteration did not converge in 300 iterations; use EigenMethod::Dense".into(),
    ))
}

/// K + σ M for sparse matrices of the same pattern family.
fn sparse_add(
    k: faer::sparse::SparseColMatRef<'_, usize, f64>,
    m: faer::sparse::SparseColMatRef<'_, usize, f64>,
    sigma: f64,
) -> Result<faer::sparse::SparseColMat<usize, f64>, BeamError> {
    let mut t = Vec::with_capacity(k.compute_nnz() + m.compute_nnz());
    for (mat, s) in [(k, 1.0), (m, sigma)] {
        for j in 0..mat.ncols() {
            for (i, v) in mat.row_idx_of_col(j).zip(mat.val_of_col(j)) {
                t.push(faer::sparse::Triplet::new(i, j, s * v));
            }
        }
    }
    faer::sparse::SparseColMat::try_new_from_triplets(k.nrows(), k.ncols(), &t)
        .map_err(|e| BeamError::Sparse(format!("{e:?}")))
}

/// 1 ≤ n ≤ dim, or the matching error.
fn check_count(n: usize, dim: usize) -> Result<(), BeamError> {
    if n == 0 {
        return Err(BeamError::ZeroModes);
    }
    if n > dim {
        return Err(BeamError::TooManyModes {
            requested: n,
            available: dim,
        });
    }
    Ok(())
}

/// An eigenvalue ω² (rad²/s²): 0 when |ω²| ≤ [`ZERO_MODE_TOL`] · λ_ref (rigid-body mode),
/// an error when clearly negative (indefinite stiffness).
fn classify(lambda: f64, lambda_ref: f64) -> Result<f64, BeamError> {
    if lambda.abs() <= ZERO_MODE_TOL * lambda_ref {
        Ok(0.0)
    } else if lambda < 0.0 {
        Err(BeamError::Indefinite { lambda })
    } else {
        Ok(lambda)
    }
}

/// Deterministic sign: the largest-magnitude component of each column positive.
fn fix_signs(y: &mut Mat<f64>) {
    for j in 0..y.ncols() {
        let mut imax = 0;
        for i in 0..y.nrows() {
            if y[(i, j)].abs() > y[(imax, j)].abs() {
                imax = i;
            }
        }
        if y[(imax, j)] < 0.0 {
            for i in 0..y.nrows() {
                y[(i, j)] = -y[(i, j)];
            }
        }
    }
}

/// Lowest `n` eigenpairs of K φ = λ M φ (K symmetric positive semi-definite, M symmetric
/// positive definite), by shift-invert with σ = `lambda_ref` (see the module docs). Returns
/// λ ascending (rigid-body λ set to 0) and M-normalized eigenvectors as columns.
pub fn lowest_modes(
    k: MatRef<'_, f64>,
    m: MatRef<'_, f64>,
    n: usize,
    lambda_ref: f64,
) -> Result<(Vec<f64>, Mat<f64>), BeamError> {
    let dim = k.nrows();
    check_count(n, dim)?;
    // M must be positive definite on its own.
    m.llt(Side::Lower).map_err(|_| BeamError::SingularMass)?;
    let sigma = lambda_ref;
    let a = Mat::from_fn(dim, dim, |i, j| k[(i, j)] + sigma * m[(i, j)]);
    let llt = a
        .llt(Side::Lower)
        .map_err(|_| BeamError::Indefinite { lambda: -sigma })?;
    let l = llt.L();
    // X = L⁻¹ M, then B = L⁻¹ Xᵀ = L⁻¹ M L⁻ᵀ.
    let mut x = m.to_owned();
    solve_lower_triangular_in_place(l, x.as_mut(), Par::Seq);
    let mut b = x.transpose().to_owned();
    solve_lower_triangular_in_place(l, b.as_mut(), Par::Seq);
    // Symmetrize against round-off.
    let b = Mat::from_fn(dim, dim, |i, j| 0.5 * (b[(i, j)] + b[(j, i)]));
    let evd = b
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| BeamError::Eigen(format!("{e:?}")))?;
    let s = evd.S().column_vector();
    let u = evd.U();
    let mut lambda = Vec::with_capacity(n);
    let mut y = Mat::<f64>::zeros(dim, n);
    for j in 0..n {
        let c = dim - 1 - j; // eigenvalues ascending: largest μ last
        let mu = s[c];
        if mu.is_nan() || mu <= 0.0 {
            return Err(BeamError::Eigen(format!(
                "non-positive inverted eigenvalue {mu}"
            )));
        }
        lambda.push(classify(1.0 / mu - sigma, lambda_ref)?);
        let scale = 1.0 / mu.sqrt();
        for i in 0..dim {
            y[(i, j)] = u[(i, c)] * scale;
        }
    }
    solve_upper_triangular_in_place(l.transpose(), y.as_mut(), Par::Seq);
    fix_signs(&mut y);
    Ok((lambda, y))
}
