//! The spatial run: consistent initial state, then the shared step loop ([`crate::driver`]) with
//! what differs in space (the model is its own integrand, balls are watched for going through
//! their sockets, the quaternion drift is reported); the recorded columns are in
//! [`super::output`].

use clr_ode::OdeSystem;

use super::model::SpatialModel;
use crate::driver::{check_options, drive, AnySolver, Engine, StepEnd, Stop};
use crate::error::MbdError;
use crate::impacts::{ContactProbe, Probe};
use crate::plausible::{finish, implausible};
use crate::{InitialConditionsMode, JacobianMode, Results, SimOptions};

impl ContactProbe for SpatialModel {
    fn tracked(&self) -> Vec<(usize, String)> {
        let balls = self.spheres.iter().map(|s| s.name.clone());
        let groups = self.journal_points.iter().map(|&(j, g)| {
            format!(
                "{}.{}",
                self.journals[j].name,
                super::journal::GROUP_NAMES[g]
            )
        });
        let pairs = self.shape_contacts.iter().map(|c| c.name.clone());
        balls.chain(groups).chain(pairs).enumerate().collect()
    }
    fn joint_gap(&mut self, k: usize, y: &[f64]) -> f64 {
        // the tracker asks for every tracked contact at one state in turn: each journal's gaps
        // (all groups from one geometry) are kept until the state changes
        self.ws.kin.update(self.bodies.len(), y);
        if self.ws.gap_state.as_slice() != y {
            self.ws.gap_state.clear();
            self.ws.gap_state.extend_from_slice(y);
            self.ws.gap_cache.fill(None);
        }
        let ns = self.spheres.len();
        match k.checked_sub(ns).and_then(|p| self.journal_points.get(p)) {
            Some(&(j, g)) => {
                let journal = &self.journals[j];
                let kin = &self.ws.kin;
                self.ws.gap_cache[j].get_or_insert_with(|| journal.gaps(kin))[g].0
            }
            None => self.contact_gap(k),
        }
    }
    fn joint_probe(&mut self, k: usize, y: &[f64]) -> Probe {
        self.ws.kin.update(self.bodies.len(), y);
        let ns = self.spheres.len();
        if let Some(c) = k
            .checked_sub(ns + self.journal_points.len())
            .map(|c| &self.shape_contacts[c])
        {
            let r = c.apply(&self.ws.kin, &mut self.memory, None);
            return Probe::new(r.penetration, r.rate, r.normal_force);
        }
        if k >= ns {
            let (j, g) = self.journal_points[k - ns];
            let r = self.journals[j].apply(&self.ws.kin, &mut self.memory, None);
            return Probe::new(r.penetration[g], r.rate[g], r.normal_force[g]);
        }
        let mut zd = nalgebra::Vector3::zeros();
        let z = self.bristle(k, y);
        let r = self.spheres[k].apply(&self.ws.kin, &mut self.memory, z, &mut zd, None);
        Probe::new(r.penetration, r.rate, r.normal_force)
    }
}

impl SpatialModel {
    /// Number of tracked contacts: one per ball, one per journal contact group, one per shape
    /// contact (its deepest point).
    pub(crate) fn n_contacts(&self) -> usize {
        self.spheres.len() + self.journal_points.len() + self.shape_contacts.len()
    }

    /// Penetration (m) of tracked contact `k` at the kinematics in the workspace: the event
    /// function of its onsets.
    pub(crate) fn contact_gap(&self, k: usize) -> f64 {
        let ns = self.spheres.len();
        let nj = ns + self.journal_points.len();
        if k >= nj {
            self.shape_contacts[k - nj].gap(&self.ws.kin)
        } else if k < ns {
            self.spheres[k].gap(&self.ws.kin)
        } else {
            let (j, g) = self.journal_points[k - ns];
            self.journals[j].gap(&self.ws.kin, g)
        }
    }

    /// Bristle vector of spherical joint `k` in y (zero without LuGre).
    fn bristle(&self, k: usize, y: &[f64]) -> nalgebra::Vector3<f64> {
        match self.spheres[k].bristle {
            Some(o) => {
                let z = self.bristle_offset() + o;
                nalgebra::Vector3::new(y[z], y[z + 1], y[z + 2])
            }
            None => nalgebra::Vector3::zeros(),
        }
    }

    /// Whether a journal joint carries an oil film.
    fn lubricated(&self) -> bool {
        self.journals.iter().any(|j| j.film.is_some())
    }

