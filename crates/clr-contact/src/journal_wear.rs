//! Archard wear along the axis of the spatial journal joint ([`crate::journal`]): the worn bore
//! as a depth map h_w(φ, z) over angle and axial position, and Archard's law accumulated from the
//! joint's distributed contact (docs/wear.md, "Spatial journal: wear along the axis").
//!
//! - [`BearingWearMap`]: the radial wear depth h_w(φ, z) ≥ 0 (m) of the bore on N angles × M
//!   axial stations of the **bearing body frame**: φ about the bore axis u_b (right-handed) from a
//!   body-fixed reference direction, z along u_b from the bore centre over [−L_b/2, L_b/2]. Each
//!   station is a planar [`BearingProfile`] (periodic monotone cubic Hermite in φ); the stations
//!   sit at the centres z_m = −L_b/2 + (m + ½)Δz of M equal cells, Δz = L_b/M, and the depth is
//!   linear in z between station centres and constant over the half cells at the rims. That
//!   reading integrates to exactly Δz Σ_m h_m (the linear pieces' trapezoids and the two half
//!   cells add up to the cell sum), so the worn volume R_b Δφ Δz Σ h_km is that of the
//!   interpolated surface, as the planar profile's knot sum is. Linear (not cubic) along z
//!   because it is shape preserving without a limiter and the axial profile of a rim contact is
//!   a wedge (a kink at the wetted end), which a cubic would ring at.
//! - [`JournalWear`]: Archard's law Δh = K p ds / H (J.F. Archard, J. Appl. Phys. 24 (1953)
//!   981–988) per section of the journal: at each Gauss node z_k of each wetted radial region
//!   (the nodes of the force evaluation, [`JournalGeometry::visit_radial_nodes`]) the line load
//!   p(z_k) (N/m) spreads over the Hertz line-contact half-width a = √(4 p R/(π E*)) (K.L.
//!   Johnson, *Contact Mechanics*, 1985, §4.3; R = R_b R_j/(R_b − R_j)) around the local contact
//!   angle φ(z_k), exactly as the planar [`ArchardWear`] spreads F_N/L (the same bins and
//!   pressure integrals), and over the node's share of the wetted length (the partial sums of the
//!   quadrature weights, [`RadialNode::share`]) along z, each station receiving the part of the
//!   share inside its cell; the sliding distance is |v_t(z_k)| dt, the slip of the deepest points
//!   there. So the worn volume added is K Σ_k w_k p_k |v_t,k| dt / H, the Gauss rule of Archard's
//!   global law K ∫ p |v_t| dz dt / H, and both spreadings conserve it.
//!
//! Not modelled: the thrust faces' wear (their ring contact is left out: the map is the bore's
//! cylindrical surface only); the journal's wear; the worn geometry in the contact (the pressure
//! is that of the unworn bore, as in the planar studies, Flores 2009; the map is an output).
//! A negative line load (a damping law pulling at separation) wears nothing.
//!
//! Nothing here allocates after the map's construction.

use nalgebra::Vector3;

use crate::error::{positive, ContactError};
use crate::journal::{
    JournalClearance, JournalError, JournalGeometry, JournalLaws, JournalState, RadialNode, GROUPS,
};
use crate::wear::{ArchardWear, BearingProfile, LineContact, PressureDistribution};

const MAP: &str = "bearing wear map";
const WEAR: &str = "journal Archard wear";

/// Errors of the journal wear accumulation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum JournalWearError {
    /// A parameter, sample or the Hertz validity check of the planar law failed.
    #[error(transparent)]
    Contact(#[from] ContactError),
    /// The joint's geometry could not be evaluated at a sample.
    #[error("journal wear, sample {sample}: {source}")]
    Journal {
        /// Sample index (0 for a single state).
        sample: usize,
        /// Why.
        source: JournalError,
    },
}

/// The worn bore h_w(φ, z) ≥ 0 (m) on N angles × M axial stations of the bearing body frame
/// (module docs). The bore surface is ρ(φ, z) = R_b + h_w(φ, z).
#[derive(Debug, Clone, PartialEq)]
pub struct BearingWearMap {
    stations: Vec<BearingProfile>,
    bearing_radius: f64,
    bearing_length: f64,
}

