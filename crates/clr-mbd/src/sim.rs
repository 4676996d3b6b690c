//! The planar run: [`Model::simulate`] and its variants, the output columns and the recorder.
//!
//! [`Model::simulate`] integrates y = (q, q̇, E_d, W_in, z) with clr-ode in the shared step loop
//! ([`crate::driver`]), one accepted step at a time: after each step the contact memory is
//! committed (clr-contact memory rule 1), requested output times inside the step are recorded
//! from the dense output, the state is optionally projected onto the constraint manifold, and
//! contact onsets located as terminal events restart the solver at the onset with δ̇⁻ equal to
//! the penetration rate there.

use clr_ode::OdeSystem;

use crate::driver::{check_options, drive, AnySolver, Engine, StepEnd, Stop};
use crate::error::MbdError;
use crate::guide_exit::GuideExits;
use crate::newton::{Integrand, NewtonWs};
pub use crate::options::{InitialConditionsMode, SimOptions, SolverKind};
use crate::plausible::{finish, implausible};
pub use crate::results::Results;
use crate::system::Model;
use crate::JacobianMode;

impl Model {
    /// The output column names (see [`Results`]): the run's own, then those of the
    /// `[[measure]]` items.
    pub fn columns(&self) -> Vec<String> {
        let mut c = self.own_columns();
        c.extend(self.measure_columns().into_iter().map(|(n, _)| n));
        c
    }

    /// The `[[measure]]` columns with their units.
    pub fn measure_columns(&self) -> Vec<(String, &'static str)> {
        (self.measures.iter().flat_map(|m| m.columns.iter().cloned())).collect()
    }

    /// The columns every run writes, before the measures.
    pub(crate) fn own_columns(&self) -> Vec<String> {
        let mut c = vec!["t".to_string()];
        for b in &self.body_names {
            for s in ["x", "y", "theta", "vx", "vy", "omega", "ax", "ay", "alpha"] {
                c.push(format!("{b}.{s}"));
            }
        }
        for b in &self.beams {
            c.extend(b.dof_names());
        }
        for f in &self.floating {
            c.extend(f.coord_names());
        }
        c.extend(self.node_output_columns());
        for j in self.joint_names() {
            for s in ["Fx", "Fy", "M"] {
                c.push(format!("{j}.{s}"));
            }
        }
        for cl in &self.clearances {
            for s in crate::results::CONTACT_COLUMNS.iter().chain(&["ex", "ey"]) {
                c.push(format!("{}.{s}", cl.name));
            }
            if cl.lugre.is_some() {
                c.push(format!("{}.lugre_z", cl.name));
            }
            if cl.film.is_some() {
                c.push(format!("{}.film_force", cl.name));
                c.push(format!("{}.film_thickness", cl.name));
            }
        }
        c.extend(crate::results::ENERGY_COLUMNS.map(String::from));
        c.extend(["violation.position", "violation.velocity"].map(String::from));
        c
    }

    /// The automatic choices of a run with `opts`, in words ([`Results::notes`]).
    pub(crate) fn run_notes(&self, opts: &SimOptions) -> Vec<String> {
        let mut notes = self.notes.clone();
        if opts.solver == SolverKind::Ndf
            && opts.jacobian == JacobianMode::Analytic
            && self.n_bristle_states() > 0
        {
            notes.push(format!(
                "NDF differenced the whole right-hand side for its Newton matrix (jacobian = \
                 \"finite_difference\"): the {} LuGre bristle states have no analytic Jacobian \
                 rows yet",
                self.n_bristle_states()
            ));
        }
        if opts.solver == SolverKind::Ndf
            && opts.jacobian == JacobianMode::Analytic
            && !self.feedback.is_empty()
        {
            notes.push(format!(
                "NDF differenced the whole right-hand side for its Newton matrix: inputs {} are \
                 functions of the state (Model::set_input_function), whose derivatives are not \
                 known",
                self.feedback.names(&self.inputs).join(", ")
            ));
        }
        notes
    }

    /// The assembled initial state at `opts.t0` (with `opts.initial_setup`) as a one-row
    /// [`Results`] (the columns of a run, `initial_conditions` set), without integrating: what
    /// `clr view` draws.
    ///
    /// # Errors
    /// As [`Model::assemble_initial_state_with`].
    pub fn initial_results(&mut self, opts: &SimOptions) -> Result<Results, MbdError> {
        let t0 = opts.t0;
        let (y, ic) = self.assemble_initial_state_with(t0, &opts.initial_setup)?;
        let mut data = Vec::new();
        self.record(t0, &y, &mut data);
        Ok(Results {
            columns: self.columns(),
            data,
            initial_conditions: Some(ic),
            ..Default::default()
        })
    }