    /// Options a spatial run does not have yet: refused, or noted when the choice only
    /// changes the cost.
    fn option_notes(&self, opts: &SimOptions) -> Vec<String> {
        let mut notes = Vec::new();
        if opts.solver == crate::SolverKind::Ndf
            && opts.jacobian == JacobianMode::Analytic
            && self.n_bristle > 0
        {
            notes.push(format!(
                "NDF differenced the whole right-hand side for its Newton matrix (jacobian = \
                 \"finite_difference\"): the {} LuGre bristle states have no analytic Jacobian \
                 rows yet",
                self.n_bristle
            ));
        }
        if opts.solver == crate::SolverKind::Ndf
            && opts.jacobian == JacobianMode::Analytic
            && !self.shape_contacts.is_empty()
        {
            notes.push(
                "NDF differenced the whole right-hand side for its Newton matrix (jacobian = \
                 \"finite_difference\"): the shape contacts have no analytic Jacobian blocks"
                    .to_string(),
            );
        }
        if opts.solver == crate::SolverKind::Ndf
            && opts.jacobian == JacobianMode::Analytic
            && self.lubricated()
        {
            notes.push(
                "NDF differenced the whole right-hand side for its Newton matrix (jacobian = \
                 \"finite_difference\"): the film blocks of lubricated journals do not yet match \
                 central differences (docs/lubrication.md §13)"
                    .to_string(),
            );
        }
        if opts.linear_solver == crate::LinearSolver::Sparse {
            notes.push("spatial models: the augmented equations are solved dense".to_string());
        }
        notes
    }

    /// The consistent initial state at `t0` as one row of results, with the assembly's notes
    /// (what `clr view` draws).
    ///
    /// # Errors
    /// [`MbdError::RedundantConstraints`] or [`MbdError::Assembly`].
    pub fn initial_results(&mut self, t0: f64) -> Result<Results, MbdError> {
        let (y, notes) = self.initial_state(t0)?;
        let mut data = Vec::new();
        self.memory.reset();
        self.record(t0, &y, &mut data);
        Ok(Results {
            columns: self.columns(),
            data,
            notes,
            y_final: y,
            ..Default::default()
        })
    }

    /// Simulate from the consistent initial state at `opts.t0` (assembled by
    /// [`SpatialModel::initial_state`]).
    ///
    /// # Errors
    /// Assembly and option errors, and [`MbdError::Failed`] with the partial results when the
    /// integrator fails.
    pub fn simulate(&mut self, opts: &SimOptions) -> Result<Results, MbdError> {
        self.simulate_with(opts, &|_| {})
    }

    /// As [`SpatialModel::simulate`], calling `progress(t)` about every 1 % of the span.
    ///
    /// # Errors
    /// As [`SpatialModel::simulate`].
    pub fn simulate_with(
        &mut self,
        opts: &SimOptions,
        progress: &dyn Fn(f64),
    ) -> Result<Results, MbdError> {
        let (y0, ic_notes) = self.initial_state(opts.t0)?;
        if opts.initial_conditions == InitialConditionsMode::Exact {
            let changed: Vec<&String> = ic_notes
                .iter()
                .filter(|n| n.contains("changed to"))
                .collect();
            if !changed.is_empty() {
                return Err(MbdError::InconsistentInitialConditions {
                    corrected: changed
                        .iter()
                        .map(|s| s.as_str())
                        .collect::<Vec<_>>()
                        .join("; "),
                    field: String::new(),
                });
            }
        }
        let start = self.check_start(opts.t0, &y0)?;
        if opts.strict && !start.is_empty() {
            return Err(implausible(&start, None));
        }
        let scales = self.scales(&y0);
        let mut notes = self.notes.clone();
        notes.extend(ic_notes);
        notes.extend(self.option_notes(opts));
        let with_report = |model: &SpatialModel, mut r: Results| {
            let mut n = notes.clone();
            n.append(&mut r.notes);
            r.notes = n;
            r.warnings = start.clone();
            r.warnings.extend(model.check_end(&r, &scales));
            r
        };
        let run = self.simulate_from_with(opts, &y0, progress);
        finish(self, run, opts.strict, with_report)
    }

    /// Simulate from a given state y0 = (q, v, E_d, W_in, z) of length [`OdeSystem::dim`].
    ///
    /// # Errors
    /// As [`SpatialModel::simulate`].
    pub fn simulate_from_with(
        &mut self,
        opts: &SimOptions,
        y0: &[f64],
        progress: &dyn Fn(f64),
    ) -> Result<Results, MbdError> {
        check_options(opts, y0.len(), self.dim(), || {
            format!(
                "7 + 6 per body, 2 energy quadratures and {} bristle states = {}",
                self.n_bristle,
                self.dim()
            )
        })?;
        self.events_on = opts.contact_events;
        self.ws.newton.on = opts.jacobian == JacobianMode::Analytic
            && self.n_bristle == 0
            && self.shape_contacts.is_empty()
            && !self.lubricated();
        let (nq, nv) = (self.n_q(), self.n_v());
        let mut solver = AnySolver::new(opts, |ode| {
            if opts.scale_velocity_error {
                ode.h_scaled_error(nq..nq + nv)
            } else {
                ode
            }
        });
        drive(self, opts, y0, (&mut solver, &mut ()), Drift(0.0), progress)
    }
}

/// The spatial model in the shared step loop: it is its own integrand (its Newton workspace
/// lives inside), balls are watched for going through their sockets, and the quaternion norm
/// drift is reported.
impl Engine for SpatialModel {
    type Ws = ();
    type Sys<'a> = &'a mut SpatialModel;
    type Watch = Drift;

