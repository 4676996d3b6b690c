//! Sparse LU with a fixed pattern: the symbolic analysis (COLAMD column ordering, elimination
//! structure) is done once, and each [`SparseLu::factor`] only redoes the numeric factorization
//! with partial pivoting (faer's `sparse::linalg::lu`, Gilbert–Peierls left-looking or
//! supernodal by faer's flop-ratio threshold). For Newton matrices whose values change at every
//! factorization while their pattern does not (the iteration matrices of an implicit integrator),
//! as KLU's `klu_refactor` or UMFPACK's numeric phase are used.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::sparse::linalg::lu::{
    factorize_symbolic_lu, LuRef, LuSymbolicParams, NumericLu, SymbolicLu,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par};

use crate::linalg::Singular;

/// An LU factorization of n × n matrices with one sparsity pattern.
pub struct SparseLu {
    n: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    values: Vec<f64>,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    factored: bool,
    mem: MemBuffer,
    probe: Vec<f64>,
}

impl std::fmt::Debug for SparseLu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SparseLu")
            .field("n", &self.n)
            .field("nnz", &self.values.len())
            .finish()
    }
}

impl SparseLu {
    /// Analyse the pattern of an n × n matrix given as (row, column) entries (duplicates are
    /// merged; the diagonal is always included so that a structurally empty row cannot make the
    /// analysis fail). Returns `None` when an index is out of range or the analysis fails.
    pub fn new(n: usize, entries: impl IntoIterator<Item = (usize, usize)>) -> Option<Self> {
        let mut cols: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (r, c) in entries {
            if r >= n || c >= n {
                return None;
            }
            cols[c].push(r);
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for (c, rows) in cols.iter_mut().enumerate() {
            rows.push(c);
            rows.sort_unstable();
            rows.dedup();
            row_idx.extend_from_slice(rows);
            col_ptr.push(row_idx.len());
        }
        let sym = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
        let symbolic = factorize_symbolic_lu(sym, LuSymbolicParams::default()).ok()?;
        let req = StackReq::any_of(&[
            symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
        ]);
        let nnz = row_idx.len();
        Some(Self {
            n,
            col_ptr,
            row_idx,
            values: vec![0.0; nnz],
            symbolic,
            numeric: NumericLu::new(),
            factored: false,
            mem: MemBuffer::new(req),
            probe: vec![0.0; n],
        })
    }

    /// Dimension n.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.values.len()
    }

    /// Position of entry (row, col) in [`SparseLu::values_mut`], `None` outside the pattern.
    pub fn position(&self, row: usize, col: usize) -> Option<usize> {
        let (a, b) = (self.col_ptr[col], self.col_ptr[col + 1]);
        self.row_idx[a..b].binary_search(&row).ok().map(|k| a + k)
    }

    /// The stored entries (row, col, value), column by column.
    pub fn entries(&self) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
        (0..self.n).flat_map(move |c| {
            (self.col_ptr[c]..self.col_ptr[c + 1])
                .map(move |k| (self.row_idx[k], c, self.values[k]))
        })
    }

    /// The values in pattern order (column by column, rows increasing), to fill before
    /// [`SparseLu::factor`].
    pub fn values_mut(&mut self) -> &mut [f64] {
        &mut self.values
    }

    /// Factor the matrix held in [`SparseLu::values_mut`] (numeric phase only).
    pub fn factor(&mut self) -> Result<(), Singular> {
        self.factored = false;
        if !self.values.iter().all(|v| v.is_finite()) {
            return Err(Singular);
        }
        let sym = SymbolicSparseColMatRef::new_checked(
            self.n,
            self.n,
            &self.col_ptr,
            None,
            &self.row_idx,
        );
        let a = SparseColMatRef::new(sym, &self.values);
        let stack = MemStack::new(&mut self.mem);
        self.symbolic
            .factorize_numeric_lu(&mut self.numeric, a, Par::Seq, stack, Default::default())
            .map_err(|_| Singular)?;
        self.factored = true;
        // faer's numeric phase does not report a zero pivot: a solve with a probe vector does
        // (inf or NaN), at the cost of one solve per factorization
        let mut probe = std::mem::take(&mut self.probe);
        probe.clear();
        probe.resize(self.n, 1.0);
        self.solve(&mut probe);
        let ok = probe.iter().all(|v| v.is_finite());
        self.probe = probe;
        if !ok {
            self.factored = false;
            return Err(Singular);
        }
        Ok(())
    }

    /// Solve A x = b in place with the last successful factorization (`b` becomes x; left
    /// unchanged when there is none).
    pub fn solve(&mut self, b: &mut [f64]) {
        if !self.factored {
            return;
        }
        let lu = LuRef::new_unchecked(&self.symbolic, &self.numeric);
        let rhs = MatMut::from_column_major_slice_mut(&mut b[..self.n], self.n, 1);
        let stack = MemStack::new(&mut self.mem);
        lu.solve_in_place_with_conj(Conj::No, rhs, Par::Seq, stack);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tridiagonal matrix with a dense border row and column (the arrow shape of a beam with a
    /// slider), solved and checked by multiplication; a singular matrix is reported.
    #[test]
    fn arrow_matrix_solves_and_singular_is_reported() {
        let n: usize = 40;
        let mut entries = Vec::new();
        for i in 0..n {
            for j in [i.wrapping_sub(1), i, i + 1] {
                if j < n {
                    entries.push((i, j));
                }
            }
            entries.push((i, n - 1));
            entries.push((n - 1, i));
        }
        let value = |i: usize, j: usize| -> f64 {
            if i == j {
                4.0 + i as f64 * 0.01
            } else if i == n - 1 || j == n - 1 {
                0.1 * ((i + 2 * j) % 7) as f64 - 0.3
            } else {
                -1.0
            }
        };
        let mut lu = SparseLu::new(n, entries.iter().copied()).unwrap();
        for &(i, j) in &entries {
            let p = lu.position(i, j).unwrap();
            lu.values_mut()[p] = value(i, j);
        }
        assert_eq!(lu.position(0, 5), None);
        lu.factor().unwrap();
        let x: Vec<f64> = (0..n).map(|i| 1.0 + (i as f64).sin()).collect();
        let mut b = vec![0.0; n];
        let mut seen = std::collections::HashSet::new();
        for &(i, j) in &entries {
            if seen.insert((i, j)) {
                b[i] += value(i, j) * x[j];
            }
        }
        lu.solve(&mut b);
        for i in 0..n {
            assert!((b[i] - x[i]).abs() < 1e-12, "{i}: {} vs {}", b[i], x[i]);
        }
        lu.values_mut().fill(0.0);
        assert_eq!(lu.factor(), Err(Singular));
    }
}
