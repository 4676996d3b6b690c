//! The initial state of a mechanism with clearance joints: which coordinates the assembly
//! solves, from which constraints, with the clearance joints replaced by their ideal
//! counterparts ([`crate::ideal`]), and which coordinates nothing determines.
//!
//! Assembly (Adams' initial-conditions analysis, with the clearance joints closed as in the
//! published studies): positions by Newton's method on Φ(q, t0) = 0 and velocities by the linear
//! solve of Φ_q q̇ = −Φ_t, both as the correction of least weighted norm in which the given
//! coordinates weigh 1e8 times more than the ones left out ([`crate::init`]). In the default
//! [`InitialState::Ideal`] the rows of every clearance joint's ideal counterpart join Φ for the
//! phase (positions or velocities) in which one of its two bodies has a coordinate left out, or
//! when the joint names an initial eccentricity; the rows are removed afterwards.
//!
//! A coordinate c left out is *determined* when the unit vector e_c lies in the row space of
//! Φ_q restricted to the coordinates left out (every admissible change of them keeps c), which
//! the modified Gram–Schmidt basis of those rows tells (Golub & Van Loan, *Matrix Computations*,
//! 4th ed., §5.2.8).

use crate::error::MbdError;
use crate::init::{InitialConditions, Metric, Phase, COORDINATE_NAMES, RANK_TOL};
pub use crate::initial_data::{
    unit_of, IdealCounterpart, InitialSetup, InitialState, SolvedCoordinate,
};
use crate::runtime::{Con, GROUND_ID};
use crate::system::Model;

/// Residual of e_c after its projection on the row space above which coordinate c counts as
/// undetermined (rows and e_c have unit norm, so rounding leaves ~1e-15).
const UNDETERMINED_TOL: f64 = 1e-8;

impl Model {
    /// As [`Model::assemble_initial_state`] with explicit settings: ideal counterparts of the
    /// clearance joints or not, and the bodies deliberately left free.
    ///
    /// # Errors
    /// [`MbdError::RedundantConstraints`], [`MbdError::Assembly`], or
    /// [`MbdError::UndeterminedCoordinates`] naming every coordinate left out that nothing
    /// determines (bodies in `free_bodies` excepted).
    pub fn assemble_initial_state_with(
        &mut self,
        t0: f64,
        setup: &InitialSetup,
    ) -> Result<(Vec<f64>, InitialConditions), MbdError> {
        for b in &setup.free_bodies {
            if self.body_index(b).is_none() {
                return Err(MbdError::Invalid {
                    path: "solver.free_bodies".into(),
                    message: format!(
                        "`{b}` is not a rigid body of the model (bodies: {})",
                        self.body_names.join(", ")
                    ),
                });
            }
        }
        let given = self.given_state();
        let mut y = given.clone();
        let n = self.n;
        self.check_rank(t0, &y[..n])?;
        let ideal = setup.state == InitialState::Ideal;
        if self.fixed.iter().flatten().all(|&f| f)
            && self.flexible_all_fixed()
            && (!ideal || self.initial_offsets.is_empty())
        {
            // everything given: the kinetic metric (the same correction, one velocity pass)
            // (elastic coordinates held)
            let iterations = match self.project_in(t0, &mut y, 1e-12, Metric::Given) {
                Ok(it) => it,
                Err(e) => return Err(self.flexible_assembly_error(t0, &given, e)),
            };
            let report = InitialConditions {
                newton_iterations: iterations,
                bodies: self.body_corrections(&given, &y),
                flexible: self.flexible_corrections(&given, &y),
                ..Default::default()
            };
            return Ok((y, report));
        }
        let mut counterparts = if ideal {
            self.counterparts()
        } else {
            Vec::new()
        };
        let mut solved = Vec::new();
        let mut undetermined = Vec::new();
        let mut iterations = 0;
        for phase in [Phase::Position, Phase::Velocity] {
            let rows: Vec<Con> = counterparts
                .iter()
                .filter(|(c, _)| c.used(phase))
                .flat_map(|(_, rows)| rows.iter().cloned())
                .collect();
            let saved = self.push_rows(rows);
            self.keep_rows_on_solved(t0, &y[..n], saved, phase);
            let dropped = self.drop_dependent_rows(t0, &y[..n], saved);
            for (c, _) in counterparts.iter_mut() {
                let prefix = format!("{} (", c.element);
                c.dropped
                    .extend(dropped.iter().filter(|d| d.starts_with(&prefix)).cloned());
            }
            let run = self.assemble_phase(t0, &given, &mut y, phase);
            if let Ok(it) = run {
                iterations += it;
                let (s, u) = self.solved_coordinates(t0, &y, phase, &setup.free_bodies);
                solved.extend(s);
                undetermined.extend(u);
            }
            self.pop_rows(saved);
            if let Err(e) = run {
                return Err(self.flexible_assembly_error(t0, &given, e));
            }
        }
        if !undetermined.is_empty() {
            return Err(undetermined_error(&undetermined));
        }
        let report = InitialConditions {
            newton_iterations: iterations,
            bodies: self.body_corrections(&given, &y),
            flexible: self.flexible_corrections(&given, &y),
            counterparts: counterparts.into_iter().map(|(c, _)| c).collect(),
            solved_coordinates: solved,
        };
        Ok((y, report))
    }

