//! Linear systems of the multibody equations: the augmented matrix G = [M Φ_qᵀ; Φ_q 0] of every
//! right-hand-side evaluation and the reduced Newton matrix of the integrator
//! ([`crate::newton`]), factored densely (small models) or as sparse matrices whose pattern is
//! analysed once and grows on demand ([`GrowingLu`]).
//!
//! A beam meshed with N elements has a banded mass and stiffness matrix; the contact of a slider
//! couples its three coordinates with the beam's, and constraints couple a few bodies each. With
//! the sparse factorization the cost of a step grows about linearly with N (measured by
//! `cargo xtask bench beam`, docs/performance.md), where the dense LU grows with N³.

use clr_ode::linalg::{DenseLu, Singular};
use clr_ode::sparse::SparseLu;

/// Which factorization the augmented and Newton systems use (`[solver] linear_solver` in model
/// files: `auto`, `dense`, `sparse`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LinearSolver {
    /// Sparse for models with n + m ≥ [`SPARSE_FROM`] coordinates and constraint rows, dense
    /// below (the default).
    #[default]
    Auto,
    /// Dense LU with partial pivoting.
    Dense,
    /// Sparse LU with a fixed (growing) pattern and COLAMD ordering.
    Sparse,
}

/// Size n + m from which [`LinearSolver::Auto`] factors sparse matrices. Measured (release, 2
/// cores): the clearance slider–crank (n + m = 16) runs 1.4× faster dense, the flap with two
/// flexible parts (n + m = 56) 1.35× faster sparse (docs/performance.md).
pub const SPARSE_FROM: usize = 32;

impl LinearSolver {
    /// Whether a system of size `dim` is factored sparse.
    pub fn is_sparse(self, dim: usize) -> bool {
        match self {
            LinearSolver::Auto => dim >= SPARSE_FROM,
            LinearSolver::Dense => false,
            LinearSolver::Sparse => true,
        }
    }
}

/// A sparse LU whose pattern grows when an entry outside it is added: the symbolic analysis is
/// redone then (rarely: the pattern settles after the first contacts), and kept otherwise. Use
/// [`GrowingLu::begin`], [`GrowingLu::add`] for every non-zero, then [`GrowingLu::factor`].
#[derive(Debug, Default)]
pub(crate) struct GrowingLu {
    n: usize,
    lu: Option<SparseLu>,
    /// Entries added since `begin` that lie outside the pattern.
    missing: Vec<(usize, usize, f64)>,
    /// Symbolic analyses made (1 + pattern growths).
    pub(crate) analyses: usize,
}

impl GrowingLu {
    /// Start a new matrix of size n (all entries zero).
    pub(crate) fn begin(&mut self, n: usize) {
        if self.n != n {
            self.n = n;
            self.lu = None;
        }
        self.missing.clear();
        if let Some(lu) = &mut self.lu {
            lu.values_mut().fill(0.0);
        }
    }

    /// Add v at (row, col).
    #[inline]
    pub(crate) fn add(&mut self, row: usize, col: usize, v: f64) {
        if v == 0.0 {
            return;
        }
        match self.lu.as_mut().and_then(|lu| {
            let p = lu.position(row, col)?;
            Some((lu, p))
        }) {
            Some((lu, p)) => lu.values_mut()[p] += v,
            None => self.missing.push((row, col, v)),
        }
    }

    /// Factor the matrix added since [`GrowingLu::begin`], first widening the pattern (a new
    /// symbolic analysis) if entries fell outside it.
    pub(crate) fn factor(&mut self) -> Result<(), Singular> {
        if !self.missing.is_empty() || self.lu.is_none() {
            self.grow()?;
        }
        self.lu.as_mut().ok_or(Singular)?.factor()
    }

    /// Solve with the last factorization.
    pub(crate) fn solve(&mut self, b: &mut [f64]) {
        if let Some(lu) = &mut self.lu {
            lu.solve(b);
        }
    }

    fn grow(&mut self) -> Result<(), Singular> {
        let n = self.n;
        let old: Vec<(usize, usize, f64)> = match &self.lu {
            Some(lu) => lu.entries().collect(),
            None => Vec::new(),
        };
        let entries = old
            .iter()
            .chain(&self.missing)
            .map(|&(r, c, _)| (r, c))
            .collect::<Vec<_>>();
        let mut lu = SparseLu::new(n, entries).ok_or(Singular)?;
        for &(r, c, v) in old.iter().chain(&self.missing) {
            if let Some(p) = lu.position(r, c) {
                lu.values_mut()[p] += v;
            }
        }
        self.missing.clear();
        self.lu = Some(lu);
        self.analyses += 1;
        Ok(())
    }
}

/// The factorization of one kind of system: dense or growing sparse.
#[derive(Debug, Default)]
pub(crate) struct Factorization {
    pub(crate) sparse: bool,
    pub(crate) dense: DenseLu,
    pub(crate) growing: GrowingLu,
}
