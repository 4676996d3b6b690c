//! Consistent initial conditions, coordinate projection and the redundancy check.
//!
//! Positions: Newton's iteration on Φ(q, t) = 0 with the mass-weighted minimum-norm update
//! Δq = −W Φ_qᵀ (Φ_q W Φ_qᵀ)⁻¹ Φ, W = M⁻¹ (the correction of least kinetic metric; E. Bayo &
//! R. Ledesma, Nonlinear Dyn. 9 (1996) 113–130, and W. Blajer, Multibody Syst. Dyn. 7 (2002)
//! 265–284, use the same projector). Velocities: one linear solve of Φ_q q̇ = −Φ_t with the same
//! projector applied to the given velocities.
//! Rank deficiency of Φ_q is detected by modified Gram–Schmidt on the rows of Φ_q W^{1/2}
//! (Golub & Van Loan, *Matrix Computations*, 4th ed., §5.2.8) before any solve.

use clr_ode::linalg::DenseLu;

use crate::error::MbdError;
use crate::system::Model;

/// Relative tolerance of the rank test: a row whose Gram–Schmidt residual is below this
/// fraction of its norm is a combination of the rows before it.
pub(crate) const RANK_TOL: f64 = 1e-9;
/// Largest number of Newton iterations of the position assembly.
const MAX_NEWTON: usize = 50;
/// Weight of a solved (not given) coordinate relative to a fixed one in the assembly metric:
/// the correction goes to the solved coordinates whenever they can satisfy the constraints,
/// and a fixed one moves by about 1e-8 of the correction only where they cannot.
pub(crate) const SOLVED_WEIGHT: f64 = 1e8;
/// Relative size, against max(1, |value|), of a change of a fixed coordinate that the
/// initial-conditions report counts as a correction (and `exact` mode refuses).
pub const CORRECTION_TOL: f64 = 1e-9;

/// Which of q (positions) or q̇ (velocities) an assembly step corrects.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Phase {
    /// Positions and angles (Φ = 0).
    Position,
    /// Velocities (Φ̇ = 0).
    Velocity,
}

/// How the assembly weighs the coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Metric {
    /// The kinetic metric W = M⁻¹ for every coordinate (drift projection during a run).
    Kinetic,
    /// Initial conditions with every coordinate given: W = M⁻¹, except that floating flexible
    /// bodies weigh as [`Model::flexible_weight_sqrt`] says (elastic coordinates held).
    Given,
    /// W = M⁻¹ for fixed coordinates and [`SOLVED_WEIGHT`]·M⁻¹ for solved ones (initial
    /// conditions; floating flexible bodies as [`Model::flexible_weight_sqrt`] says).
    FixedFirst,
}

impl Model {
    /// W^{1/2} for coordinate c (inverse square root of its mass or inertia).
    fn w_sqrt(&self, c: usize) -> f64 {
        if let Some(b) = self.bodies.get(c / 3) {
            return 1.0 / if c % 3 == 2 { b.inertia } else { b.mass }.sqrt();
        }
        // beam DOF: the diagonal of its mass matrix (constraints never involve them yet)
        for fb in &self.beams {
            let (o, nf) = (fb.offset, fb.n_free());
            if (o..o + nf).contains(&c) {
                let a = c - o;
                return 1.0 / fb.m.get(a, a).abs().max(f64::MIN_POSITIVE).sqrt();
            }
        }
        1.0
    }

    /// Check that Φ_q(q, t) has full row rank; otherwise report the dependent equations.
    ///
    /// # Errors
    /// [`MbdError::RedundantConstraints`] with the equations involved.
    pub fn check_rank(&mut self, t: f64, q: &[f64]) -> Result<(), MbdError> {
        let dependent = self.dependent_rows(t, q);
        if dependent.is_empty() {
            return Ok(());
        }
        let labels = self.row_labels();
        let text: Vec<String> = dependent
            .iter()
            .map(|(r, used)| {
                let others: Vec<&str> = used.iter().map(|&k| labels[k].as_str()).collect();
                format!(
                    "{} depends on [{}]",
                    labels[*r],
                    if others.is_empty() {
                        "nothing: the equation is empty".to_string()
                    } else {
                        others.join(", ")
                    }
                )
            })
            .collect();
        Err(MbdError::RedundantConstraints {
            rank: self.m - dependent.len(),
            rows: self.m,
            involved: text.join("; "),
        })
    }

