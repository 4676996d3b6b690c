//! The spatial revolute and cylindrical clearance joints: a journal of finite length on body j in
//! a bore of finite length on body i, which can tilt, touch at the bore's rims and (revolute)
//! slide axially against its thrust faces. The geometry, the distributed line contact and the
//! thrust faces are clr-contact's [`JournalClearance`] (module docs there and docs/contact.md
//! "Spatial journal in bearing", after Marques, Isaac, Dourado & Flores, Mech. Mach. Theory 116
//! (2017) 123–144, and Tian, Liu, Machado & Flores, Nonlinear Dyn. 64 (2011) 25–47); this module
//! carries the joint's ends on its bodies and puts the resultant force and moments into Q.
//!
//! A joint has four contact groups ([`GROUPS`]: radial region A at the bore's low-z end, radial
//! region B at its high-z end, thrust face −, thrust face +), each with its own slot in the
//! contact memory, its own onset event and its own row in impacts.csv (`J.radial_a`,
//! `J.radial_b`, `J.thrust_minus`, `J.thrust_plus`; the cylindrical kind has only the radial
//! two).

use nalgebra::Vector3;

use clr_contact::journal::{JournalForces, JournalGeometry, GROUPS};
use clr_contact::journal_film::{FilmLoads, JournalFilm};
use clr_contact::{ContactMemory, JournalClearance, JournalError, JournalLaws, JournalState};
use clr_contact::{FrictionLaw, NormalLaw};

use super::kin::{add_force, add_torque, Kinematics};

/// Names of the contact groups, in clr-contact's group order.
pub(crate) const GROUP_NAMES: [&str; GROUPS] =
    ["radial_a", "radial_b", "thrust_minus", "thrust_plus"];

/// A compiled journal-in-bearing clearance joint.
#[derive(Debug, Clone)]
pub(crate) struct Journal {
    pub(crate) name: String,
    /// Bearing body, bore centre (centre-of-mass frame, m) and bore axis (body frame).
    pub(crate) i: usize,
    pub(crate) si: Vector3<f64>,
    pub(crate) ui: Vector3<f64>,
    /// Journal body, journal centre and axis.
    pub(crate) j: usize,
    pub(crate) sj: Vector3<f64>,
    pub(crate) uj: Vector3<f64>,
    pub(crate) joint: JournalClearance,
    pub(crate) laws: JournalLaws,
    /// The radial and thrust laws and the friction (for plausibility checks).
    pub(crate) radial: NormalLaw,
    pub(crate) thrust: NormalLaw,
    pub(crate) friction: Option<FrictionLaw>,
    /// The oil film of a lubricated joint (added unweighted to the dry contact, clr-contact
    /// `journal_film` module docs).
    pub(crate) film: Option<JournalFilm>,
    /// First of its [`GROUPS`] slots in the contact memory.
    pub(crate) memory: usize,
}

/// What a journal joint gives at one state (its result columns).
#[derive(Debug, Clone, Copy)]
pub struct JournalReport {
    /// Per group ([`GROUP_NAMES`]): penetration, m (the gap when negative; −∞ for a thrust
    /// face of the cylindrical kind).
    pub penetration: [f64; GROUPS],
    /// Per group: the penetration rate δ̇ of its deepest point, m/s (0 for a group the joint
    /// does not have).
    pub rate: [f64; GROUPS],
    /// Per group: integrated normal force, N.
    pub normal_force: [f64; GROUPS],
    /// Resultant contact force on the journal, world, N.
    pub force: Vector3<f64>,
    /// Its moment about the journal centre O_j, world, N·m.
    pub moment: Vector3<f64>,
    /// Tilt γ of the journal axis against the bore axis, rad.
    pub tilt: f64,
    /// Axial offset a = (O_j − O_b)·u_b of the journal centre along the bore axis, m.
    pub axial_offset: f64,
    /// Power dissipated by contact damping and friction, W.
    pub dissipated: f64,
    /// Elastic energy, J.
    pub elastic_energy: f64,
    /// Magnitude of the film force on the journal, N (0 without a film).
    pub film_force: f64,
    /// Minimum film thickness, m (0 without a film).
    pub film_thickness: f64,
}

impl Default for JournalReport {
    fn default() -> Self {
        Self {
            penetration: [f64::NEG_INFINITY; GROUPS],
            rate: [0.0; GROUPS],
            normal_force: [0.0; GROUPS],
            force: Vector3::zeros(),
            moment: Vector3::zeros(),
            tilt: 0.0,
            axial_offset: 0.0,
            dissipated: 0.0,
            elastic_energy: 0.0,
            film_force: 0.0,
            film_thickness: 0.0,
        }
    }
}

impl Journal {
    /// Number of contact groups it tracks: 4 for the revolute kind, 2 (the radial ones) for the
    /// cylindrical kind.
    pub(crate) fn n_groups(&self) -> usize {
        if self.joint.axial_clearance().is_some() {
            GROUPS
        } else {
            2
        }
    }

    /// The world state of the joint's two ends.
    pub(crate) fn state(&self, kin: &Kinematics) -> JournalState<f64> {
        let (ki, kj) = (kin.get(self.i), kin.get(self.j));
        let (ob, oj) = (ki.point(&self.si), kj.point(&self.sj));
        JournalState::new(
            ob,
            ki.a * self.ui,
            ki.point_velocity(&ob),
            ki.w,
            oj,
            kj.a * self.uj,
            kj.point_velocity(&oj),
            kj.w,
        )
    }

