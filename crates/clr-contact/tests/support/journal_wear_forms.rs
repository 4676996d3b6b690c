//! The closed-form wear configurations of the spatial journal joint, shared by the tests
//! (crates/clr-contact/tests/journal_wear.rs) and the verify cases `wear.spatial.*`
//! (xtask/src/verify/wear_spatial.rs): each builds its state, wears a fresh map and returns the
//! map with the measured and the closed-form quantities; the includer compares them. On the
//! bearing of journal_setup.rs (R_b = 10 mm, R_j = 9.9 mm, L = 15 mm), K = 1e-5, H = 2 GPa
//! (typical dry steel, as the planar wear study), the journal spinning at 100 rad/s over 1 ms.

// each includer uses its own subset
#![allow(dead_code)]

use clr_contact::journal::{JournalClearance, JournalFriction, JournalLaws, JournalState, GROUPS};
use clr_contact::journal_wear::{BearingWearMap, JournalWear};
use clr_contact::wear::{ArchardWear, BearingProfile, LineContact};
use clr_contact::{DampingFactor, ElasticLaw, Material, NormalLaw};
use nalgebra::Vector3;

use super::journal_setup::{state, tilted, v3, C, L, RB, RJ};

/// Wear coefficient, –, and hardness, Pa.
pub const K: f64 = 1e-5;
pub const H: f64 = 2e9;
/// Journal spin, rad/s, and the sliding interval, s.
pub const OMEGA: f64 = 100.0;
pub const DT: f64 = 1e-3;
pub const NO_IMPACT: [f64; GROUPS] = [0.0; GROUPS];

type Res<T> = Result<T, String>;

fn s<E: ToString>(e: E) -> String {
    e.to_string()
}

/// Composite modulus of steel on steel, Pa.
pub fn e_star() -> f64 {
    Material::steel().composite_modulus(&Material::steel())
}

/// Undamped radial and thrust laws of `law`, no friction.
pub fn elastic(law: ElasticLaw) -> Res<JournalLaws> {
    let n = NormalLaw::new(law, DampingFactor::None, 1.0).map_err(s)?;
    JournalLaws::new(n, n, JournalFriction::None).map_err(s)
}

/// Hertz internal cylinder of the bearing's radii, steel.
pub fn hertz_law() -> Res<ElasticLaw> {
    ElasticLaw::hertz_internal_cylinder(&Material::steel(), RB, &Material::steel(), RJ).map_err(s)
}

/// The study's Archard law: K, H, E* of steel, Hertz pressure.
pub fn wear() -> Res<JournalWear> {
    JournalWear::new(K, H, e_star()).map_err(s)
}

/// The aligned journal pressed by δ₀ (m) along +x, spinning at [`OMEGA`] about its axis.
pub fn aligned_state(delta0: f64) -> JournalState<f64> {
    state(
        v3(C + delta0, 0.0, 0.0),
        Vector3::z(),
        Vector3::zeros(),
        v3(0.0, 0.0, OMEGA),
    )
}

/// [`aligned_uniform`]'s result.
pub struct Aligned {
    /// The worn map (360 angles × 12 stations).
    pub map: BearingWearMap,
    /// Volume returned by `accumulate`, m³.
    pub volume: f64,
    /// The planar Archard profile of F_N over ds = ω R_j dt, and its volume, m³.
    pub planar: BearingProfile,
    pub planar_volume: f64,
    /// Archard's global law K F_N ω R_j dt / H, m³.
    pub archard: f64,
}

impl Aligned {
    /// Largest |h_m(φ_k) − h_planar(φ_k)| over all stations and angles over the planar peak.
    pub fn worst_station_error(&self) -> f64 {
        let worst = self
            .map
            .stations()
            .iter()
            .flat_map(|st| st.depths().iter().zip(self.planar.depths()))
            .map(|(h, hp)| (h - hp).abs())
            .fold(0.0, f64::max);
        worst / self.planar.max_depth()
    }
}

/// The aligned journal pressed by 2 µm: the line load F_N/L is uniform along the whole bore and
/// the slip ω R_j everywhere, so every station must carry the planar Archard profile of F_N over
/// ds = ω R_j dt, and the volume is Archard's K F_N ω R_j dt / H.
pub fn aligned_uniform() -> Res<Aligned> {
    let joint = JournalClearance::cylindrical(RB, L, RJ, L).map_err(s)?;
    let laws = elastic(hertz_law()?)?;
    let st = aligned_state(2e-6);
    let mut map = BearingWearMap::zero(360, 12, RB, L).map_err(s)?;
    let volume = wear()?
        .accumulate(&mut map, &joint, &laws, &st, &Vector3::x(), &NO_IMPACT, DT)
        .map_err(s)?;
    let f = joint.geometry(&st).map_err(s)?.forces(&laws, &NO_IMPACT);
    let f_n = f.groups[0].normal_force + f.groups[1].normal_force;
    let line = LineContact::new(RB, RJ, L, e_star()).map_err(s)?;
    let mut planar = BearingProfile::zero(360).map_err(s)?;
    let planar_volume = ArchardWear::new(K, H, line)
        .map_err(s)?
        .accumulate(&mut planar, 0.0, f_n, OMEGA * RJ * DT)
        .map_err(s)?;
    Ok(Aligned {
        map,
        volume,
        planar,
        planar_volume,
        archard: K * f_n * OMEGA * RJ * DT / H,
    })
}