    /// Evaluate everything at (t, y) and append one output row.
    pub(crate) fn record(&mut self, t: f64, y: &[f64], out: &mut Vec<f64>) {
        let n = self.n;
        self.load_bristles(y);
        let (q, qd) = y.split_at(n);
        self.solve_accelerations(t, q, qd);
        let row_start = out.len();
        out.push(t);
        for k in 0..self.bodies.len() {
            out.extend_from_slice(&q[3 * k..3 * k + 3]);
            out.extend_from_slice(&qd[3 * k..3 * k + 3]);
            out.extend_from_slice(&self.accelerations()[3 * k..3 * k + 3]);
        }
        for b in &self.beams {
            out.extend_from_slice(&q[b.offset..b.offset + b.n_free()]);
        }
        for f in &self.floating {
            out.extend_from_slice(&q[f.offset..f.offset + f.n_coords()]);
        }
        self.record_node_outputs(q, out);
        for s in self.joint_starts() {
            out.extend_from_slice(&self.reaction(s));
        }
        for (k, c) in self.contacts.iter().enumerate() {
            out.extend_from_slice(&[
                c.penetration,
                c.penetration_rate,
                c.normal_force,
                c.friction_force,
                c.active_points as f64,
                c.eccentricity[0],
                c.eccentricity[1],
            ]);
            if let Some(z) = self.bristle_output(k) {
                out.push(z);
            }
            if self.clearances[k].film.is_some() {
                out.extend_from_slice(&[c.film_force, c.film_thickness]);
            }
        }
        let e = self.energies(q, qd);
        let pv = self.phi.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let vv = self.phid.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let o = self.energy_offset();
        let (dissipated, work_in) = (y[o], y[o + 1]);
        out.extend_from_slice(&[
            e.kinetic,
            e.potential,
            e.elastic,
            e.total(),
            dissipated,
            work_in,
            // constant up to the integration error: what went in is stored or dissipated
            e.total() + dissipated - work_in,
            pv,
            vv,
        ]);
        let row = crate::measure::runtime::Row {
            frames: &self.frames,
            q,
            qd,
            qdd: self.accelerations(),
        };
        for m in &self.measures {
            m.write(&row, out, row_start);
        }
    }

    /// World position (m) of a body-fixed point `local` on body k at coordinates q.
    pub fn point_position(&self, k: usize, local: [f64; 2], q: &[f64]) -> [f64; 2] {
        let b = clr_contact::BodyState::fixed(
            nalgebra::Vector2::new(q[3 * k], q[3 * k + 1]),
            q[3 * k + 2],
        );
        let p = b.point(nalgebra::Vector2::new(local[0], local[1]));
        [p.x, p.y]
    }

    /// Integrate from a consistent initial state ([`Model::initial_state`]) over
    /// [`SimOptions::t0`, `SimOptions::t_end`] and record the outputs.
    ///
    /// # Errors
    /// Invalid options, assembly failures, or [`MbdError::Failed`] when the integrator fails:
    /// it carries every row recorded up to the failure ([`MbdError::partial`]).
    pub fn simulate(&mut self, opts: &SimOptions) -> Result<Results, MbdError> {
        self.simulate_with(opts, &|_| {})
    }

    /// As [`Model::simulate`], calling `progress` with the simulated time t (s) as the run
    /// advances: after the first accepted step that reaches 1 % of the span beyond the previous
    /// call (at most about 100 calls per run, however many steps), and once more with the final
    /// time (t_end when the run completes). The times passed are strictly increasing. The
    /// driver itself allocates nothing per call.
    ///
    /// # Errors
    /// As [`Model::simulate`].
    pub fn simulate_with(
        &mut self,
        opts: &SimOptions,
        progress: &dyn Fn(f64),
    ) -> Result<Results, MbdError> {
        let (y0, ic) = self.assemble_initial_state_with(opts.t0, &opts.initial_setup)?;
        let corrected = ic.corrected();
        if opts.initial_conditions == InitialConditionsMode::Exact && !corrected.is_empty() {
            return Err(inconsistent(&ic, &corrected));
        }
        let start = self.check_start(opts.t0, &y0, &ic)?;
        if opts.strict && !start.is_empty() {
            return Err(implausible(&start, None));
        }
        let scales = self.scales(&y0[..self.n]);
        let with_report = |model: &Model, mut r: Results| {
            let mut notes = ic.notes();
            notes.append(&mut r.notes);
            r.notes = notes;
            r.initial_conditions = Some(ic.clone());
            r.warnings = start.clone();
            r.warnings.extend(model.check_end(&r, &scales));
            r
        };
        let run = self.simulate_from_with(opts, &y0, progress);
        finish(self, run, opts.strict, with_report)
    }

    /// As [`Model::simulate`] from a given state y0 = (q, q̇, E_d, W_in, z) of length
    /// [`OdeSystem::dim`] = 2n + 2 + [`Model::n_bristle_states`] (not modified; project it first
    /// with [`Model::project`] if it may violate the constraints). The recorded
    /// `energy.dissipated` and `energy.work_in` continue from the E_d and W_in given in y0 (J).
    ///
    /// # Errors
    /// As [`Model::simulate`].
    pub fn simulate_from(&mut self, opts: &SimOptions, y0: &[f64]) -> Result<Results, MbdError> {
        self.simulate_from_with(opts, y0, &|_| {})
    }

