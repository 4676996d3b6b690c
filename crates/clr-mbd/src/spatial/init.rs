//! Consistent initial conditions of a spatial model, as the planar assembly ([`crate::init`]):
//! Newton's iteration on Φ = 0 with the weighted minimum-norm update
//! Δ = −W Gᵀ(G W Gᵀ)⁻¹Φ in the velocity coordinates (translations and body-frame rotation
//! increments, A ← A exp([Δφ]×)), W = M⁻¹ for given fields and 10⁸ M⁻¹ for solved ones, then
//! one linear solve for the velocities. When a field is left out, spherical clearance joints are
//! held as their ideal counterpart (ball centred in the socket); with every field given they
//! are left out. Redundant equations are found by modified Gram–Schmidt on the rows of
//! G W^{1/2} before any solve.

use nalgebra::Vector3;

use super::constraint::{Prim, PrimKind, Rows};
use super::frame::{exp_map, quaternion_of, rotation};
use super::model::SpatialModel;
use crate::error::MbdError;
use crate::init::{RANK_TOL, SOLVED_WEIGHT};
use crate::CORRECTION_TOL;

const MAX_NEWTON: usize = 50;
/// Position residual accepted by the assembly, m or rad.
const POSITION_TOL: f64 = 1e-12;

/// The assembly's rows: the model's constraints, then, when some initial field is left out, one
/// coincidence per spherical clearance joint (its ideal counterpart). With every field given
/// the counterparts are left out, as in the planar assembly: they would move a ball given off
/// centre, and in a closed loop (a planar mechanism written in space) they are redundant with
/// the joints although the clearance model is not.
struct Assembly {
    prims: Vec<Prim>,
    labels: Vec<String>,
    m: usize,
}

impl SpatialModel {
    fn assembly_rows(&self) -> Assembly {
        let mut prims = self.prims.clone();
        let mut labels = self.row_labels();
        let mut row = self.m;
        let all_given = self.fixed.iter().all(|f| f.iter().all(|&g| g));
        for s in self.spheres.iter().filter(|_| !all_given) {
            prims.push(Prim {
                owner: usize::MAX,
                i: s.i,
                j: s.j,
                kind: PrimKind::Coincide { si: s.si, sj: s.sj },
                row,
            });
            for c in ["x", "y", "z"] {
                labels.push(format!("{} (ideal counterpart, {c})", s.name));
            }
            row += 3;
        }
        Assembly {
            prims,
            labels,
            m: row,
        }
    }

    /// Which velocity coordinates belong to a given field in the position (`phase` 0) or
    /// velocity (1) assembly.
    fn given(&self, phase: usize) -> Vec<bool> {
        self.fixed
            .iter()
            .flat_map(|f| (0..6).map(move |c| f[2 * phase + usize::from(c >= 3)]))
            .collect()
    }

    /// Weights W^{1/2} per velocity coordinate of the position (`phase` 0) or velocity (1)
    /// assembly: kinetic, solved fields 10⁴ times larger.
    fn weights(&self, phase: usize) -> Vec<f64> {
        let mut w = Vec::with_capacity(self.n_v());
        for (b, f) in self.bodies.iter().zip(&self.fixed) {
            for c in 0..6 {
                let kin = if c < 3 {
                    1.0 / b.mass.sqrt()
                } else {
                    1.0 / b.j[(c - 3, c - 3)].sqrt()
                };
                let given = f[2 * phase + usize::from(c >= 3)];
                w.push(if given {
                    kin
                } else {
                    kin * SOLVED_WEIGHT.sqrt()
                });
            }
        }
        w
    }

    fn eval_rows(&mut self, asm: &Assembly, t: f64, y: &[f64], out: &mut AsmWs) {
        let nv = self.n_v();
        self.ws.kin.update(self.bodies.len(), y);
        out.g.fill(0.0);
        let mut rows = Rows {
            phi: &mut out.phi,
            g: &mut out.g,
            phit: &mut out.phit,
            gamma: &mut out.gamma,
            nv,
        };
        for p in &asm.prims {
            p.eval(&self.ws.kin, t, &self.motions, &mut rows);
        }
    }

