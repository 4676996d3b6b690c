//! Dense LU with partial pivoting for the Newton matrix, factored in place into preallocated
//! storage. Small systems (n ≤ [`SMALL_N`]) use a straight-line Doolittle loop, which beats a
//! general blocked factorization at these sizes; larger ones use faer's
//! `lu::partial_pivoting` with a preallocated memory stack. Neither allocates per call.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::{MatMut, MatRef, Par};

/// Largest dimension factored by the hand-written small-matrix path.
pub const SMALL_N: usize = 48;

/// An LU factorization P A = L U held in place (column-major, n × n).
#[derive(Default)]
pub struct DenseLu {
    n: usize,
    lu: Vec<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    mem: Option<MemBuffer>,
}

/// The matrix was singular (a zero or non-finite pivot).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Singular;

impl std::fmt::Debug for DenseLu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DenseLu").field("n", &self.n).finish()
    }
}

impl DenseLu {
    /// Prepare storage for n × n matrices (allocates only when n grows).
    pub fn resize(&mut self, n: usize) {
        if n == self.n {
            return;
        }
        self.n = n;
        self.lu.resize(n * n, 0.0);
        self.perm.resize(n, 0);
        self.perm_inv.resize(n, 0);
        if n > SMALL_N {
            let req = StackReq::any_of(&[
                factor::lu_in_place_scratch::<usize, f64>(n, n, Par::Seq, Default::default()),
                solve::solve_in_place_scratch::<usize, f64>(n, 1, Par::Seq),
            ]);
            self.mem = Some(MemBuffer::new(req));
        }
    }

    /// Bytes of storage held (for checking that restarts do not reallocate).
    pub fn capacity(&self) -> usize {
        self.lu.capacity() + self.perm.capacity() + self.perm_inv.capacity()
    }

    /// The matrix storage to fill before [`DenseLu::factor`] (column-major n × n).
    pub fn matrix_mut(&mut self) -> &mut [f64] {
        &mut self.lu
    }

    /// Factor the matrix written through [`DenseLu::matrix_mut`] in place.
    pub fn factor(&mut self) -> Result<(), Singular> {
        let n = self.n;
        if n <= SMALL_N {
            small_lu(n, &mut self.lu, &mut self.perm)
        } else {
            let mem = self.mem.as_mut().ok_or(Singular)?;
            let stack = MemStack::new(mem);
            let a = MatMut::from_column_major_slice_mut(&mut self.lu, n, n);
            factor::lu_in_place(
                a,
                &mut self.perm,
                &mut self.perm_inv,
                Par::Seq,
                stack,
                Default::default(),
            );
            for i in 0..n {
                let d = self.lu[i + i * n];
                if d == 0.0 || !d.is_finite() {
                    return Err(Singular);
                }
            }
            Ok(())
        }
    }

    /// Solve A x = b in place (`b` becomes x), using the last successful factorization.
    pub fn solve(&mut self, b: &mut [f64]) {
        let n = self.n;
        if n <= SMALL_N {
            small_solve(n, &self.lu, &self.perm, b);
        } else if let Some(mem) = self.mem.as_mut() {
            let stack = MemStack::new(mem);
            let lu = MatRef::from_column_major_slice(&self.lu, n, n);
            let perm = faer::perm::PermRef::new_checked(&self.perm, &self.perm_inv, n);
            let rhs = MatMut::from_column_major_slice_mut(b, n, 1);
            solve::solve_in_place(lu, lu, perm, rhs, Par::Seq, stack);
        }
    }
}

/// Doolittle LU with partial pivoting, column-major, row swaps recorded in `piv`
/// (Golub & Van Loan, Matrix Computations, 4th ed., Algorithm 3.4.1).
fn small_lu(n: usize, a: &mut [f64], piv: &mut [usize]) -> Result<(), Singular> {
    for k in 0..n {
        let mut p = k;
        let mut best = a[k + k * n].abs();
        for i in k + 1..n {
            let v = a[i + k * n].abs();
            if v > best {
                best = v;
                p = i;
            }
        }
        piv[k] = p;
        if best == 0.0 || !best.is_finite() {
            return Err(Singular);
        }
        if p != k {
            for j in 0..n {
                a.swap(k + j * n, p + j * n);
            }
        }
        let inv = 1.0 / a[k + k * n];
        for i in k + 1..n {
            a[i + k * n] *= inv;
        }
        for j in k + 1..n {
            let akj = a[k + j * n];
            if akj != 0.0 {
                for i in k + 1..n {
                    a[i + j * n] -= a[i + k * n] * akj;
                }
            }
        }
    }
    Ok(())
}

fn small_solve(n: usize, a: &[f64], piv: &[usize], b: &mut [f64]) {
    let b = &mut b[..n];
    let a = &a[..n * n];
    for (k, &p) in piv[..n].iter().enumerate() {
        b.swap(k, p);
    }
    // forward: L y = P b (unit lower), column by column
    for (j, col) in a.chunks_exact(n).enumerate() {
        let bj = b[j];
        if bj != 0.0 {
            for i in j + 1..n {
                b[i] -= col[i] * bj;
            }
        }
    }
    // backward: U x = y
    for (j, col) in a.chunks_exact(n).enumerate().rev() {
        let bj = b[j] / col[j];
        b[j] = bj;
        for i in 0..j {
            b[i] -= col[i] * bj;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Residual check A x = b for both paths: an independent verification by multiplication.
    fn check(n: usize) {
        let mut lu = DenseLu::default();
        lu.resize(n);
        let a: Vec<f64> = (0..n * n)
            .map(|k| {
                let (i, j) = (k % n, k / n);
                ((i * 7 + j * 13) % 11) as f64 - 5.0 + if i == j { 0.5 } else { 0.0 }
            })
            .collect();
        let x: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
        let mut b = vec![0.0; n];
        for j in 0..n {
            for i in 0..n {
                b[i] += a[i + j * n] * x[j];
            }
        }
        lu.matrix_mut().copy_from_slice(&a);
        lu.factor().expect("non-singular test matrix");
        lu.solve(&mut b);
        for i in 0..n {
            assert!(
                (b[i] - x[i]).abs() < 1e-9 * (1.0 + x[i].abs()),
                "n={n} i={i}"
            );
        }
    }

    #[test]
    fn small_and_faer_paths_solve() {
        check(3);
        check(8);
        check(SMALL_N + 4);
    }

    #[test]
    fn singular_is_reported() {
        for n in [3, SMALL_N + 2] {
            let mut lu = DenseLu::default();
            lu.resize(n);
            lu.matrix_mut().fill(1.0);
            assert_eq!(lu.factor(), Err(Singular));
        }
    }
}