impl BearingWearMap {
    /// The unworn map of a bore of radius R_b and length L_b (m) with N ≥ 8 angles and M ≥ 1
    /// axial stations.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for N < 8, M = 0 or a radius or length not positive
    /// and finite.
    pub fn zero(
        angles: usize,
        stations: usize,
        bearing_radius: f64,
        bearing_length: f64,
    ) -> Result<Self, ContactError> {
        Self::from_fn(angles, stations, bearing_radius, bearing_length, |_, _| 0.0)
    }

    /// A map sampled from h(φ, z) (m) at the knots φ_k = 2πk/N and the station centres z_m.
    ///
    /// # Errors
    /// As [`zero`](Self::zero), and for a negative or non-finite depth.
    pub fn from_fn(
        angles: usize,
        stations: usize,
        bearing_radius: f64,
        bearing_length: f64,
        depth: impl Fn(f64, f64) -> f64,
    ) -> Result<Self, ContactError> {
        positive(MAP, "bearing radius R_b (m)", bearing_radius)?;
        positive(MAP, "bearing length L_b (m)", bearing_length)?;
        if stations == 0 {
            return Err(ContactError::invalid(
                MAP,
                "number of axial stations M (-)",
                0.0,
                "must be at least 1 (one station is the planar profile)",
            ));
        }
        let dz = bearing_length / stations as f64;
        let stations = (0..stations)
            .map(|m| {
                let z = -0.5 * bearing_length + (m as f64 + 0.5) * dz;
                BearingProfile::from_fn(angles, |phi| depth(phi, z))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            stations,
            bearing_radius,
            bearing_length,
        })
    }

    /// Number of angles N.
    pub fn angles(&self) -> usize {
        self.stations[0].len()
    }
    /// Number of axial stations M.
    pub fn station_count(&self) -> usize {
        self.stations.len()
    }
    /// Bore radius R_b, m.
    pub fn bearing_radius(&self) -> f64 {
        self.bearing_radius
    }
    /// Bore length L_b, m.
    pub fn bearing_length(&self) -> f64 {
        self.bearing_length
    }
    /// Cell length Δz = L_b/M, m.
    pub fn station_step(&self) -> f64 {
        self.bearing_length / self.stations.len() as f64
    }
    /// Axial coordinate z_m = −L_b/2 + (m + ½)Δz of station m, m.
    pub fn station_z(&self, m: usize) -> f64 {
        -0.5 * self.bearing_length + (m as f64 + 0.5) * self.station_step()
    }
    /// The angular profile of station m (panics for m ≥ M, as slice indexing).
    pub fn station(&self, m: usize) -> &BearingProfile {
        &self.stations[m]
    }
    /// All stations, from z = −L_b/2 to +L_b/2.
    pub fn stations(&self) -> &[BearingProfile] {
        &self.stations
    }

    /// Wear depth h_w(φ, z), m: the stations' Hermite interpolants at φ (rad, periodic), linear
    /// in z between station centres, constant in the rim half cells; 0 outside |z| ≤ L_b/2 (no
    /// bore there).
    pub fn depth_at(&self, angle: f64, z: f64) -> f64 {
        if z.abs() > 0.5 * self.bearing_length {
            return 0.0;
        }
        let x = (z + 0.5 * self.bearing_length) / self.station_step() - 0.5;
        let last = self.stations.len() - 1;
        if x <= 0.0 {
            return self.stations[0].depth_at(angle);
        }
        if x >= last as f64 {
            return self.stations[last].depth_at(angle);
        }
        let m = x.floor() as usize;
        let t = x - m as f64;
        let (h0, h1) = (
            self.stations[m].depth_at(angle),
            self.stations[m + 1].depth_at(angle),
        );
        h0 + t * (h1 - h0)
    }

    /// Largest knot depth, m (also the largest depth of the interpolant).
    pub fn max_depth(&self) -> f64 {
        self.stations
            .iter()
            .map(BearingProfile::max_depth)
            .fold(0.0, f64::max)
    }

    /// Mean depth over the bore surface, m: (1/(NM)) Σ h_km.
    pub fn mean_depth(&self) -> f64 {
        self.stations
            .iter()
            .map(BearingProfile::mean_depth)
            .sum::<f64>()
            / self.stations.len() as f64
    }

    /// Worn volume V = R_b Δφ Δz Σ h_km, m³ (thin layer, exact for the interpolated surface).
    pub fn worn_volume(&self) -> f64 {
        self.stations
            .iter()
            .map(|s| s.worn_volume(self.bearing_radius, self.station_step()))
            .sum()
    }