    /// The consistent initial state at t0 and the notes saying what was solved and changed.
    ///
    /// # Errors
    /// [`MbdError::RedundantConstraints`] or [`MbdError::Assembly`].
    pub fn initial_state(&mut self, t0: f64) -> Result<(Vec<f64>, Vec<String>), MbdError> {
        let asm = self.assembly_rows();
        let (nq, nv) = (self.n_q(), self.n_v());
        let mut y = self.y_given.clone();
        let mut ws = AsmWs::new(asm.m, nv);
        let w = self.weights(0);
        let mut iterations = 0;
        loop {
            self.eval_rows(&asm, t0, &y, &mut ws);
            let res = ws.phi.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            if res <= POSITION_TOL {
                break;
            }
            if iterations == 0 {
                check_rank(&asm, &ws.g, &w)?;
            }
            if iterations == MAX_NEWTON || !res.is_finite() {
                return Err(MbdError::Assembly {
                    t: t0,
                    residual: res,
                    iterations,
                    worst: worst_row(&asm, &ws.phi),
                });
            }
            let rhs: Vec<f64> = ws.phi.iter().map(|v| -v).collect();
            let dx = ws.min_norm_held(&asm, &w, &self.given(0), &rhs)?;
            apply_increment(&mut y[..nq], &dx);
            iterations += 1;
        }
        // velocities: G v = −Φ_t with the least weighted change of the given ones
        let wv = self.weights(1);
        if asm.m > 0 {
            check_rank(&asm, &ws.g, &wv)?;
            let rhs = velocity_residual(&ws, &y[nq..nq + nv]);
            let dv = ws.min_norm_held(&asm, &wv, &self.given(1), &rhs)?;
            for (c, d) in dv.iter().enumerate() {
                y[nq + c] += d;
            }
        }
        let centred = asm.m > self.m;
        let notes = self.report(&self.y_given.clone(), &y, iterations, centred);
        Ok((y, notes))
    }

    /// Project y = (q, v, …) onto Φ = 0 (Newton) and Φ̇ = 0 (one linear solve) at time t in the
    /// kinetic metric W = M⁻¹ (the correction of least kinetic energy, as the planar
    /// [`crate::Model::project`]); the increments act on the velocity coordinates (translations
    /// and body-frame rotations, A ← A exp([Δφ]×)), so the quaternions stay unit. Clearance
    /// joints are not constraints and are left as they are. Returns the Newton iterations.
    ///
    /// # Errors
    /// [`MbdError::Assembly`] when Newton does not reach `tol` (‖Φ‖∞ in m or rad) in 50
    /// iterations, and [`MbdError::RedundantConstraints`] when G loses rank. A `tol` below the
    /// rounding of the positions (16 ε max(1, |q|)) is raised to it.
    pub fn project(&mut self, t: f64, y: &mut [f64], tol: f64) -> Result<usize, MbdError> {
        if self.m == 0 {
            return Ok(0);
        }
        let asm = Assembly {
            prims: self.prims.clone(),
            labels: self.row_labels(),
            m: self.m,
        };
        let (nq, nv) = (self.n_q(), self.n_v());
        let mut ws = AsmWs::new(asm.m, nv);
        // kinetic weights: every coordinate counts as given
        let w: Vec<f64> = self
            .bodies
            .iter()
            .flat_map(|b| {
                (0..6).map(move |c| 1.0 / if c < 3 { b.mass } else { b.j[(c - 3, c - 3)] }.sqrt())
            })
            .collect();
        // a residual at rounding level cannot be reduced further: stop there even when `tol`
        // asks for less (positions of magnitude r carry about ε r)
        let size = y[..nq].iter().fold(1.0f64, |a, v| a.max(v.abs()));
        let tol = tol.max(16.0 * f64::EPSILON * size);
        let mut iterations = 0;
        loop {
            self.eval_rows(&asm, t, y, &mut ws);
            let res = ws.phi.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            if res <= tol {
                break;
            }
            if iterations == MAX_NEWTON || !res.is_finite() {
                return Err(MbdError::Assembly {
                    t,
                    residual: res,
                    iterations,
                    worst: worst_row(&asm, &ws.phi),
                });
            }
            if iterations == 0 {
                check_rank(&asm, &ws.g, &w)?;
            }
            let rhs: Vec<f64> = ws.phi.iter().map(|v| -v).collect();
            let dx = min_norm(&ws.g, nv, &w, &rhs);
            apply_increment(&mut y[..nq], &dx);
            iterations += 1;
        }
        let rhs = velocity_residual(&ws, &y[nq..nq + nv]);
        let dv = min_norm(&ws.g, nv, &w, &rhs);
        for (c, d) in dv.iter().enumerate() {
            y[nq + c] += d;
        }
        Ok(iterations)
    }