    /// Penetration of group `g` (m): the event function of its contact onsets; a large
    /// negative number when the geometry is out of the joint's range (a tilt beyond 60°), which
    /// the depth check stops.
    pub(crate) fn gap(&self, kin: &Kinematics, g: usize) -> f64 {
        self.gaps(kin)[g].0
    }

    /// Penetration and its rate (m, m/s) of every group from one evaluation of the geometry
    /// (the events and the impact tracker ask for all groups at one state, and the geometry
    /// costs about what the forces do).
    pub(crate) fn gaps(&self, kin: &Kinematics) -> [(f64, f64); GROUPS] {
        match self.joint.geometry(&self.state(kin)) {
            Ok(geo) => std::array::from_fn(|g| finite_gap(geo.gap(g))),
            Err(_) => [(-self.joint.bearing_radius(), 0.0); GROUPS],
        }
    }

    /// The geometry at one state.
    ///
    /// # Errors
    /// clr-contact's tilt and non-finite errors.
    pub(crate) fn geometry<'a>(
        &'a self,
        state: &JournalState<f64>,
    ) -> Result<JournalGeometry<'a, f64>, JournalError> {
        self.joint.geometry(state)
    }

    /// Commit the groups' (δ, δ̇) to the contact memory at an accepted step.
    pub(crate) fn commit(&self, kin: &Kinematics, memory: &mut ContactMemory) {
        if let Ok(geo) = self.geometry(&self.state(kin)) {
            geo.commit(memory, self.memory);
        }
    }

    /// Apply the contact forces into Q (when `q` is given) and report. A state out of the
    /// joint's range (tilt beyond 60°, non-finite pose) fills Q with NaN: the integrator
    /// rejects the step, and the depth check names the joint.
    pub(crate) fn apply(
        &self,
        kin: &Kinematics,
        memory: &mut ContactMemory,
        q: Option<&mut [f64]>,
    ) -> JournalReport {
        let state = self.state(kin);
        let geo = match self.geometry(&state) {
            Ok(g) => g,
            Err(_) => {
                if let Some(q) = q {
                    q.fill(f64::NAN);
                }
                return JournalReport::default();
            }
        };
        let f = geo.forces_with_memory(&self.laws, memory, self.memory);
        let mut rep = self.report(&state, &geo, &f);
        let film = match self.film.as_ref().map(|film| film.loads(&state)) {
            None => None,
            Some(Ok(l)) => Some(l),
            Some(Err(_)) => {
                if let Some(q) = q {
                    q.fill(f64::NAN);
                }
                return JournalReport::default();
            }
        };
        if let Some(l) = &film {
            rep.film_force = l.force.value().norm();
            rep.film_thickness = l.min_film_thickness;
            rep.dissipated += film_dissipated(&state, l);
        }
        if let Some(q) = q {
            let (ob, oj) = (state.bearing_centre.value(), state.journal_centre.value());
            let mut force = f.force.value();
            let mut mj = f.journal_moment.value();
            let mut mi = f.bearing_moment.value();
            if let Some(l) = &film {
                force += l.force.value();
                mj += l.journal_moment.value();
                mi += l.bearing_moment.value();
            }
            add_force(q, kin, self.j, &oj, &force);
            add_torque(q, kin, self.j, &mj);
            add_force(q, kin, self.i, &ob, &(-force));
            add_torque(q, kin, self.i, &mi);
        }
        rep
    }

    fn report(
        &self,
        state: &JournalState<f64>,
        geo: &JournalGeometry<'_, f64>,
        f: &JournalForces<f64>,
    ) -> JournalReport {
        let ub = state.bearing_axis.value().normalize();
        let d = state.journal_centre.value() - state.bearing_centre.value();
        let mut rep = JournalReport {
            force: f.force.value(),
            moment: f.journal_moment.value(),
            tilt: geo.tilt(),
            axial_offset: d.dot(&ub),
            dissipated: f.dissipated(),
            elastic_energy: f.elastic_energy(),
            ..Default::default()
        };
        for (g, gf) in f.groups.iter().enumerate().take(self.n_groups()) {
            let gap = geo.gap(g);
            rep.penetration[g] = gap.0;
            rep.rate[g] = finite_gap(gap).1;
            rep.normal_force[g] = gf.normal_force;
        }
        rep
    }
}

/// Power the film dissipates, W: minus the power of its loads on both bodies (force on the
/// journal at O_j, its opposite on the bearing at O_b, the two moments), so that the energy
/// balance closes.
fn film_dissipated(state: &JournalState<f64>, l: &FilmLoads<f64>) -> f64 {
    let force = l.force.value();
    let power = force.dot(&(state.journal_velocity.value() - state.bearing_velocity.value()))
        + l.journal_moment
            .value()
            .dot(&state.journal_angular_velocity.value())
        + l.bearing_moment
            .value()
            .dot(&state.bearing_angular_velocity.value());
    -power
}

/// A thrust face of the cylindrical kind has the gap −∞: the event and memory get a finite
/// "far open" value instead.
fn finite_gap((d, r): (f64, f64)) -> (f64, f64) {
    if d.is_finite() {
        (d, r)
    } else {
        (-1.0, 0.0)
    }
}