    /// As [`Model::simulate_from`] with a progress hook (see [`Model::simulate_with`]).
    ///
    /// # Errors
    /// As [`Model::simulate`].
    pub fn simulate_from_with(
        &mut self,
        opts: &SimOptions,
        y0: &[f64],
        progress: &dyn Fn(f64),
    ) -> Result<Results, MbdError> {
        check_options(opts, y0.len(), self.dim(), || {
            format!(
                "2n + 2 + m = {} (q, q̇, dissipated energy, input work, {} LuGre bristle states)",
                self.dim(),
                self.n_bristle_states()
            )
        })?;
        let (mut solver, mut newton) = self.solver(opts);
        let exits = GuideExits::new(self);
        let mut res = drive(self, opts, y0, (&mut solver, &mut newton), exits, progress)?;
        let mut notes = self.run_notes(opts);
        notes.append(&mut res.notes);
        res.notes = notes;
        Ok(res)
    }
}

impl Model {
    /// The integrator and Newton workspace of a run with `opts` (contact events and the linear
    /// solver set on the model as `opts` asks).
    pub(crate) fn solver(&mut self, opts: &SimOptions) -> (AnySolver, NewtonWs) {
        self.events_on = opts.contact_events;
        self.set_linear_solver(opts.linear_solver);
        let solver = AnySolver::new(opts, |mut ode| {
            if opts.scale_velocity_error {
                ode = ode.h_scaled_error(self.n..2 * self.n);
            }
            if let Some(atol) = self.bristle_atol(opts.atol, opts.rtol) {
                ode = ode.atol_vec(atol);
            }
            ode
        });
        let newton = NewtonWs::new(self, opts.jacobian, opts.linear_solver);
        (solver, newton)
    }
}

/// The planar model in the shared step loop: the integrand carries the Newton workspace,
/// sliders on guides are watched for their ends, LuGre bristles reset at open points and new
/// contacts, and the state is projected when `projection` is set.
impl Engine for Model {
    type Ws = NewtonWs;
    type Sys<'a> = Integrand<'a>;
    type Watch = GuideExits;

    fn system<'a>(&'a mut self, ws: &'a mut NewtonWs) -> Integrand<'a> {
        Integrand { model: self, ws }
    }
    fn reset_memory(&mut self) {
        self.memory.reset();
    }
    fn commit_contacts(&mut self, y: &[f64]) {
        Model::commit_contacts(self, y);
    }
    fn record(&mut self, t: f64, y: &[f64], out: &mut Vec<f64>) {
        Model::record(self, t, y, out);
    }
    fn columns(&self) -> Vec<String> {
        Model::columns(self)
    }
    /// The units that the columns' suffixes do not say: the measures' (`<name>.value`) and
    /// the flexible parts' elastic coordinates (`F.q<k>`, m, rad or - by what each is).
    fn units(&self) -> Vec<(String, &'static str)> {
        let elastic = (self.flexible_coordinates().into_iter())
            .flat_map(|f| f.coordinates)
            .map(|c| (c.column, c.unit));
        (self.measure_columns().into_iter())
            .chain(elastic)
            .filter(|(c, u)| crate::results::unit_of(c) != *u)
            .collect()
    }
    fn violation(&mut self, t: f64, y: &[f64]) -> f64 {
        Model::violation(self, t, y).0
    }
    fn watch(&mut self, exits: &mut GuideExits, t: f64, _y: &[f64]) -> Result<(), Stop> {
        exits.observe(self, t);
        Ok(())
    }
    fn step_end(
        &mut self,
        t: f64,
        y: &mut [f64],
        onset: Option<usize>,
        violation: f64,
        opts: &SimOptions,
    ) -> Result<StepEnd, Stop> {
        // LuGre bristles: undeflected at open points and at a new contact (crate::lugre)
        let mut end = StepEnd {
            restart: self.reset_bristles(y, onset),
            projected: false,
        };
        if let Some(tol) = opts.projection {
            // also at t_end: the last recorded state satisfies the threshold like the others
            if violation > tol {
                self.project(t, y, tol * 1e-3)?;
                end = StepEnd {
                    restart: true,
                    projected: true,
                };
            }
        }
        Ok(end)
    }
    fn watch_notes(&self, exits: &GuideExits) -> Vec<String> {
        exits.notes(self)
    }
    fn failure_cause(&mut self, t: f64, y: &[f64]) -> String {
        Model::failure_cause(self, t, y)
    }
}

/// The error of `exact` initial conditions for the given changes (body, coordinate, given,
/// assembled).
pub(crate) fn inconsistent(
    ic: &crate::InitialConditions,
    corrected: &[(&str, &'static str, f64, f64)],
) -> MbdError {
    let list: Vec<String> = corrected
        .iter()
        .map(|(b, c, g, a)| format!("{b}.{c} from {g:.9e} to {a:.9e}"))
        .collect();
    MbdError::InconsistentInitialConditions {
        corrected: list.join(", "),
        field: corrected
            .first()
            .map_or(String::new(), |(b, c, _, _)| ic.field_of(b, c)),
    }
}