    /// Positions (Newton, then two passes that put the fixed coordinates back: the weights
    /// leave about 1e-8 of the correction on them even where the solved ones suffice) or
    /// velocities (the same for the linear solve). Returns the Newton iterations.
    fn assemble_phase(
        &mut self,
        t0: f64,
        given: &[f64],
        y: &mut [f64],
        phase: Phase,
    ) -> Result<usize, MbdError> {
        let mut lu = clr_ode::linalg::DenseLu::default();
        let metric = Metric::FixedFirst;
        let mut it = 0;
        for pass in 0..3 {
            if pass > 0 {
                self.restore_fixed_in(given, y, phase);
            }
            match phase {
                Phase::Position => {
                    let k = self.newton_positions(t0, y, 1e-12, metric, &mut lu)?;
                    if pass == 0 {
                        it = k;
                    }
                }
                Phase::Velocity => self.project_velocities(t0, y, metric, &mut lu)?,
            }
        }
        Ok(it)
    }

    /// The ideal counterparts of the contact elements, each with its rows, and the phases in
    /// which it takes part: positions when a coordinate of position of its bodies is left out
    /// or its initial offset is given, velocities when a velocity is left out.
    fn counterparts(&self) -> Vec<(IdealCounterpart, Vec<Con>)> {
        let free = |frame: usize, phase: usize| -> bool {
            frame != GROUND_ID
                && self
                    .fixed
                    .get(frame)
                    .is_some_and(|f| f[3 * phase..3 * phase + 3].iter().any(|x| !x))
        };
        self.clearances
            .iter()
            .filter_map(|c| {
                let given = self.initial_offsets.get(&c.name).copied();
                let offset = given.unwrap_or_default();
                let rows = crate::ideal::counterpart(c, offset)?;
                let positions = given.is_some() || free(c.i, 0) || free(c.j, 0);
                let velocities = free(c.i, 1) || free(c.j, 1);
                let info = IdealCounterpart {
                    element: c.name.clone(),
                    positions,
                    velocities,
                    offset: [offset.x, offset.y],
                    dropped: Vec::new(),
                };
                (positions || velocities).then_some((info, rows))
            })
            .collect()
    }

    /// Append `extra` constraints after the model's rows and size the workspace; returns the
    /// (rows, items) to restore with [`Model::pop_rows`].
    fn push_rows(&mut self, extra: Vec<Con>) -> (usize, usize) {
        let saved = (self.m, self.cons.len());
        for mut c in extra {
            c.row = self.m;
            self.m += c.rows();
            self.cons.push(c);
        }
        self.size_constraint_workspace();
        saved
    }

