//! The spatial run: consistent initial state, integration with clr-ode one accepted step at a
//! time (the planar driver's integrator set-up, [`AnySolver`], and its impact tracker,
//! [`ImpactTracker`]), contact memory commits, located onsets that restart the integrator, and
//! the recorded columns ([`super::output`]).

use clr_ode::{OdeSystem, StopReason};

use super::model::SpatialModel;
use crate::error::MbdError;
use crate::impacts::{ContactProbe, ImpactTracker, Probe};
use crate::sim::{check_options, with_solver, AnySolver, StopEachStep};
use crate::{InitialConditionsMode, JacobianMode, Results, SimOptions};

impl ContactProbe for SpatialModel {
    fn tracked(&self) -> Vec<(usize, String)> {
        self.spheres
            .iter()
            .enumerate()
            .map(|(k, s)| (k, s.name.clone()))
            .collect()
    }
    fn joint_gap(&mut self, k: usize, y: &[f64]) -> f64 {
        self.ws.kin.update(self.bodies.len(), y);
        self.spheres[k].gap(&self.ws.kin)
    }
    fn joint_probe(&mut self, k: usize, y: &[f64]) -> Probe {
        self.ws.kin.update(self.bodies.len(), y);
        let mut zd = nalgebra::Vector3::zeros();
        let z = self.bristle(k, y);
        let r = self.spheres[k].apply(&self.ws.kin, &mut self.memory, z, &mut zd, None);
        Probe::new(r.penetration, r.rate, r.normal_force)
    }
}

impl SpatialModel {
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

    /// Options a spatial run does not have yet: refused, or noted when the choice only
    /// changes the cost.
    fn option_notes(&self, opts: &SimOptions) -> Result<Vec<String>, MbdError> {
        if opts.projection.is_some() {
            return Err(MbdError::Options(
                "`projection` is not available for spatial models yet: leave it out (Baumgarte \
                 stabilization keeps the constraints; violation.position reports them)"
                    .into(),
            ));
        }
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
        if opts.linear_solver == crate::LinearSolver::Sparse {
            notes.push("spatial models: the augmented equations are solved dense".to_string());
        }
        Ok(notes)
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
        let mut notes = self.notes.clone();
        notes.extend(ic_notes);
        notes.extend(self.option_notes(opts)?);
        let with_notes = |mut r: Results| {
            let mut n = notes.clone();
            n.append(&mut r.notes);
            r.notes = n;
            r
        };
        match self.simulate_from_with(opts, &y0, progress) {
            Ok(r) => Ok(with_notes(r)),
            Err(e) => Err(e.map_partial(with_notes)),
        }
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
        self.ws.newton.on = opts.jacobian == JacobianMode::Analytic && self.n_bristle == 0;
        let (nq, nv) = (self.n_q(), self.n_v());
        let mut solver = AnySolver::new(opts, |ode| {
            if opts.scale_velocity_error {
                ode.h_scaled_error(nq..nq + nv)
            } else {
                ode
            }
        });
        let mut run = Run {
            data: Vec::new(),
            y: y0.to_vec(),
            onsets: 0,
            max_viol: 0.0,
            max_drift: 0.0,
            impacts: ImpactTracker::new(self, opts.t0, y0),
        };
        let out = self.integrate(opts, &mut solver, &mut run, progress);
        let stats = with_solver!(&solver, s => s.stats());
        match out {
            Ok(()) => Ok(run.results(self.columns(), stats)),
            Err(Stop::ThroughSocket(what)) => Err(MbdError::Implausible {
                warnings: what,
                count: 1,
                partial: Some(Box::new(run.results(self.columns(), stats))),
            }),
            Err(Stop::Ode(e)) => {
                let sol = e.solution();
                let stats = if sol.stats == Default::default() {
                    stats
                } else {
                    sol.stats
                };
                if sol.y_final.len() == run.y.len() {
                    run.y.copy_from_slice(&sol.y_final);
                }
                Err(MbdError::Failed {
                    partial: Box::new(run.results(self.columns(), stats)),
                    source: e,
                    cause: String::new(),
                })
            }
        }
    }