    /// The rows of Φ_q(q, t) that are combinations of the rows before them, each with the
    /// earlier rows it involves (modified Gram–Schmidt on the rows of Φ_q W^{1/2}).
    pub(crate) fn dependent_rows(&mut self, t: f64, q: &[f64]) -> Vec<(usize, Vec<usize>)> {
        let (n, m) = (self.n, self.m);
        let zeros = vec![0.0; n];
        self.eval_constraints(t, q, &zeros);
        let mut basis: Vec<Vec<f64>> = Vec::new();
        let mut basis_row: Vec<usize> = Vec::new();
        let mut dependent = Vec::new();
        for r in 0..m {
            let mut v: Vec<f64> = (0..n)
                .map(|c| self.phiq[r * n + c] * self.w_sqrt(c))
                .collect();
            let norm0 = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            let mut used = Vec::new();
            for (b, &br) in basis.iter().zip(basis_row.iter()) {
                let p: f64 = b.iter().zip(v.iter()).map(|(x, y)| x * y).sum();
                if p.abs() > RANK_TOL * norm0 {
                    used.push(br);
                }
                for (vi, bi) in v.iter_mut().zip(b.iter()) {
                    *vi -= p * bi;
                }
            }
            let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            if norm <= RANK_TOL * norm0.max(f64::MIN_POSITIVE) {
                dependent.push((r, used));
            } else {
                v.iter_mut().for_each(|x| *x /= norm);
                basis.push(v);
                basis_row.push(r);
            }
        }
        dependent
    }

    /// The square root of the assembly weight W_cc of coordinate c in `phase` under `metric`.
    fn weight_sqrt(&self, c: usize, phase: Phase, metric: Metric) -> f64 {
        if metric == Metric::Kinetic {
            return self.w_sqrt(c);
        }
        let fixed_first = metric == Metric::FixedFirst;
        if let Some(w) = self.flexible_weight_sqrt(c, phase == Phase::Velocity, fixed_first) {
            return w;
        }
        let w = self.w_sqrt(c);
        let k = c / 3;
        if !fixed_first || k >= self.fixed.len() {
            return w;
        }
        let slot = c % 3 + if phase == Phase::Velocity { 3 } else { 0 };
        if self.fixed[k][slot] {
            w
        } else {
            SOLVED_WEIGHT.sqrt() * w
        }
    }

    /// Factor S = Φ_q W Φ_qᵀ (m × m) from the current Φ_q.
    fn factor_s(&self, lu: &mut DenseLu, phase: Phase, metric: Metric) -> bool {
        let (n, m) = (self.n, self.m);
        lu.resize(m);
        let s = lu.matrix_mut();
        for a in 0..m {
            for b in 0..m {
                let mut v = 0.0;
                for c in 0..n {
                    let w = self.weight_sqrt(c, phase, metric);
                    v += self.phiq[a * n + c] * self.phiq[b * n + c] * w * w;
                }
                s[a + b * m] = v;
            }
        }
        lu.factor().is_ok()
    }

    /// x ← x − W Φ_qᵀ S⁻¹ r (r overwritten).
    fn correct(&self, lu: &mut DenseLu, r: &mut [f64], x: &mut [f64], ph: (Phase, Metric)) {
        let n = self.n;
        lu.solve(r);
        for (c, xc) in x.iter_mut().enumerate() {
            let w = self.weight_sqrt(c, ph.0, ph.1).powi(2);
            let mut v = 0.0;
            for (a, ra) in r.iter().enumerate() {
                v += self.phiq[a * n + c] * ra;
            }
            *xc -= w * v;
        }
    }

    /// Project y = (q, q̇, …) onto Φ = 0 (Newton) and Φ̇ = 0 (one linear solve) at time t, in
    /// the kinetic metric (the correction of least kinetic energy). Returns the number of Newton
    /// iterations.
    ///
    /// # Errors
    /// [`MbdError::Assembly`] when Newton does not reach `tol` (‖Φ‖∞ in m or rad), and
    /// [`MbdError::RedundantConstraints`] when Φ_q loses rank.
    pub fn project(&mut self, t: f64, y: &mut [f64], tol: f64) -> Result<usize, MbdError> {
        self.project_in(t, y, tol, Metric::Kinetic)
    }