    /// Remove the rows appended by [`Model::push_rows`].
    fn pop_rows(&mut self, (m, items): (usize, usize)) {
        self.cons.truncate(items);
        self.m = m;
        self.size_constraint_workspace();
    }

    fn size_constraint_workspace(&mut self) {
        let (n, m) = (self.n, self.m);
        for v in [
            &mut self.phi,
            &mut self.phid,
            &mut self.phit,
            &mut self.gamma,
        ] {
            v.resize(m, 0.0);
        }
        self.phiq.resize(m * n, 0.0);
    }

    /// Keep only the appended rows that involve a coordinate of `phase` left out of the
    /// description, or that impose a given initial offset: a row on given coordinates alone
    /// would move what the user gave (a slider given resting on its guide's lower surface stays
    /// there while its angle left out is solved from the aligned guide).
    fn keep_rows_on_solved(&mut self, t: f64, q: &[f64], saved: (usize, usize), phase: Phase) {
        let n = self.n;
        let zeros = vec![0.0; n];
        self.eval_constraints(t, q, &zeros);
        let solved = self.solved_columns(phase);
        let explicit = |c: &Con| {
            phase == Phase::Position
                && self
                    .initial_offsets
                    .keys()
                    .any(|e| c.name == format!("{e} ({})", crate::ideal::SUFFIX))
        };
        let kept: Vec<Con> = self.cons[saved.1..]
            .iter()
            .filter(|c| {
                let row = &self.phiq[c.row * n..(c.row + 1) * n];
                let norm = row.iter().fold(0.0f64, |a, x| a.max(x.abs()));
                explicit(c) || solved.iter().any(|&col| row[col].abs() > 1e-12 * norm)
            })
            .cloned()
            .collect();
        self.pop_rows(saved);
        self.push_rows(kept);
    }

    /// Drop the appended rows (after `saved`) that depend on the rows before them at q (each
    /// appended item has one row); returns their labels.
    fn drop_dependent_rows(&mut self, t: f64, q: &[f64], saved: (usize, usize)) -> Vec<String> {
        let dependent = self.dependent_rows(t, q);
        let labels = self.row_labels();
        let drop: Vec<usize> = dependent
            .iter()
            .map(|(r, _)| *r)
            .filter(|&r| r >= saved.0)
            .collect();
        if drop.is_empty() {
            return Vec::new();
        }
        let kept: Vec<Con> = self.cons[saved.1..]
            .iter()
            .filter(|c| !drop.contains(&c.row))
            .cloned()
            .collect();
        self.pop_rows(saved);
        self.push_rows(kept);
        drop.iter().map(|&r| labels[r].clone()).collect()
    }

    /// The columns (of q, or of q̇ for velocities) of the rigid-body coordinates of `phase`
    /// left out of the description.
    fn solved_columns(&self, phase: Phase) -> Vec<usize> {
        let slot0 = if phase == Phase::Position { 0 } else { 3 };
        (0..self.fixed.len())
            .flat_map(|k| (0..3).map(move |s| (k, s)))
            .filter(|&(k, s)| !self.fixed[k][slot0 + s])
            .map(|(k, s)| 3 * k + s)
            .collect()
    }

    /// Set the fixed coordinates of `phase` in y back to their given values.
    fn restore_fixed_in(&self, given: &[f64], y: &mut [f64], phase: Phase) {
        let base = if phase == Phase::Position { 0 } else { self.n };
        let slot0 = if phase == Phase::Position { 0 } else { 3 };
        for (k, fixed) in self.fixed.iter().enumerate() {
            for s in 0..3 {
                if fixed[slot0 + s] {
                    y[base + 3 * k + s] = given[base + 3 * k + s];
                }
            }
        }
        // the frames of floating flexible bodies (their elastic coordinates weigh 0: never moved)
        for f in &self.floating {
            for s in 0..3 {
                if f.fixed[slot0 + s] {
                    y[base + f.offset + s] = given[base + f.offset + s];
                }
            }
        }
    }