    fn integrate(
        &mut self,
        opts: &SimOptions,
        solver: &mut AnySolver,
        run: &mut Run,
        progress: &dyn Fn(f64),
    ) -> Result<(), Stop> {
        let mut y_out = vec![0.0; self.dim()];
        let report_every = 0.01 * (opts.t_end - opts.t0);
        let mut last_report = opts.t0;
        self.memory.reset();
        self.commit_contacts(&run.y);
        with_solver!(&mut *solver, s => s.start(self, opts.t0, &run.y, opts.t_end))?;
        let mut recorded = with_solver!(&*solver, s => s.solution().t.len());
        for _ in 0..recorded.max(usize::from(opts.every_step)) {
            self.record(opts.t0, &run.y.clone(), &mut run.data);
        }
        loop {
            let reason =
                with_solver!(&mut *solver, s => s.advance_observed(self, &mut StopEachStep))?;
            let t = with_solver!(&*solver, s => s.solution().t_final);
            run.y
                .copy_from_slice(with_solver!(&*solver, s => &s.solution().y_final));
            let n_out = with_solver!(&*solver, s => s.solution().t.len());
            while recorded < n_out {
                let to = with_solver!(&*solver, s => s.solution().t[recorded]);
                y_out.copy_from_slice(with_solver!(&*solver, s => s.solution().state(recorded)));
                self.record(to, &y_out, &mut run.data);
                recorded += 1;
            }
            let interp =
                |tp: f64, out: &mut [f64]| with_solver!(&*solver, s => s.interpolate(tp, out));
            run.impacts.step(self, (t, &run.y), &interp, &mut y_out);
            self.commit_contacts(&run.y);
            self.check_depth(t, &run.y)?;
            let (pv, _) = self.violation(t, &run.y);
            run.max_viol = run.max_viol.max(pv);
            run.max_drift = run.max_drift.max(self.quaternion_drift(&run.y));
            let onset = match reason {
                StopReason::TerminalEvent(e) => Some(e),
                _ => None,
            };
            if let Some(k) = onset {
                run.onsets += 1;
                // LuGre bristles start undeflected at a new contact (as the planar joints)
                if let Some(o) = self.spheres[k].bristle {
                    let z = self.bristle_offset() + o;
                    run.y[z..z + 3].fill(0.0);
                }
            }
            if opts.every_step {
                self.record(t, &run.y.clone(), &mut run.data);
            }
            let done = reason == StopReason::EndReached || t >= opts.t_end;
            if (done && t > last_report) || t - last_report >= report_every {
                progress(t);
                last_report = t;
            }
            if done {
                return Ok(());
            }
            if onset.is_some() {
                with_solver!(&mut *solver, s => s.restart(self, t, &run.y))?;
            }
        }
    }
}

/// Largest penetration accepted, as a fraction of the ball radius: deeper, the ball's centre is
/// far outside any contact law's range (Hertz assumes δ ≪ R) and the run stops.
const DEPTH_LIMIT: f64 = 0.1;

/// Why the step loop stopped early.
enum Stop {
    Ode(clr_ode::OdeError),
    /// A ball went through its socket (the message says which and what it means).
    ThroughSocket(String),
}

impl From<clr_ode::OdeError> for Stop {
    fn from(e: clr_ode::OdeError) -> Self {
        Stop::Ode(e)
    }
}

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
                return Err(Stop::ThroughSocket(format!(
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
        Ok(())
    }
}

/// What a spatial run has computed so far.
struct Run {
    data: Vec<f64>,
    y: Vec<f64>,
    onsets: usize,
    max_viol: f64,
    max_drift: f64,
    impacts: ImpactTracker,
}

impl Run {
    fn results(&mut self, columns: Vec<String>, stats: clr_ode::Stats) -> Results {
        Results {
            notes: vec![format!(
                "quaternion norm drift: largest |‖p‖ − 1| over the run {:.2e} (every use \
                 normalizes p; column violation.quaternion)",
                self.max_drift
            )],
            columns,
            data: std::mem::take(&mut self.data),
            stats,
            onsets: self.onsets,
            projections: 0,
            max_position_violation: self.max_viol,
            y_final: self.y.clone(),
            impacts: std::mem::replace(&mut self.impacts, ImpactTracker::empty()).into_impacts(),
            initial_conditions: None,
            warnings: Vec::new(),
        }
    }
}