    /// Worn cross-section area A(z_m) = R_b Δφ Σ_k h_km (m²) of station m: the axial profile of
    /// the worn volume (V = Δz Σ_m A(z_m)).
    pub fn worn_area(&self, m: usize) -> f64 {
        self.stations[m].worn_volume(self.bearing_radius, 1.0)
    }

    /// Edge concentration, –: the larger of the two rim stations' largest depths over the mean
    /// of all stations' largest depths (1 for wear uniform along the axis, larger when the
    /// rims wear more; NaN for an unworn map).
    pub fn edge_concentration(&self) -> f64 {
        let peaks = self.stations.iter().map(BearingProfile::max_depth);
        let mean = peaks.clone().sum::<f64>() / self.stations.len() as f64;
        let last = self.stations.len() - 1;
        let rim = self.stations[0]
            .max_depth()
            .max(self.stations[last].max_depth());
        if mean > 0.0 {
            rim / mean
        } else {
            f64::NAN
        }
    }

    /// Add `cycles` × `increment` in place (the multi-cycle update of the planar study,
    /// [`BearingProfile::add_scaled`]).
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] when the maps differ in N, M or dimensions, or `cycles`
    /// is negative or not finite; the map is then unchanged.
    pub fn add_scaled(
        &mut self,
        increment: &BearingWearMap,
        cycles: f64,
    ) -> Result<(), ContactError> {
        self.check_same(increment)?;
        // the first station checks `cycles` before anything is added
        for (s, d) in self.stations.iter_mut().zip(&increment.stations) {
            s.add_scaled(d, cycles)?;
        }
        Ok(())
    }

    /// Set every depth to zero.
    pub fn reset(&mut self) {
        self.stations.iter_mut().for_each(BearingProfile::reset);
    }

    fn check_same(&self, o: &BearingWearMap) -> Result<(), ContactError> {
        if o.stations.len() != self.stations.len()
            || o.angles() != self.angles()
            || o.bearing_radius != self.bearing_radius
            || o.bearing_length != self.bearing_length
        {
            return Err(ContactError::invalid(
                MAP,
                "shape of the increment (N·M)",
                (o.angles() * o.station_count()) as f64,
                format!(
                    "must match the map it is added to: {} angles × {} stations, R_b = {} m, \
                     L_b = {} m",
                    self.angles(),
                    self.station_count(),
                    self.bearing_radius,
                    self.bearing_length
                ),
            ));
        }
        Ok(())
    }

    /// Deposit the volume of one node over the stations its share [z_a, z_b] crosses.
    fn deposit(
        &mut self,
        law: &ArchardWear,
        angle: f64,
        line_load: f64,
        slip: f64,
        share: (f64, f64),
    ) {
        let dz = self.station_step();
        let half = 0.5 * self.bearing_length;
        let (za, zb) = (share.0.max(-half), share.1.min(half));
        if zb <= za {
            return;
        }
        let last = self.stations.len() - 1;
        let m_lo = (((za + half) / dz).floor() as usize).min(last);
        let m_hi = (((zb + half) / dz).floor() as usize).min(last);
        for m in m_lo..=m_hi {
            let cell = (-half + m as f64 * dz, -half + (m + 1) as f64 * dz);
            let len = zb.min(cell.1) - za.max(cell.0);
            if len > 0.0 {
                // the planar law of a contact of length Δz: F = p Δz keeps F/L = p (the Hertz
                // width), ds = |v_t| dt · len/Δz makes its volume K p len |v_t| dt / H
                law.deposit(
                    &mut self.stations[m],
                    angle,
                    line_load * dz,
                    slip * len / dz,
                );
            }
        }
    }
}

/// One recorded state of a journal joint for [`JournalWear::accumulate_history`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JournalSample {
    /// Time, s.
    pub time: f64,
    /// Poses and velocities of the two bodies (as [`JournalClearance::geometry`] takes them).
    pub state: JournalState<f64>,
    /// World direction of the bearing body frame's reference direction (φ = 0); projected on
    /// the plane ⟂ u_b, must not be parallel to u_b.
    pub reference: Vector3<f64>,
    /// Impact velocities δ̇⁻ of the four groups (m/s), as the simulation's contact memory had
    /// them ([`JournalGeometry::forces`]).
    pub impact_velocities: [f64; GROUPS],
}

/// Archard's law for the bore of a spatial journal joint (module docs): the planar
/// [`ArchardWear`] (K, H, E* and the pressure distribution) applied per section, its line
/// contact rebuilt for the joint's radii and each station's length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JournalWear {
    law: ArchardWear,
}