    fn system<'a>(&'a mut self, _ws: &'a mut ()) -> &'a mut SpatialModel {
        self
    }
    fn reset_memory(&mut self) {
        self.memory.reset();
    }
    fn commit_contacts(&mut self, y: &[f64]) {
        SpatialModel::commit_contacts(self, y);
    }
    fn record(&mut self, t: f64, y: &[f64], out: &mut Vec<f64>) {
        SpatialModel::record(self, t, y, out);
    }
    fn columns(&self) -> Vec<String> {
        SpatialModel::columns(self)
    }
    fn violation(&mut self, t: f64, y: &[f64]) -> f64 {
        SpatialModel::violation(self, t, y).0
    }
    fn watch(&mut self, drift: &mut Drift, t: f64, y: &[f64]) -> Result<(), Stop> {
        self.check_depth(t, y)?;
        drift.0 = drift.0.max(self.quaternion_drift(y));
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
        // LuGre bristles start undeflected at a new contact (as the planar joints); the onset
        // restarts the integrator anyway
        if let Some(o) = onset.and_then(|k| self.spheres.get(k).and_then(|s| s.bristle)) {
            let z = self.bristle_offset() + o;
            y[z..z + 3].fill(0.0);
        }
        match opts.projection {
            // also at t_end: the last recorded state meets the threshold like the others
            Some(tol) if violation > tol => {
                self.project(t, y, tol * 1e-3)?;
                Ok(StepEnd {
                    restart: true,
                    projected: true,
                })
            }
            _ => Ok(StepEnd::default()),
        }
    }
    fn watch_notes(&self, drift: &Drift) -> Vec<String> {
        vec![format!(
            "quaternion norm drift: largest |‖p‖ − 1| over the run {:.2e} (every use \
             normalizes p; column violation.quaternion)",
            drift.0
        )]
    }
    fn failure_cause(&mut self, _t: f64, _y: &[f64]) -> String {
        String::new()
    }
}

/// The largest quaternion norm drift |‖p‖ − 1| over a run so far.
pub(crate) struct Drift(f64);

/// Largest penetration accepted, as a fraction of the ball radius: deeper, the ball's centre is
/// far outside any contact law's range (Hertz assumes δ ≪ R) and the run stops.
const DEPTH_LIMIT: f64 = 0.1;

impl SpatialModel {
    /// Stop when a ball has gone deeper than [`DEPTH_LIMIT`] of its radius into its socket: a
    /// driven loop that cannot close at this pose (the linkage locks, and the driver pushes the
    /// ball through), or a law far too soft for the load; either way the results beyond are
    /// not physics.
    fn check_depth(&mut self, t: f64, y: &[f64]) -> Result<(), Stop> {
        self.ws.kin.update(self.bodies.len(), y);
        for s in &self.spheres {
            let d = s.gap(&self.ws.kin);
            if d > DEPTH_LIMIT * s.r_ball {
                return Err(Stop::Unphysical(format!(
                    "clearance `{}` at t = {t:.6} s: the ball is {d:.3e} m deep in its socket, more \
                     than {:.0} % of its radius: the loop probably cannot close at this pose (a \
                     driven linkage that locks, which an ideal joint would report as singular), \
                     or the normal law is far too soft for the load; check the lengths and the \
                     stiffness",
                    s.name,
                    100.0 * DEPTH_LIMIT
                )));
            }
        }
        for c in &self.shape_contacts {
            let d = c.gap(&self.ws.kin);
            if d > DEPTH_LIMIT * c.size() {
                return Err(Stop::Unphysical(format!(
                    "contact `{}` at t = {t:.6} s: the shapes are {d:.3e} m deep in each other, \
                     more than {:.0} % of the smaller shape's bounding radius {:.3e} m: the \
                     normal law is far too soft for the load, or a step carried one shape \
                     through the other; check the stiffness and the prediction distance",
                    c.name,
                    100.0 * DEPTH_LIMIT,
                    c.size()
                )));
            }
        }
        for jn in &self.journals {
            let state = jn.state(&self.ws.kin);
            let geo = match jn.geometry(&state) {
                Ok(g) => g,
                Err(e) => {
                    return Err(Stop::Unphysical(format!(
                        "clearance `{}` at t = {t:.6} s: {e}",
                        jn.name
                    )))
                }
            };
            for g in 0..jn.n_groups() {
                let d = geo.gap(g).0;
                let r = jn.joint.journal_radius();
                if d > DEPTH_LIMIT * r {
                    return Err(Stop::Unphysical(format!(
                        "clearance `{}` at t = {t:.6} s: the journal is {d:.3e} m deep in its \
                         bearing ({}), more than {:.0} % of its radius: the loop probably cannot \
                         close at this pose, or the normal law is far too soft for the load; \
                         check the lengths and the stiffness",
                        jn.name,
                        super::journal::GROUP_NAMES[g],
                        100.0 * DEPTH_LIMIT
                    )));
                }
            }
        }
        Ok(())
    }
}
