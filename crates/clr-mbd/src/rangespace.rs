//! Range-space solution of the augmented equations G [a; λ] = [Q; b], G = [M Φ_qᵀ; Φ_q 0],
//! through the block-diagonal mass matrix (Nikravesh 1988, §13.4; the "range-space" method of
//! the KKT literature, e.g. Nocedal & Wright, *Numerical Optimization*, 2nd ed., §16.2):
//!
//! ```text
//! x = M⁻¹ Q,   Y = M⁻¹ Φ_qᵀ,   (Φ_q Y) λ = Φ_q x − b,   a = x − Y λ.
//! ```
//!
//! M is block diagonal: 3 diagonal entries per rigid body, the constant banded M_ff of a
//! ground-fixed beam (factored once by a banded Cholesky), and the (3 + r)² block of a
//! floating-frame body (a dense Cholesky at every evaluation, M depends on q). Only the m × m
//! matrix W = Φ_q M⁻¹ Φ_qᵀ is factored densely, instead of the (n + m) augmented matrix: on the
//! slider–crank (n = 9, m = 7) and the flap (n = 34, m = 22) this is the dominant cost of a
//! right-hand side. A constraint row touches the coordinates of two bodies, so Y and W are
//! formed block by block.
//!
//! Not applicable (the augmented matrix is factored instead, [`crate::linsys`]) when some
//! coordinates carry no mass: the node-frame coordinates of a floating body's node ties, which
//! only the tie constraints determine.

use clr_ode::linalg::{DenseLu, Singular};

use crate::flexible::FlexBeam;
use crate::floating::FloatingBody;
use crate::runtime::RigidBody;

/// One diagonal block of M.
#[derive(Debug, Clone)]
enum Block {
    /// A rigid body: 1/m, 1/m, 1/I.
    Rigid([f64; 3]),
    /// A ground-fixed beam: banded Cholesky factor of its constant M_ff.
    Beam(Banded),
    /// A floating-frame body (index): dense Cholesky factor of its block, refactored per call.
    Floating(usize, Vec<f64>),
}

/// Workspace of the range-space solve. Sized at the first call; no allocation afterwards.
#[derive(Debug, Default)]
pub(crate) struct RangeSpace {
    /// `None` before the first call; `Some(false)` when the model has coordinates without mass
    /// (the node-frame coordinates of floating-body node ties, or a beam mass matrix that is not
    /// positive definite): then the augmented form is used for every evaluation.
    pub(crate) applicable: Option<bool>,
    /// (first coordinate, size, block).
    blocks: Vec<(usize, usize, Block)>,
    /// Block index of each coordinate.
    block_of: Vec<usize>,
    /// touched[r · n_blocks + k]: constraint row r has non-zeros in block k.
    touched: Vec<bool>,
    /// Y = M⁻¹ Φ_qᵀ, column-major n × m (only touched blocks are valid).
    y: Vec<f64>,
    w: DenseLu,
    lambda_rhs: Vec<f64>,
}

impl RangeSpace {
    fn setup(
        &mut self,
        bodies: &[RigidBody],
        beams: &[FlexBeam],
        floating: &[FloatingBody],
        n: usize,
    ) -> Result<(), Singular> {
        self.blocks.clear();
        for (k, b) in bodies.iter().enumerate() {
            let inv = [1.0 / b.mass, 1.0 / b.mass, 1.0 / b.inertia];
            self.blocks.push((3 * k, 3, Block::Rigid(inv)));
        }
        for fb in beams {
            let entries: Vec<_> = fb.m.entries().collect();
            let band = Banded::factor(fb.n_free(), entries.iter().copied())?;
            self.blocks
                .push((fb.offset, fb.n_free(), Block::Beam(band)));
        }
        for (i, f) in floating.iter().enumerate() {
            let nc = f.n_coords();
            self.blocks
                .push((f.offset, nc, Block::Floating(i, vec![0.0; nc * nc])));
        }
        self.block_of = vec![usize::MAX; n];
        for (k, &(o, size, _)) in self.blocks.iter().enumerate() {
            self.block_of[o..o + size].fill(k);
        }
        if self.block_of.contains(&usize::MAX) {
            // a coordinate without mass: the augmented form must be used
            return Err(Singular);
        }
        Ok(())
    }