impl JournalWear {
    /// From the wear coefficient K (–, in (0, 1]), the hardness H of the bore (Pa, ≥ 1 MPa) and
    /// the composite modulus E* = 1/(σ_b + σ_j) (Pa) of the line contact; Hertz pressure.
    ///
    /// # Errors
    /// As [`ArchardWear::new`] for K and H, [`ContactError::InvalidParameter`] for E*.
    pub fn new(
        coefficient: f64,
        hardness: f64,
        composite_modulus: f64,
    ) -> Result<Self, ContactError> {
        // a nominal geometry: radii and length are replaced per joint and station
        let line = LineContact::new(1.0, 0.5, 1.0, composite_modulus)?;
        Ok(Self {
            law: ArchardWear::new(coefficient, hardness, line)?,
        })
    }

    /// The same law with the pressure spread over the contact width as `distribution` says.
    pub fn with_distribution(mut self, distribution: PressureDistribution) -> Self {
        self.law = self.law.with_distribution(distribution);
        self
    }

    /// Wear coefficient K, –.
    pub fn coefficient(&self) -> f64 {
        self.law.coefficient()
    }
    /// Hardness H, Pa.
    pub fn hardness(&self) -> f64 {
        self.law.hardness()
    }
    /// Composite modulus E*, Pa.
    pub fn composite_modulus(&self) -> f64 {
        self.law.contact().composite_modulus()
    }

    /// The planar law of one station of `map` (contact length Δz).
    fn station_law(
        &self,
        joint: &JournalClearance,
        map: &BearingWearMap,
    ) -> Result<ArchardWear, ContactError> {
        if map.bearing_radius != joint.bearing_radius()
            || map.bearing_length != joint.bearing_length()
        {
            return Err(ContactError::invalid(
                WEAR,
                "wear map bearing radius R_b (m)",
                map.bearing_radius,
                format!(
                    "the map (R_b = {} m, L_b = {} m) must be made for the joint's bore (R_b = {} \
                     m, L_b = {} m)",
                    map.bearing_radius,
                    map.bearing_length,
                    joint.bearing_radius(),
                    joint.bearing_length()
                ),
            ));
        }
        let line = LineContact::new(
            joint.bearing_radius(),
            joint.journal_radius(),
            map.station_step(),
            self.composite_modulus(),
        )?;
        Ok(ArchardWear::new(self.coefficient(), self.hardness(), line)?
            .with_distribution(self.law.distribution()))
    }

    /// Accumulate the wear of one state over the sliding interval `dt` (s, ≥ 0) into `map`;
    /// `reference` is the world direction of the bearing frame's φ = 0 (module docs). Returns the
    /// worn volume added, K Σ_k w_k p_k |v_t,k| dt / H (m³). The map is unchanged on error.
    ///
    /// # Errors
    /// [`JournalWearError::Journal`] when the geometry fails (non-finite state, tilt);
    /// [`JournalWearError::Contact`] for a map of another bore, a negative or non-finite `dt`, a
    /// reference parallel to u_b, or a Hertz half-angle over π/2 (as [`ArchardWear::accumulate`]).
    #[allow(clippy::too_many_arguments)]
    pub fn accumulate(
        &self,
        map: &mut BearingWearMap,
        joint: &JournalClearance,
        laws: &JournalLaws,
        state: &JournalState<f64>,
        reference: &Vector3<f64>,
        impact_velocities: &[f64; GROUPS],
        dt: f64,
    ) -> Result<f64, JournalWearError> {
        let sample = JournalSample {
            time: 0.0,
            state: *state,
            reference: *reference,
            impact_velocities: *impact_velocities,
        };
        if !(dt.is_finite() && dt >= 0.0) {
            return Err(ContactError::invalid(
                WEAR,
                "sliding interval dt (s)",
                dt,
                "must be finite and >= 0",
            )
            .into());
        }
        let law = self.station_law(joint, map)?;
        let geo = self.checked_geometry(joint, laws, &law, &sample, 0)?;
        Ok(self.deposit_state(map, &law, &geo, laws, &sample, dt))
    }