    /// The labels of the model's constraint rows ("joint (equation k)").
    fn row_labels(&self) -> Vec<String> {
        let mut labels = Vec::with_capacity(self.m);
        for o in &self.owners {
            for r in o.rows.0..o.rows.1 {
                labels.push(format!("{} (equation {})", o.name, r - o.rows.0 + 1));
            }
        }
        labels
    }

    /// Notes on the fields solved and the given fields changed by the assembly.
    fn report(&self, given: &[f64], y: &[f64], iterations: usize, centred: bool) -> Vec<String> {
        let (nq, _) = (self.n_q(), self.n_v());
        let mut notes = Vec::new();
        if iterations > 0 {
            let held = if centred {
                ", spherical clearance joints held centred (their ideal counterparts)"
            } else {
                ""
            };
            notes.push(format!(
                "initial conditions: positions assembled in {iterations} Newton iteration(s){held}"
            ));
        }
        for (k, name) in self.names.iter().enumerate() {
            let fields: [(&str, &[f64], &[f64]); 4] = [
                (
                    "position (centre of mass, m)",
                    &given[7 * k..7 * k + 3],
                    &y[7 * k..7 * k + 3],
                ),
                (
                    "orientation (quaternion)",
                    &given[7 * k + 3..7 * k + 7],
                    &y[7 * k + 3..7 * k + 7],
                ),
                (
                    "velocity (m/s)",
                    &given[nq + 6 * k..nq + 6 * k + 3],
                    &y[nq + 6 * k..nq + 6 * k + 3],
                ),
                (
                    "angular velocity (body frame, rad/s)",
                    &given[nq + 6 * k + 3..nq + 6 * k + 6],
                    &y[nq + 6 * k + 3..nq + 6 * k + 6],
                ),
            ];
            for (f, (what, g, a)) in fields.iter().enumerate() {
                let changed = g
                    .iter()
                    .zip(a.iter())
                    .any(|(g, a)| (a - g).abs() > CORRECTION_TOL * g.abs().max(1.0));
                if self.fixed[k][f] && changed {
                    notes.push(format!(
                        "initial conditions: {name}.{what} given {g:.9?} changed to {a:.9?} to meet \
                         the joints"
                    ));
                } else if !self.fixed[k][f] {
                    notes.push(format!("initial conditions: {name}.{what} solved: {a:.9?}"));
                }
            }
        }
        notes
    }
}

/// The label of the row with the largest |Φ|.
fn worst_row(asm: &Assembly, phi: &[f64]) -> String {
    let k = (0..asm.m).fold(0, |b, r| if phi[r].abs() > phi[b].abs() { r } else { b });
    asm.labels[k].clone()
}

/// −(G v + Φ_t): what the velocity correction must make up.
fn velocity_residual(ws: &AsmWs, v: &[f64]) -> Vec<f64> {
    let nv = ws.nv;
    (0..ws.phi.len())
        .map(|r| {
            let gv: f64 = ws.g[r * nv..(r + 1) * nv]
                .iter()
                .zip(v)
                .map(|(a, b)| a * b)
                .sum();
            -(gv + ws.phit[r])
        })
        .collect()
}

/// p ← p ⊗ q(Δφ) and r += Δr per body, from the velocity-coordinate increment dx.
fn apply_increment(q: &mut [f64], dx: &[f64]) {
    for k in 0..q.len() / 7 {
        for c in 0..3 {
            q[7 * k + c] += dx[6 * k + c];
        }
        let a = rotation(&q[7 * k + 3..7 * k + 7])
            * exp_map(&Vector3::new(dx[6 * k + 3], dx[6 * k + 4], dx[6 * k + 5]));
        q[7 * k + 3..7 * k + 7].copy_from_slice(&quaternion_of(&a));
    }
}

/// Storage of the assembly's rows.
struct AsmWs {
    phi: Vec<f64>,
    g: Vec<f64>,
    phit: Vec<f64>,
    gamma: Vec<f64>,
    nv: usize,
}

impl AsmWs {
    fn new(m: usize, nv: usize) -> Self {
        Self {
            phi: vec![0.0; m],
            g: vec![0.0; m * nv],
            phit: vec![0.0; m],
            gamma: vec![0.0; m],
            nv,
        }
    }