    /// Solve G [a; λ] = [Q; b] for `sol` = [a; λ] (on entry [Q; b]), with Φ_q row-major m × n.
    pub(crate) fn solve(
        &mut self,
        (bodies, beams, floating): (&[RigidBody], &[FlexBeam], &[FloatingBody]),
        q: &[f64],
        phiq: &[f64],
        sol: &mut [f64],
    ) -> Result<(), Singular> {
        let n = q.len();
        let m = sol.len() - n;
        match self.applicable {
            Some(false) => return Err(Singular),
            Some(true) => {}
            None => {
                let ok = self.setup(bodies, beams, floating, n).is_ok();
                self.applicable = Some(ok);
                if !ok {
                    return Err(Singular);
                }
            }
        }
        for (o, size, blk) in &mut self.blocks {
            if let Block::Floating(i, l) = blk {
                l.fill(0.0);
                let (o, size) = (*o, *size);
                floating[*i].add_mass(q, &mut |r, c, v| l[(r - o) + (c - o) * size] += v);
                cholesky(size, l)?;
            }
        }
        let (x, b) = sol.split_at_mut(n);
        for (o, size, blk) in &self.blocks {
            blk.solve(&mut x[*o..*o + size]);
        }
        if m == 0 {
            return Ok(());
        }
        let nb = self.blocks.len();
        self.touched.clear();
        self.touched.resize(m * nb, false);
        self.y.resize(n * m, 0.0);
        for r in 0..m {
            for (c, &v) in phiq[r * n..(r + 1) * n].iter().enumerate() {
                if v != 0.0 {
                    self.touched[r * nb + self.block_of[c]] = true;
                }
            }
            for (k, (o, size, blk)) in self.blocks.iter().enumerate() {
                if self.touched[r * nb + k] {
                    let yr = &mut self.y[r * n + o..r * n + o + size];
                    yr.copy_from_slice(&phiq[r * n + o..r * n + o + size]);
                    blk.solve(yr);
                }
            }
        }
        // W = Φ_q Y and the right-hand side Φ_q x − b, block by block
        self.w.resize(m);
        self.lambda_rhs.resize(m, 0.0);
        let w = self.w.matrix_mut();
        w.fill(0.0);
        for r1 in 0..m {
            let mut s = -b[r1];
            for (k, &(o, size, _)) in self.blocks.iter().enumerate() {
                if !self.touched[r1 * nb + k] {
                    continue;
                }
                let p = &phiq[r1 * n + o..r1 * n + o + size];
                s += dot(p, &x[o..o + size]);
                for r2 in 0..m {
                    if self.touched[r2 * nb + k] {
                        w[r1 + r2 * m] += dot(p, &self.y[r2 * n + o..r2 * n + o + size]);
                    }
                }
            }
            self.lambda_rhs[r1] = s;
        }
        self.w.factor()?;
        self.w.solve(&mut self.lambda_rhs);
        b.copy_from_slice(&self.lambda_rhs);
        for (r, &l) in b.iter().enumerate() {
            for (k, &(o, size, _)) in self.blocks.iter().enumerate() {
                if self.touched[r * nb + k] {
                    for (xi, yi) in x[o..o + size]
                        .iter_mut()
                        .zip(&self.y[r * n + o..r * n + o + size])
                    {
                        *xi -= yi * l;
                    }
                }
            }
        }
        Ok(())
    }
}

#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

impl Block {
    /// x ← M_block⁻¹ x.
    fn solve(&self, x: &mut [f64]) {
        match self {
            Block::Rigid(inv) => {
                for (xi, s) in x.iter_mut().zip(inv) {
                    *xi *= s;
                }
            }
            Block::Beam(band) => band.solve(x),
            Block::Floating(_, l) => cholesky_solve(x.len(), l, x),
        }
    }
}

/// Dense Cholesky M = L Lᵀ in place (column-major, lower triangle), Golub & Van Loan,
/// *Matrix Computations*, 4th ed., Algorithm 4.2.1.
fn cholesky(n: usize, a: &mut [f64]) -> Result<(), Singular> {
    for j in 0..n {
        let mut d = a[j + j * n];
        for k in 0..j {
            d -= a[j + k * n] * a[j + k * n];
        }
        if !(d > 0.0 && d.is_finite()) {
            return Err(Singular);
        }
        let d = d.sqrt();
        a[j + j * n] = d;
        for i in j + 1..n {
            let mut s = a[i + j * n];
            for k in 0..j {
                s -= a[i + k * n] * a[j + k * n];
            }
            a[i + j * n] = s / d;
        }
    }
    Ok(())
}