/// [`rim_wedge`]'s result.
pub struct Wedge {
    /// The worn map (720 angles × 10 stations).
    pub map: BearingWearMap,
    /// Volume returned by `accumulate`, m³.
    pub volume: f64,
    /// Closed-form volume K ω R_j dt k tan γ (L/2 − z₀)²/(2 L H), m³.
    pub total: f64,
    /// Closed-form worn area of each station, m² (K ω R_j dt ∫_cell p dz / (H Δz)).
    pub areas: Vec<f64>,
    /// Start of the wetted wedge z₀, m.
    pub z0: f64,
}

impl Wedge {
    /// Largest |A_m − A_m,closed| over the rim station's closed-form area.
    pub fn worst_station_error(&self) -> f64 {
        let rim = self.areas[self.areas.len() - 1];
        (0..self.areas.len())
            .map(|m| (self.map.worn_area(m) - self.areas[m]).abs() / rim)
            .fold(0.0, f64::max)
    }
}

/// The journal tilted by γ in the x–z plane and offset along x so that it touches only towards
/// the rim z = +L/2: the section ellipse's long semi-axis R_j/cos γ lies along the offset, so
/// δ(z) = e₀ + z tan γ + R_j/cos γ − R_b exactly (the far vertex; docs/contact.md), a wedge that
/// opens at z₀ = L/10; with the linear law F = kδ (k = 2e8 N/m) the line load is
/// p(z) = k tan γ (z − z₀)/L and the slip of the deepest point is ω R_j. Gauss order 32.
pub fn rim_wedge() -> Res<Wedge> {
    let joint = JournalClearance::cylindrical(RB, L, RJ, 1.2 * L)
        .and_then(|j| j.with_quadrature_order(32))
        .map_err(s)?;
    let k = 2e8;
    let laws = elastic(ElasticLaw::linear(k).map_err(s)?)?;
    let (z0, d_max) = (0.1 * L, 5e-6);
    let tan_g = d_max / (0.5 * L - z0);
    let g = tan_g.atan();
    let e0 = RB - RJ / g.cos() - z0 * tan_g;
    let uj = tilted(g, 0.0);
    let st = state(v3(e0, 0.0, 0.0), uj, Vector3::zeros(), uj * OMEGA);
    let stations = 10;
    let mut map = BearingWearMap::zero(720, stations, RB, L).map_err(s)?;
    let volume = wear()?
        .accumulate(&mut map, &joint, &laws, &st, &Vector3::x(), &NO_IMPACT, DT)
        .map_err(s)?;
    let c = K * OMEGA * RJ * DT / H * k * tan_g / L;
    let prim = |z: f64| c * (z.max(z0) - z0).powi(2) / 2.0;
    let dz = map.station_step();
    let areas = (0..stations)
        .map(|m| {
            let a = -0.5 * L + m as f64 * dz;
            (prim(a + dz) - prim(a)) / dz
        })
        .collect();
    Ok(Wedge {
        map,
        volume,
        total: prim(0.5 * L),
        areas,
        z0,
    })
}

/// [`global_law`]'s result.
pub struct GlobalLaw {
    /// The worn map (360 angles × 15 stations).
    pub map: BearingWearMap,
    /// Volume returned by `accumulate`, m³.
    pub volume: f64,
    /// K ∫ p |v_t| dz dt / H by composite Simpson, m³.
    pub simpson: f64,
}

/// Both rims wetted on opposite sides (a crossed journal), Hertz line load, spin and axial
/// sliding: the worn volume and an independent composite Simpson rule (4000 intervals per
/// wetted region) of K p |v_t| dt / H over the joint's public sections.
pub fn global_law() -> Res<GlobalLaw> {
    let joint = JournalClearance::cylindrical(RB, L, RJ, L).map_err(s)?;
    let law = hertz_law()?;
    let laws = elastic(law)?;
    let uj = tilted(2.0 * (C + 3e-6) / L, 0.3);
    let (vj, wj) = (v3(0.0, 0.0, 0.02), uj * OMEGA + v3(0.0, 0.0, 5.0));
    let st = state(Vector3::zeros(), uj, vj, wj);
    let geo = joint.geometry(&st).map_err(s)?;
    let mut map = BearingWearMap::zero(360, 15, RB, L).map_err(s)?;
    let volume = wear()?
        .accumulate(
            &mut map,
            &joint,
            &laws,
            &st,
            &v3(1.0, 1.0, 0.3),
            &NO_IMPACT,
            DT,
        )
        .map_err(s)?;
    let normal = NormalLaw::new(law, DampingFactor::None, 1.0).map_err(s)?;
    let mut integral = 0.0;
    for k in 0..2 {
        let (lo, hi) = geo.wetted(k).ok_or("a rim region is dry")?;
        let n = 4000;
        let h = (hi - lo) / n as f64;
        for i in 0..=n {
            let sec = geo.section(lo + i as f64 * h);
            if sec.penetration <= 0.0 {
                continue;
            }
            let (xj, nn) = (sec.journal_point.value(), sec.normal.value());
            // the bearing is at rest: the relative velocity is the journal point's
            let vel = vj + wj.cross(&(xj - st.journal_centre.value()));
            let slip = (vel - nn * vel.dot(&nn)).norm();
            let w = match i {
                0 => 1.0,
                _ if i == n => 1.0,
                _ if i % 2 == 1 => 4.0,
                _ => 2.0,
            };
            integral += w * h / 3.0 * normal.force(sec.penetration, vel.dot(&nn), 0.0) / L * slip;
        }
    }
    Ok(GlobalLaw {
        map,
        volume,
        simpson: K * integral * DT / H,
    })
}