    /// The least weighted x with G x = rhs, holding the `given` coordinates exactly when the
    /// solved ones alone can meet every row: rows that touch no solved coordinate must then be
    /// met already (|rhs| ≤ 1e-14), and the others must be independent over the solved
    /// coordinates. Otherwise the soft weights `w` move the given coordinates too (by about
    /// their weight's ratio to the solved ones', reported as corrections). Holding them exactly
    /// matters: through the soft weights alone a given crank speed moved by 1e-7 of itself (the
    /// inertia ratio of a light crank to a heavy slider), which the spatial slider–crank against
    /// its minimal-coordinate reference showed.
    fn min_norm_held(
        &self,
        asm: &Assembly,
        w: &[f64],
        given: &[bool],
        rhs: &[f64],
    ) -> Result<Vec<f64>, MbdError> {
        let nv = self.nv;
        let hard: Vec<f64> = w
            .iter()
            .zip(given)
            .map(|(&w, &k)| if k { 0.0 } else { w })
            .collect();
        let touches = |r: usize| (0..nv).any(|c| hard[c] != 0.0 && self.g[r * nv + c] != 0.0);
        let active: Vec<usize> = (0..rhs.len()).filter(|&r| touches(r)).collect();
        let idle_met = (0..rhs.len())
            .filter(|r| !active.contains(r))
            .all(|r| rhs[r].abs() <= 1e-14);
        let sub = Assembly {
            prims: Vec::new(),
            labels: active.iter().map(|&r| asm.labels[r].clone()).collect(),
            m: active.len(),
        };
        let g_sub: Vec<f64> = active
            .iter()
            .flat_map(|&r| self.g[r * nv..(r + 1) * nv].iter().copied())
            .collect();
        if idle_met && dependent_rows(&sub, &g_sub, &hard).is_empty() {
            let rhs_sub: Vec<f64> = active.iter().map(|&r| rhs[r]).collect();
            return Ok(min_norm(&g_sub, nv, &hard, &rhs_sub));
        }
        Ok(min_norm(&self.g, nv, w, rhs))
    }
}

/// x = W² Gᵀ (G W² Gᵀ)⁻¹ rhs with W = diag(w) and G row-major (rhs.len() × nv): the least
/// weighted x with G x = rhs (rows independent: checked by the callers).
fn min_norm(g: &[f64], nv: usize, w: &[f64], rhs: &[f64]) -> Vec<f64> {
    {
        let m = rhs.len();
        let mut lu = clr_ode::linalg::DenseLu::default();
        lu.resize(m);
        let a = lu.matrix_mut();
        for r in 0..m {
            for s in 0..m {
                a[s * m + r] = (0..nv)
                    .map(|c| g[r * nv + c] * w[c] * w[c] * g[s * nv + c])
                    .sum();
            }
        }
        let mut l = rhs.to_vec();
        if m > 0 && lu.factor().is_ok() {
            lu.solve(&mut l);
        } else {
            l.fill(0.0);
        }
        (0..nv)
            .map(|c| w[c] * w[c] * (0..m).map(|r| g[r * nv + c] * l[r]).sum::<f64>())
            .collect()
    }
}

/// Modified Gram–Schmidt on the rows of G W: the rows that depend on earlier ones.
fn check_rank(asm: &Assembly, g: &[f64], w: &[f64]) -> Result<(), MbdError> {
    let dependent = dependent_rows(asm, g, w);
    if dependent.is_empty() {
        return Ok(());
    }
    Err(MbdError::RedundantConstraints {
        rank: asm.m - dependent.len(),
        rows: asm.m,
        involved: format!(
            "{} (in space, a closed loop of revolute joints is over-constrained: replace one \
             revolute by a spherical or universal joint, as in models/examples/spatial_four_bar.toml)",
            dependent.join(", ")
        ),
    })
}

/// The labels of the rows of G W that depend on earlier ones (modified Gram–Schmidt, Golub &
/// Van Loan §5.2.8, relative tolerance [`RANK_TOL`]).
fn dependent_rows(asm: &Assembly, g: &[f64], w: &[f64]) -> Vec<String> {
    let nv = w.len();
    let mut basis: Vec<Vec<f64>> = Vec::new();
    let mut dependent = Vec::new();
    for r in 0..asm.m {
        let mut v: Vec<f64> = (0..nv).map(|c| g[r * nv + c] * w[c]).collect();
        let n0 = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        for b in &basis {
            let d: f64 = v.iter().zip(b).map(|(x, y)| x * y).sum();
            v.iter_mut().zip(b).for_each(|(x, y)| *x -= d * y);
        }
        let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if n <= RANK_TOL * n0.max(f64::MIN_POSITIVE) {
            dependent.push(asm.labels[r].clone());
        } else {
            basis.push(v.iter().map(|x| x / n).collect());
        }
    }
    dependent
}