fn cholesky_solve(n: usize, l: &[f64], x: &mut [f64]) {
    for i in 0..n {
        let mut s = x[i];
        for k in 0..i {
            s -= l[i + k * n] * x[k];
        }
        x[i] = s / l[i + i * n];
    }
    for i in (0..n).rev() {
        let mut s = x[i];
        for k in i + 1..n {
            s -= l[k + i * n] * x[k];
        }
        x[i] = s / l[i + i * n];
    }
}

/// Banded Cholesky of a symmetric positive definite matrix with half-bandwidth p (row i of L
/// holds columns i − p … i), Golub & Van Loan, Algorithm 4.3.5: O(n p²) to factor, O(n p) to
/// solve.
#[derive(Debug, Clone)]
pub(crate) struct Banded {
    n: usize,
    p: usize,
    /// l[i · (p + 1) + (j + p − i)] = L[i, j] for i − p ≤ j ≤ i.
    l: Vec<f64>,
}

impl Banded {
    pub(crate) fn factor(
        n: usize,
        entries: impl Iterator<Item = (usize, usize, f64)> + Clone,
    ) -> Result<Self, Singular> {
        let p = entries
            .clone()
            .map(|(r, c, _)| r.abs_diff(c))
            .max()
            .unwrap_or(0);
        let w = p + 1;
        let mut l = vec![0.0; n * w];
        for (r, c, v) in entries {
            if c <= r {
                l[r * w + (c + p - r)] = v;
            }
        }
        let at = |i: usize, j: usize| i * w + (j + p - i);
        for j in 0..n {
            let lo = j.saturating_sub(p);
            let mut d = l[at(j, j)];
            for k in lo..j {
                d -= l[at(j, k)] * l[at(j, k)];
            }
            if !(d > 0.0 && d.is_finite()) {
                return Err(Singular);
            }
            let d = d.sqrt();
            l[at(j, j)] = d;
            for i in j + 1..(j + p + 1).min(n) {
                let lo_i = i.saturating_sub(p);
                let mut s = l[at(i, j)];
                for k in lo_i.max(lo)..j {
                    s -= l[at(i, k)] * l[at(j, k)];
                }
                l[at(i, j)] = s / d;
            }
        }
        Ok(Banded { n, p, l })
    }

    fn solve(&self, x: &mut [f64]) {
        let (n, p, w) = (self.n, self.p, self.p + 1);
        let at = |i: usize, j: usize| i * w + (j + p - i);
        for i in 0..n {
            let lo = i.saturating_sub(p);
            let mut s = x[i];
            for (k, xk) in x[lo..i].iter().enumerate() {
                s -= self.l[at(i, lo + k)] * xk;
            }
            x[i] = s / self.l[at(i, i)];
        }
        for i in (0..n).rev() {
            let hi = (i + p + 1).min(n);
            let mut s = x[i];
            for (k, xk) in x[i + 1..hi].iter().enumerate() {
                s -= self.l[at(i + 1 + k, i)] * xk;
            }
            x[i] = s / self.l[at(i, i)];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A banded SPD matrix (bandwidth 3) solved by the banded Cholesky, checked by
    /// multiplication.
    #[test]
    fn banded_cholesky_solves() {
        let n = 30;
        let val = |i: usize, j: usize| -> f64 {
            match i.abs_diff(j) {
                0 => 6.0 + 0.1 * i as f64,
                1 => -1.0,
                3 => 0.5,
                _ => 0.0,
            }
        };
        let entries: Vec<(usize, usize, f64)> = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j, val(i, j))))
            .filter(|e| e.2 != 0.0)
            .collect();
        let band = Banded::factor(n, entries.iter().copied()).unwrap();
        assert_eq!(band.p, 3);
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).cos()).collect();
        let mut b = vec![0.0; n];
        for &(i, j, v) in &entries {
            b[i] += v * x[j];
        }
        band.solve(&mut b);
        for i in 0..n {
            assert!((b[i] - x[i]).abs() < 1e-13);
        }
        let bad = [(0, 0, -1.0)];
        assert!(Banded::factor(1, bad.iter().copied()).is_err());
    }
}