    pub(crate) fn project_in(
        &mut self,
        t: f64,
        y: &mut [f64],
        tol: f64,
        metric: Metric,
    ) -> Result<usize, MbdError> {
        if self.m == 0 {
            return Ok(0);
        }
        let mut lu = DenseLu::default();
        let it = self.newton_positions(t, y, tol, metric, &mut lu)?;
        self.project_velocities(t, y, metric, &mut lu)?;
        Ok(it)
    }

    /// Newton's iteration on Φ(q, t) = 0 for the positions of y, in `metric`; returns the
    /// number of iterations.
    pub(crate) fn newton_positions(
        &mut self,
        t: f64,
        y: &mut [f64],
        tol: f64,
        metric: Metric,
        lu: &mut DenseLu,
    ) -> Result<usize, MbdError> {
        let (n, m) = (self.n, self.m);
        if m == 0 {
            return Ok(0);
        }
        let zeros = vec![0.0; n];
        let mut r = vec![0.0; m];
        let mut it = 0;
        let pos = (Phase::Position, metric);
        loop {
            let (q, _) = y.split_at_mut(n);
            self.eval_constraints(t, q, &zeros);
            let res = self.phi.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            if res <= tol {
                break;
            }
            if it >= MAX_NEWTON || !res.is_finite() {
                return Err(self.assembly_error(t, res, it));
            }
            if !self.factor_s(lu, pos.0, pos.1) {
                self.check_rank(t, &y[..n])?;
                return Err(MbdError::Assembly {
                    t,
                    residual: res,
                    iterations: it,
                    worst: "singular constraint Jacobian".into(),
                });
            }
            r.copy_from_slice(&self.phi);
            self.correct(lu, &mut r, q, pos);
            it += 1;
        }
        Ok(it)
    }

    /// Φ̇(q, q̇) = Φ_q q̇ + Φ_t is affine in q̇, so one correction is exact up to rounding; with
    /// the fixed-first metric (weights 1e8 apart, S less well conditioned) a second one removes
    /// that rounding.
    pub(crate) fn project_velocities(
        &mut self,
        t: f64,
        y: &mut [f64],
        metric: Metric,
        lu: &mut DenseLu,
    ) -> Result<(), MbdError> {
        let n = self.n;
        if self.m == 0 {
            return Ok(());
        }
        let mut r = vec![0.0; self.m];
        let passes = if metric == Metric::FixedFirst { 2 } else { 1 };
        let (q, rest) = y.split_at_mut(n);
        let qd = &mut rest[..n];
        self.eval_constraints(t, q, qd);
        if !self.factor_s(lu, Phase::Velocity, metric) {
            self.check_rank(t, q)?;
            let residual = self.phid.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            if metric != Metric::Kinetic && !self.floating.is_empty() {
                // singular only with the elastic rates held (a floating body whose frame the
                // joints hold more than once): nothing to correct when the given velocities
                // already satisfy them, else the caller names the body
                if residual <= 1e-12 {
                    return Ok(());
                }
                return Err(MbdError::Assembly {
                    t,
                    residual,
                    iterations: 0,
                    worst: "singular velocity constraints with the elastic rates held".into(),
                });
            }
        }
        for _ in 0..passes {
            r.copy_from_slice(&self.phid);
            self.correct(lu, &mut r, qd, (Phase::Velocity, metric));
            self.eval_constraints(t, q, qd);
        }
        Ok(())
    }

    /// The assembly failure at (t, residual, iterations), naming the most violated equation.
    fn assembly_error(&self, t: f64, residual: f64, iterations: usize) -> MbdError {
        let (k, _) = self
            .phi
            .iter()
            .enumerate()
            .fold((0, 0.0f64), |(bk, bv), (k, v)| {
                if v.abs() > bv {
                    (k, v.abs())
                } else {
                    (bk, bv)
                }
            });
        MbdError::Assembly {
            t,
            residual,
            iterations,
            worst: self.row_labels()[k].clone(),
        }
    }

    /// A consistent initial state y0 = (q, q̇) at t0 from the poses and velocities given to the
    /// builder: rank check, Newton on positions to ‖Φ‖∞ ≤ 1e-12, then velocities. Coordinates
    /// the description left out are solved first ([`Body`](crate::desc::Body)); see
    /// [`Model::assemble_initial_state`] for the report of what changed.
    ///
    /// # Errors
    /// [`MbdError::RedundantConstraints`] or [`MbdError::Assembly`].
    pub fn initial_state(&mut self, t0: f64) -> Result<Vec<f64>, MbdError> {
        self.assemble_initial_state(t0).map(|(y, _)| y)
    }