    /// The rigid-body coordinates of `phase` left out of the description, with the items that
    /// determine them, and those nothing determines (outside `free`, as `body.coordinate`).
    fn solved_coordinates(
        &mut self,
        t: f64,
        y: &[f64],
        phase: Phase,
        free: &[String],
    ) -> (Vec<SolvedCoordinate>, Vec<String>) {
        let (n, m) = (self.n, self.m);
        let slot0 = if phase == Phase::Position { 0 } else { 3 };
        let cols = self.solved_columns(phase);
        if cols.is_empty() {
            return (Vec::new(), Vec::new());
        }
        let (q, qd) = y.split_at(n);
        self.eval_constraints(t, q, &qd[..n]);
        let basis = row_space(&self.phiq, n, m, &cols);
        let owner: Vec<&str> = self
            .cons
            .iter()
            .flat_map(|c| std::iter::repeat_n(c.name.as_str(), c.rows()))
            .collect();
        let mut solved = Vec::new();
        let mut undetermined = Vec::new();
        for (a, &col) in cols.iter().enumerate() {
            let (k, s) = (col / 3, col % 3);
            let residual = 1.0 - basis.iter().map(|b| b[a] * b[a]).sum::<f64>();
            let determined = residual <= UNDETERMINED_TOL;
            let body = self.body_names[k].clone();
            if !determined && !free.contains(&body) {
                undetermined.push(format!("{body}.{}", COORDINATE_NAMES[slot0 + s]));
            }
            let mut from: Vec<String> = Vec::new();
            if determined {
                for (r, name) in owner.iter().enumerate() {
                    if self.phiq[r * n + col] != 0.0 && !from.iter().any(|f| f == name) {
                        from.push((*name).to_string());
                    }
                }
            }
            let value = y[if phase == Phase::Position {
                col
            } else {
                n + col
            }];
            solved.push(SolvedCoordinate {
                body,
                coordinate: COORDINATE_NAMES[slot0 + s],
                value,
                from,
                undetermined: !determined,
            });
        }
        (solved, undetermined)
    }
}

/// An orthonormal basis (modified Gram–Schmidt) of the rows of the m × n matrix `a` restricted
/// to the columns `cols`.
fn row_space(a: &[f64], n: usize, m: usize, cols: &[usize]) -> Vec<Vec<f64>> {
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for r in 0..m {
        let mut v: Vec<f64> = cols.iter().map(|&c| a[r * n + c]).collect();
        let norm0 = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm0 == 0.0 {
            continue;
        }
        for b in &basis {
            let p: f64 = b.iter().zip(&v).map(|(x, y)| x * y).sum();
            v.iter_mut().zip(b).for_each(|(vi, bi)| *vi -= p * bi);
        }
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm > RANK_TOL * norm0 {
            v.iter_mut().for_each(|x| *x /= norm);
            basis.push(v);
        }
    }
    basis
}

fn undetermined_error(list: &[String]) -> MbdError {
    let mut bodies: Vec<String> = Vec::new();
    for item in list {
        let b = format!("\"{}\"", item.split('.').next().unwrap_or(item));
        if !bodies.contains(&b) {
            bodies.push(b);
        }
    }
    let field = list.first().map_or(String::new(), |c| {
        let (body, coord) = c.split_once('.').unwrap_or((c, ""));
        let name = match coord {
            "x" | "y" => "position",
            "theta" => "angle",
            "vx" | "vy" => "velocity",
            _ => "angular_velocity",
        };
        format!("{body}.{name}")
    });
    MbdError::UndeterminedCoordinates {
        coordinates: list.join(", "),
        bodies: bodies.join(", "),
        field,
    }
}

impl IdealCounterpart {
    fn used(&self, phase: Phase) -> bool {
        match phase {
            Phase::Position => self.positions,
            Phase::Velocity => self.velocities,
        }
    }
}