    /// Accumulate a recorded history into `map` by the trapezoidal rule, sample weights
    /// (t_{i+1} − t_{i−1})/2 (half intervals at the ends), as the planar
    /// [`ArchardWear::accumulate_history`]. Returns the worn volume (m³). Every sample is checked
    /// before anything is added, so the map is unchanged on error. Allocation-free.
    ///
    /// # Errors
    /// As [`accumulate`](Self::accumulate) per sample (with its index), and
    /// [`ContactError::InvalidParameter`] for decreasing or non-finite times.
    pub fn accumulate_history(
        &self,
        map: &mut BearingWearMap,
        joint: &JournalClearance,
        laws: &JournalLaws,
        samples: &[JournalSample],
    ) -> Result<f64, JournalWearError> {
        let law = self.station_law(joint, map)?;
        for (i, s) in samples.iter().enumerate() {
            if !s.time.is_finite() || (i > 0 && s.time < samples[i - 1].time) {
                return Err(ContactError::invalid(
                    WEAR,
                    "time t_i (s)",
                    s.time,
                    format!("sample {i}: times must be finite and non-decreasing"),
                )
                .into());
            }
            self.checked_geometry(joint, laws, &law, s, i)?;
        }
        let m = samples.len();
        let mut volume = 0.0;
        for i in 0..m {
            let before = samples[i.saturating_sub(1)].time;
            let after = samples[(i + 1).min(m - 1)].time;
            let geo = joint
                .geometry(&samples[i].state)
                .map_err(|source| JournalWearError::Journal { sample: i, source })?;
            volume +=
                self.deposit_state(map, &law, &geo, laws, &samples[i], 0.5 * (after - before));
        }
        Ok(volume)
    }

    /// The geometry of a sample, its reference checked and the Hertz arc of its largest line
    /// load checked against the planar law's validity.
    fn checked_geometry<'a>(
        &self,
        joint: &'a JournalClearance,
        laws: &JournalLaws,
        law: &ArchardWear,
        s: &JournalSample,
        i: usize,
    ) -> Result<JournalGeometry<'a, f64>, JournalWearError> {
        let geo = joint
            .geometry(&s.state)
            .map_err(|source| JournalWearError::Journal { sample: i, source })?;
        reference_frame(&s.state, &s.reference).ok_or_else(|| {
            ContactError::invalid(
                WEAR,
                "reference direction (|projection on the bore plane|)",
                0.0,
                format!(
                    "sample {i}: the bearing frame's reference direction must not be parallel \
                     to the bore axis"
                ),
            )
        })?;
        let mut p_max = 0.0f64;
        let mut finite = true;
        geo.visit_radial_nodes(laws, &s.impact_velocities, |n| {
            finite &= n.line_load.is_finite() && n.slip.norm().is_finite();
            p_max = p_max.max(n.line_load);
        });
        if !finite {
            return Err(ContactError::invalid(
                WEAR,
                "line load p (N/m)",
                f64::NAN,
                format!("sample {i}: a node's line load or slip is not finite"),
            )
            .into());
        }
        // the planar law's check of the Hertz half-angle a/R_b ≤ π/2 at the largest line load
        law.check_arc(p_max * law.contact().length())?;
        Ok(geo)
    }

    /// Spread the wear of one checked state over `dt` (s); returns the volume, m³.
    fn deposit_state(
        &self,
        map: &mut BearingWearMap,
        law: &ArchardWear,
        geo: &JournalGeometry<'_, f64>,
        laws: &JournalLaws,
        s: &JournalSample,
        dt: f64,
    ) -> f64 {
        let Some((e1, e2)) = reference_frame(&s.state, &s.reference) else {
            return 0.0;
        };
        let mut volume = 0.0;
        geo.visit_radial_nodes(laws, &s.impact_velocities, |n: &RadialNode| {
            let p = n.line_load.max(0.0);
            let slip = n.slip.norm() * dt;
            if p == 0.0 || slip == 0.0 {
                return;
            }
            let angle = n.normal.dot(&e2).atan2(n.normal.dot(&e1));
            map.deposit(law, angle, p, slip, n.share);
            volume += law.volume(p * n.weight, slip);
        });
        volume
    }
}

/// The bearing frame's in-plane unit directions, world: e₁ at φ = 0 and e₂ = u_b × e₁ (φ turns
/// right-handed about u_b); `None` when the reference is parallel to u_b or not finite.
fn reference_frame(
    state: &JournalState<f64>,
    reference: &Vector3<f64>,
) -> Option<(Vector3<f64>, Vector3<f64>)> {
    let ub = state.bearing_axis.value().try_normalize(0.0)?;
    let e1 = (reference - ub * reference.dot(&ub)).try_normalize(1e-12 * reference.norm())?;
    Some((e1, ub.cross(&e1)))
}