    /// As [`Model::initial_state`], with the report of every coordinate the assembly solved or
    /// changed (Adams' initial-conditions analysis). Positions are assembled by Newton's
    /// method on Φ(q, t0) = 0 and velocities by the linear solve of Φ_q q̇ = −Φ_t, both as the
    /// correction of least weighted norm: the coordinates the description left out weigh 1e8
    /// times less than the given ones, so they take the correction whenever they can satisfy
    /// the constraints alone (a rod's angular velocity left out is solved from the crank's
    /// motion and the given velocities are kept).
    ///
    /// # Errors
    /// [`MbdError::RedundantConstraints`] or [`MbdError::Assembly`].
    pub fn assemble_initial_state(
        &mut self,
        t0: f64,
    ) -> Result<(Vec<f64>, InitialConditions), MbdError> {
        self.assemble_initial_state_with(t0, &crate::initial_data::InitialSetup::default())
    }

    /// The given and assembled coordinates of every rigid body.
    pub(crate) fn body_corrections(&self, given: &[f64], y: &[f64]) -> Vec<BodyInitialState> {
        let n = self.n;
        (0..self.bodies.len())
            .map(|k| {
                let at = |c: usize| -> [f64; 2] {
                    let i = if c < 3 { 3 * k + c } else { n + 3 * k + c - 3 };
                    [given[i], y[i]]
                };
                BodyInitialState {
                    body: self.body_names[k].clone(),
                    coordinates: std::array::from_fn(|c| {
                        let [g, a] = at(c);
                        CoordinateInitialState {
                            fixed: self.fixed[k][c],
                            given: g,
                            assembled: a,
                        }
                    }),
                }
            })
            .collect()
    }

    /// Constraint violations (‖Φ‖∞ in m or rad, ‖Φ̇‖∞ in m/s or rad/s) at (t, y).
    pub fn violation(&mut self, t: f64, y: &[f64]) -> (f64, f64) {
        let n = self.n;
        let (q, qd) = y.split_at(n);
        self.eval_constraints(t, q, qd);
        let a = self.phi.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let b = self.phid.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        (a, b)
    }
}

pub use crate::initial_data::{COORDINATE_NAMES, COORDINATE_UNITS};

/// One initial coordinate of a rigid body before and after the assembly.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoordinateInitialState {
    /// True when the description gave it (fixed), false when it was left out (solved).
    pub fixed: bool,
    /// The value the description implies (0 when left out), in the unit of
    /// [`COORDINATE_UNITS`].
    pub given: f64,
    /// The value after the assembly (the start of the run).
    pub assembled: f64,
}

impl CoordinateInitialState {
    /// assembled − given.
    pub fn correction(&self) -> f64 {
        self.assembled - self.given
    }

    /// A fixed coordinate that moved by more than [`CORRECTION_TOL`]·max(1, |given|).
    pub fn is_corrected(&self) -> bool {
        self.fixed && self.correction().abs() > CORRECTION_TOL * self.given.abs().max(1.0)
    }
}

/// A rigid body's initial centre-of-mass coordinates before and after the assembly.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyInitialState {
    /// Body name.
    pub body: String,
    /// x, y, θ, v_x, v_y, ω in the order of [`COORDINATE_NAMES`].
    pub coordinates: [CoordinateInitialState; 6],
}

/// What the assembly of consistent initial conditions did ([`Model::assemble_initial_state`]).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct InitialConditions {
    /// Newton iterations on the positions (0: the given positions already closed every loop).
    pub newton_iterations: usize,
    /// Every rigid body, in definition order.
    pub bodies: Vec<BodyInitialState>,
    /// The ideal counterparts of clearance joints the assembly used (empty when every
    /// coordinate was given, or under `initial_state = "as_given"`).
    pub counterparts: Vec<crate::initial_data::IdealCounterpart>,
    /// Every coordinate left out of the description, with its assembled value and the items
    /// that determined it (positions first, then velocities).
    pub solved_coordinates: Vec<crate::initial_data::SolvedCoordinate>,
    /// Every floating flexible body, in definition order: the coordinates of its frame origin
    /// (x, y, θ and rates; not its centre of mass). Its elastic coordinates are not listed:
    /// the assembly never moves them (they start undeformed and at rest).
    pub flexible: Vec<BodyInitialState>,
}

impl InitialConditions {
    /// The coordinates left out of the description, with the values the assembly chose:
    /// (body, coordinate name, value).
    pub fn solved(&self) -> Vec<(&str, &'static str, f64)> {
        self.each()
            .filter(|(_, _, c)| !c.fixed)
            .map(|(b, name, c)| (b, name, c.assembled))
            .collect()
    }

    /// The given coordinates the assembly changed beyond [`CORRECTION_TOL`]: (body,
    /// coordinate name, given, assembled).
    pub fn corrected(&self) -> Vec<(&str, &'static str, f64, f64)> {
        self.each()
            .filter(|(_, _, c)| c.is_corrected())
            .map(|(b, name, c)| (b, name, c.given, c.assembled))
            .collect()
    }

    fn each(&self) -> impl Iterator<Item = (&str, &'static str, &CoordinateInitialState)> {
        self.bodies.iter().chain(&self.flexible).flat_map(|b| {
            b.coordinates
                .iter()
                .zip(COORDINATE_NAMES)
                .map(move |(c, name)| (b.body.as_str(), name, c))
        })
    }

    /// The report in words: one sentence for the ideal counterparts used, one listing every
    /// coordinate left out with its value (zeros included) and the items it was solved from, one
    /// for coordinates nothing determined (free bodies), and one for the corrected ones (empty
    /// when every coordinate was given and consistent).
    pub fn notes(&self) -> Vec<String> {
        let unit = crate::initial_data::unit_of;
        let mut notes = Vec::new();
        if !self.counterparts.is_empty() {
            let list: Vec<String> = self
                .counterparts
                .iter()
                .map(|c| {
                    let phases = match (c.positions, c.velocities) {
                        (true, true) => "positions and velocities",
                        (true, false) => "positions",
                        _ => "velocities",
                    };
                    let dropped = if c.dropped.is_empty() {
                        String::new()
                    } else {
                        format!("; redundant rows left out: {}", c.dropped.join(", "))
                    };
                    format!(
                        "{} ({phases}, offset [{:.3e}, {:.3e}] m{dropped})",
                        c.element, c.offset[0], c.offset[1]
                    )
                })
                .collect();
            notes.push(format!(
                "initial conditions: clearance joints closed as their ideal joints while solving \
                 (initial_state = \"ideal\"), then released: {}",
                list.join(", ")
            ));
        }
        let (solved, free): (Vec<_>, Vec<_>) = self
            .solved_coordinates
            .iter()
            .partition(|c| !c.undetermined);
        // the frames of floating flexible bodies left out (their sources are not traced)
        let frames = self.flexible.iter().flat_map(|b| {
            b.coordinates
                .iter()
                .zip(COORDINATE_NAMES)
                .filter(|(c, _)| !c.fixed)
                .map(move |(c, name)| {
                    format!(
                        "{}.{name} = {:.6e} {} [frame]",
                        b.body,
                        c.assembled,
                        unit(name)
                    )
                })
        });
        let list: Vec<String> = solved
            .iter()
            .map(|c| {
                format!(
                    "{}.{} = {:.6e} {} [from {}]",
                    c.body,
                    c.coordinate,
                    c.value,
                    unit(c.coordinate),
                    c.from.join(", ")
                )
            })
            .chain(frames)
            .collect();
        if !list.is_empty() {
            notes.push(format!(
                "initial conditions: not given in the model, solved from the constraints: {}",
                list.join(", ")
            ));
        }
        if !free.is_empty() {
            let list: Vec<String> = free
                .iter()
                .map(|c| {
                    format!(
                        "{}.{} = {:.6e} {}",
                        c.body,
                        c.coordinate,
                        c.value,
                        unit(c.coordinate)
                    )
                })
                .collect();
            notes.push(format!(
                "initial conditions: determined by nothing, kept at their start values (bodies in \
                 [solver] free_bodies): {}",
                list.join(", ")
            ));
        }
        let corrected = self.corrected();
        if !corrected.is_empty() {
            let list: Vec<String> = corrected
                .iter()
                .map(|(b, c, g, a)| {
                    format!("{b}.{c} {g:.6e} → {a:.6e} {} (Δ = {:.3e})", unit(c), a - g)
                })
                .collect();
            notes.push(format!(
                "initial conditions: given values changed to satisfy the constraints \
                 (initial_conditions = \"exact\" refuses this): {}",
                list.join(", ")
            ));
        }
        notes
    }
}
