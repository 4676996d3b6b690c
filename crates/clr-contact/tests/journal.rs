//! The spatial journal-in-bearing clearance joint (`clr_contact::journal`) against central
//! differences, a 200-point quadrature reference and energy balances. Sources and tolerances at
//! each test. The comparisons with brute-force sampling, the planar revolute joint, the
//! closed-form tilt and thrust penetration and the continuity sweeps are verify cases
//! (`cargo xtask verify contact.spatial.revolute`, xtask/src/verify/spatial_journal.rs).

// the dual numbers and the difference quotients index directions by number on purpose
#![allow(clippy::needless_range_loop)]

use std::ops::{Add, Div, Mul, Neg, Sub};

use clr_contact::journal::{
    JournalClearance, JournalError, JournalFriction, JournalLaws, JournalState, Real, Section,
    GROUPS, RADIAL_A, RADIAL_B, THRUST_MINUS, THRUST_PLUS, V3,
};
use clr_contact::{DampingFactor, ElasticLaw, FrictionLaw, LuGre, Material, NormalLaw};
use nalgebra::{Rotation3, Unit, Vector3};

#[path = "support/journal_setup.rs"]
mod journal_setup;
use journal_setup::{state, still, tilted, v3, C, L, RB, RJ};

fn hertz_ln() -> NormalLaw {
    NormalLaw::new(
        ElasticLaw::hertz_internal_cylinder(&Material::steel(), RB, &Material::steel(), RJ)
            .unwrap(),
        DampingFactor::LankaraniNikravesh,
        0.5,
    )
    .unwrap()
}

fn elastic(law: ElasticLaw) -> NormalLaw {
    NormalLaw::new(law, DampingFactor::None, 1.0).unwrap()
}

fn laws(radial: NormalLaw, friction: Option<FrictionLaw>) -> JournalLaws {
    let f = friction.map_or(JournalFriction::None, JournalFriction::Law);
    JournalLaws::new(radial, radial, f).unwrap()
}

/// A reference integration of the radial forces: 200-point Gauss–Legendre in plain z on each
/// wetted interval, the integrand written here from `section` and the laws (module docs: −p n at
/// the midpoint, p δ′ u_b at the journal point, and −(±Φ(δ_end)/L_c) u_b at a wetted journal end).
fn reference_force(
    joint: &JournalClearance,
    st: &JournalState<f64>,
    law: &NormalLaw,
    vdm: f64,
) -> (Vector3<f64>, Vector3<f64>) {
    let (x, w) = gauss_legendre_200();
    let g = joint.geometry(st).unwrap();
    let lc = joint.contact_length();
    let (oj, ub) = (
        st.journal_centre.value(),
        st.bearing_axis.value().normalize(),
    );
    let (mut force, mut moment) = (Vector3::zeros(), Vector3::zeros());
    let (lo_end, hi_end) = g.overlap().unwrap();
    for k in [RADIAL_A, RADIAL_B] {
        let Some((lo, hi)) = g.wetted(k) else {
            continue;
        };
        let mut add = |f: Vector3<f64>, at: Vector3<f64>| {
            force += f;
            moment += (at - oj).cross(&f);
        };
        for (xi, wi) in x.iter().zip(&w) {
            let z = lo + (hi - lo) * xi;
            let s: Section<f64> = g.section(z);
            if s.penetration <= 0.0 {
                continue;
            }
            let (xj, xb, n) = (
                s.journal_point.value(),
                s.bearing_point.value(),
                s.normal.value(),
            );
            let vj =
                st.journal_velocity.value() + st.journal_angular_velocity.value().cross(&(xj - oj));
            let p = law.force(s.penetration, vj.dot(&n), vdm) / lc * wi * (hi - lo);
            add(-n * p, 0.5 * (xj + xb));
            add(ub * (p * s.slope), xj);
        }
        let end = g.section(if k == 0 { lo_end } else { hi_end });
        let journal_end = if k == 0 {
            lo_end > -0.5 * joint.bearing_length()
        } else {
            hi_end < 0.5 * joint.bearing_length()
        };
        if journal_end && end.penetration > 0.0 {
            // −(±Φ/L_c) ∇z_e, the pose gradient of the end from central differences of `overlap`
            let sign = if k == 0 { -1.0 } else { 1.0 };
            let c = -sign * law.elastic_energy(end.penetration) / lc;
            let grad = end_gradient(joint, st, k);
            force += grad[2] * c;
            moment += grad[3] * c;
        }
    }
    (force, moment)
}

/// ∂z_e/∂(O_b, θ_b, O_j, θ_j) of the overlap's low (k = 0) or high end by central differences
/// (steps 1e-9 m, 1e-8 rad: truncation (h/e)² ≈ 1e-10, rounding 1e-18 m/h ≈ 1e-9 m/m).
fn end_gradient(joint: &JournalClearance, st: &JournalState<f64>, k: usize) -> [Vector3<f64>; 4] {
    let base = Base {
        ob: st.bearing_centre.value(),
        ub: st.bearing_axis.value().normalize(),
        oj: st.journal_centre.value(),
        uj: st.journal_axis.value().normalize(),
        vel: [
            st.bearing_velocity.value(),
            st.bearing_angular_velocity.value(),
            st.journal_velocity.value(),
            st.journal_angular_velocity.value(),
        ],
    };
    let end = |d: usize, h: f64| {
        let o = joint
            .geometry(&base.moved(d, h))
            .unwrap()
            .overlap()
            .unwrap();
        if k == 0 {
            o.0
        } else {
            o.1
        }
    };
    let mut g = [Vector3::zeros(); 4];
    for d in 0..12 {
        let h = if (d / 3) % 2 == 0 { 1e-9 } else { 1e-8 };
        g[d / 3][d % 3] = (end(d, h) - end(d, -h)) / (2.0 * h);
    }
    g
}

/// Gauss–Legendre, 200 points on [0, 1] (Golub–Welsch-free: Newton on P_200 from Tricomi's
/// guesses), checked below by integrating x^k exactly.
fn gauss_legendre_200() -> (Vec<f64>, Vec<f64>) {
    let n = 200;
    let (mut x, mut w) = (vec![0.0; n], vec![0.0; n]);
    for i in 0..n {
        let mut t = (std::f64::consts::PI * (4 * i + 3) as f64 / (4 * n + 2) as f64).cos();
        let mut d = 0.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, t);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * t * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            d = n as f64 * (p0 - t * p1) / (1.0 - t * t);
            let dt = p1 / d;
            t -= dt;
            if dt.abs() < 1e-16 {
                break;
            }
        }
        x[i] = 0.5 * (1.0 - t);
        w[i] = 1.0 / ((1.0 - t * t) * d * d);
    }
    for k in [0, 5, 150, 399] {
        let s: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(k)).sum();
        assert!((s - 1.0 / (k as f64 + 1.0)).abs() < 1e-13, "x^{k}: {s}");
    }
    (x, w)
}

/// Convergence of the Gauss–Legendre order per wetted region against the 200-point reference
/// (plain z, `reference_force`), partially wetted rims with Hertz (n = 3/2, the slowest: the
/// integrand vanishes like (z_A − z)^{3/2}) and damping: the default order meets 1e-8 relative
/// in force and moment (the brief's requirement). Prints the study table (`--nocapture`).
#[test]
fn quadrature_order_meets_reference() {
    let law = hertz_ln();
    let cases = [
        (v3(0.3 * C, 0.05 * C, 1e-4), tilted(0.0115, 0.7)),
        (v3(0.97 * C, 0.0, -2e-4), tilted(5e-3, 1.55)),
        (v3(0.1 * C, -0.2 * C, 0.0), tilted(0.02, 0.3)),
        (v3(1.05 * C, 0.0, 0.0), tilted(1e-3, 1.0)),
    ];
    let default = JournalClearance::cylindrical(RB, L, RJ, L)
        .unwrap()
        .quadrature_order();
    let mut worst_default: f64 = 0.0;
    for order in [2, 4, 6, 8, 10, 12, 16, 24, 32] {
        let joint = JournalClearance::cylindrical(RB, L, RJ, L)
            .unwrap()
            .with_quadrature_order(order)
            .unwrap();
        let mut worst: f64 = 0.0;
        for (oj, uj) in cases {
            let st = state(oj, uj, v3(1e-3, -2e-3, 0.0), v3(0.3, 0.1, 0.0));
            let f = joint
                .geometry(&st)
                .unwrap()
                .forces(&laws(law, None), &[0.05; GROUPS]);
            let (fr, mr) = reference_force(&joint, &st, &law, 0.05);
            let ef = (f.force.value() - fr).norm() / fr.norm();
            let em = (f.journal_moment.value() - mr).norm() / mr.norm();
            worst = worst.max(ef).max(em);
        }
        println!("order {order:2}: worst relative error {worst:.2e}");
        if order == default {
            worst_default = worst;
        }
    }
    assert!(
        worst_default <= 1e-8,
        "default order {default}: {worst_default:e}"
    );
}

/// Action and reaction act at the same points: M_j + M_b + (O_j − O_b) × F = 0 (angular
/// momentum exact), to rounding (1e-12 of |F|·L), tilted, sliding, with friction and a thrust
/// face; and LuGre friction is refused with its typed error.
#[test]
fn moments_balance_and_lugre_is_refused() {
    let joint = JournalClearance::revolute(RB, L, RJ, L, 2e-4, None).unwrap();
    let laws = laws(hertz_ln(), Some(FrictionLaw::coulomb(0.2, 1e-4).unwrap()));
    let st = JournalState::new(
        v3(0.1, -0.2, 0.3),
        v3(0.1, 0.2, 1.0),
        v3(0.5, 0.0, 0.1),
        v3(1.0, 2.0, 3.0),
        v3(0.1, -0.2, 0.3) + v3(1.2e-4, 0.3e-4, 1.05e-4),
        v3(0.1, 0.215, 1.0),
        v3(-0.2, 0.1, 0.4),
        v3(0.0, 5.0, -7.0),
    );
    let g = joint.geometry(&st).unwrap();
    let f = g.forces(&laws, &[0.1; GROUPS]);
    let (force, mj, mb) = (
        f.force.value(),
        f.journal_moment.value(),
        f.bearing_moment.value(),
    );
    let d = st.journal_centre.value() - st.bearing_centre.value();
    assert!(force.norm() > 0.0 && f.groups[THRUST_PLUS].normal_force > 0.0);
    assert!((mj + mb + d.cross(&force)).norm() <= 1e-12 * force.norm() * L);
    let lugre = LuGre::new(1e5, 300.0, 0.0, 0.2, 0.1, 1e-3).unwrap();
    assert_eq!(
        JournalLaws::new(hertz_ln(), hertz_ln(), JournalFriction::LuGre(lugre)).unwrap_err(),
        JournalError::LuGreUnsupported
    );
    assert!(matches!(
        joint.geometry(&still(Vector3::zeros(), v3(1.0, 0.0, 0.1))),
        Err(JournalError::Tilt { .. })
    ));
    assert!(JournalClearance::cylindrical(RB, L, RB, L).is_err());
}

/// Energy: without damping and friction the contact is conservative: dW/dt = −P, with P the
/// power of the contact forces and W(t) from central differences along the rigid motion (step
/// 1e-7 s), to 1e-6 of |P| (the quadrature's own error in W limits the match; measured 1e-10), and
/// the reported dissipation −P − dW/dt is 0 (to 1e-6 of |P|; measured 3e-15). Journal tilted in
/// the plane of its eccentricity, sliding axially and tilting further, with the wetted end at the
/// bore's edge and at the journal's own end circle (the end term), and out of that plane while
/// whirling at 3 rad/s (the end's deepest point slides along the end circle).
#[test]
fn conservative_contact_dissipates_nothing() {
    let joint = JournalClearance::cylindrical(RB, L, RJ, L).unwrap();
    let cases = [
        // (centre, axis, velocity, angular velocity)
        (
            v3(0.4 * C, 0.0, 2e-4),
            tilted(0.012, 0.0),
            v3(1e-4, 0.0, 2e-2),
            v3(0.0, 0.05, 0.0),
        ),
        (
            v3(0.4 * C, 0.0, -2e-4),
            tilted(0.012, 0.0),
            v3(1e-4, 0.0, 2e-2),
            v3(0.0, 0.05, 0.0),
        ),
        (
            v3(0.4 * C, 0.1 * C, -2e-4),
            tilted(0.012, 0.4),
            v3(1e-4, 3e-5, 2e-2),
            v3(0.02, 0.05, 3.0),
        ),
    ];
    assert_conservative(&joint, &cases);
}

/// The thrust ring law is conservative too (same checks and tolerances as
/// `conservative_contact_dissipates_nothing`): a centred journal (no radial contact) tilted by
/// 2e-3 rad against its thrust face (R_t = 12 mm, so R_t sin γ = 24 µm), the wetted arc partial
/// (centre penetration 10 µm: φ_e = acos(−10/24)) and the full ring (40 µm), sliding, tilting
/// further and spinning at 3 rad/s about the bore axis (the tilt whirls).
#[test]
fn thrust_ring_is_conservative() {
    let ca = 2e-4;
    let joint = JournalClearance::revolute(RB, L, RJ, L, ca, Some(12e-3)).unwrap();
    let cases = [10e-6, 40e-6].map(|d0| {
        (
            v3(0.0, 0.0, 0.5 * ca + d0),
            tilted(2e-3, 0.4),
            v3(1e-4, 0.0, 2e-2),
            v3(0.05, 0.02, 3.0),
        )
    });
    assert_conservative(&joint, &cases);
}

/// A rigid motion of the journal: centre (m), axis, velocity (m/s), angular velocity (rad/s).
type Motion = (Vector3<f64>, Vector3<f64>, Vector3<f64>, Vector3<f64>);

/// dW/dt = −P and zero reported dissipation (to 1e-6 of |P|) for a Hertz law without damping or
/// friction, along the rigid motions (centre, axis, velocity, angular velocity) of the journal.
fn assert_conservative(joint: &JournalClearance, cases: &[Motion]) {
    let laws = laws(elastic(ElasticLaw::hertz(5e9).unwrap()), None);
    for &(oj, uj, vj, wj) in cases {
        let at = |t: f64| {
            let rot = Rotation3::from_axis_angle(&Unit::new_normalize(wj), wj.norm() * t);
            state(oj + vj * t, rot * uj, vj, wj)
        };
        let eval = |t: f64| {
            joint
                .geometry(&at(t))
                .unwrap()
                .forces(&laws, &[1.0; GROUPS])
        };
        let h = 1e-7;
        let w_rate = (eval(h).elastic_energy() - eval(-h).elastic_energy()) / (2.0 * h);
        let fr = eval(0.0);
        // power of the pair on the journal (moment about O_j with ω_j, force with v_j; the
        // bearing is at rest)
        let p = fr.force.value().dot(&vj) + fr.journal_moment.value().dot(&wj);
        println!(
            "P = {p:e} W, dW/dt = {w_rate:e} W ({:e} of |P|), dissipated {:e} of |P|",
            (w_rate + p) / p.abs(),
            fr.dissipated() / p.abs()
        );
        assert!(p.abs() > 0.0);
        assert!((w_rate + p).abs() <= 1e-6 * p.abs(), "{w_rate} vs {p}");
        assert!(fr.dissipated().abs() <= 1e-6 * p.abs());
    }
}

// ---------------------------------------------------------------------------------------------
// Forward dual numbers over 24 directions (test-only), to check the genericity.

const N: usize = 24;

#[derive(Debug, Clone, Copy, PartialEq)]
struct D {
    v: f64,
    g: [f64; N],
}

impl D {
    fn var(v: f64, k: usize) -> Self {
        let mut g = [0.0; N];
        g[k] = 1.0;
        Self { v, g }
    }
}

impl Add for D {
    type Output = Self;
    fn add(mut self, o: Self) -> Self {
        self.v += o.v;
        self.g.iter_mut().zip(o.g).for_each(|(a, b)| *a += b);
        self
    }
}
impl Sub for D {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        self + -o
    }
}
impl Neg for D {
    type Output = Self;
    fn neg(self) -> Self {
        Self {
            v: -self.v,
            g: self.g.map(|x| -x),
        }
    }
}
impl Mul for D {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let mut g = [0.0; N];
        for k in 0..N {
            g[k] = self.g[k] * o.v + self.v * o.g[k];
        }
        Self { v: self.v * o.v, g }
    }
}
impl Div for D {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        self * o.chain(1.0 / o.v, -1.0 / (o.v * o.v))
    }
}
impl Real for D {
    fn from_f64(v: f64) -> Self {
        Self { v, g: [0.0; N] }
    }
    fn value(&self) -> f64 {
        self.v
    }
    fn chain(self, f: f64, df: f64) -> Self {
        Self {
            v: f,
            g: self.g.map(|x| df * x),
        }
    }
    fn chain2(a: Self, b: Self, f: f64, dfa: f64, dfb: f64) -> Self {
        let mut g = [0.0; N];
        for k in 0..N {
            g[k] = dfa * a.g[k] + dfb * b.g[k];
        }
        Self { v: f, g }
    }
}

/// The 24 directions: bearing translation (0..3) and rotation about O_b (3..6), journal
/// translation (6..9) and rotation about O_j (9..12), then the velocities V_b, ω_b, V_j, ω_j.
struct Base {
    ob: Vector3<f64>,
    ub: Vector3<f64>,
    oj: Vector3<f64>,
    uj: Vector3<f64>,
    vel: [Vector3<f64>; 4],
}

impl Base {
    fn dual(&self) -> JournalState<D> {
        let var = |v: &Vector3<f64>, k0: usize| {
            V3([D::var(v.x, k0), D::var(v.y, k0 + 1), D::var(v.z, k0 + 2)])
        };
        // u + δθ × u at δθ = 0: value u, gradient [·]× columns
        let rot = |u: &Vector3<f64>, k0: usize| {
            let th = V3([D::var(0.0, k0), D::var(0.0, k0 + 1), D::var(0.0, k0 + 2)]);
            V3::constant(u) + th.cross(&V3::constant(u))
        };
        JournalState {
            bearing_centre: var(&self.ob, 0),
            bearing_axis: rot(&self.ub, 3),
            journal_centre: var(&self.oj, 6),
            journal_axis: rot(&self.uj, 9),
            bearing_velocity: var(&self.vel[0], 12),
            bearing_angular_velocity: var(&self.vel[1], 15),
            journal_velocity: var(&self.vel[2], 18),
            journal_angular_velocity: var(&self.vel[3], 21),
        }
    }

    /// The f64 state moved by h along direction k (finite rotations for 3..6 and 9..12).
    fn moved(&self, k: usize, h: f64) -> JournalState<f64> {
        let (mut ob, mut ub, mut oj, mut uj, mut vel) =
            (self.ob, self.ub, self.oj, self.uj, self.vel);
        let unit = |i: usize| {
            let mut e = Vector3::zeros();
            e[i] = h;
            e
        };
        match k {
            0..=2 => ob += unit(k),
            3..=5 => ub = Rotation3::new(unit(k - 3)) * ub,
            6..=8 => oj += unit(k - 6),
            9..=11 => uj = Rotation3::new(unit(k - 9)) * uj,
            _ => vel[(k - 12) / 3] += unit((k - 12) % 3),
        }
        JournalState::new(ob, ub, vel[0], vel[1], oj, uj, vel[2], vel[3])
    }
}

/// The forces evaluated in dual numbers have the gradient of central differences over the 12
/// pose and 12 velocity directions, to 1e-6 relative of each output's largest derivative in the
/// block (steps 1e-10 m, 1e-9 rad, 1e-6 m/s: truncation (h/δ)² ≈ 1e-8 at δ ≈ 1 µm, rounding
/// ≈ 1e-11). Tilted journal touching at two rims on opposite sides, one region partially wetted,
/// sliding and whirling against a thrust face, Hertz with damping and Threlfall friction.
#[test]
fn dual_gradient_matches_central_differences() {
    let joint = JournalClearance::revolute(RB, L, RJ, L, 2e-4, Some(4e-3)).unwrap();
    let laws = laws(hertz_ln(), Some(FrictionLaw::threlfall(0.1, 1e-2).unwrap()));
    let base = Base {
        ob: v3(0.01, 0.02, -0.01),
        ub: v3(0.05, -0.03, 1.0).normalize(),
        oj: v3(0.01, 0.02, -0.01) + v3(0.3 * C, -0.25 * C, 0.4e-4),
        uj: v3(0.05, -0.03, 1.0).normalize() + v3(0.0165, 0.008, 0.0),
        vel: [
            v3(0.01, -0.02, 0.0),
            v3(0.5, -0.2, 3.0),
            v3(-0.01, 0.03, 0.02),
            v3(1.0, 0.5, 30.0),
        ],
    };
    let vdm = [0.2, 0.3, 0.1, 0.15];
    let outputs = |f: &clr_contact::journal::JournalForces<f64>| {
        let mut o = [0.0; 9];
        o[0..3].copy_from_slice(&f.force.0);
        o[3..6].copy_from_slice(&f.journal_moment.0);
        o[6..9].copy_from_slice(&f.bearing_moment.0);
        o
    };
    let gd = joint.geometry(&base.dual()).unwrap();
    let fd = gd.forces(&laws, &vdm);
    let g0 = joint.geometry(&base.moved(0, 0.0)).unwrap();
    println!(
        "gaps {:?}",
        (0..GROUPS).map(|k| g0.gap(k)).collect::<Vec<_>>()
    );
    assert!(g0.wetted(RADIAL_A).is_some() && g0.wetted(RADIAL_B).is_some());
    assert!(g0.gap(THRUST_PLUS).0 > 0.0 || g0.gap(THRUST_MINUS).0 > 0.0);
    let dual_rows: Vec<[f64; N]> = (0..9)
        .map(|i| {
            let v = [fd.force, fd.journal_moment, fd.bearing_moment][i / 3].0[i % 3];
            v.g
        })
        .collect();
    let mut cd = vec![[0.0; N]; 9];
    for k in 0..N {
        let h = match k {
            0..=2 | 6..=8 => 1e-10,
            3..=5 | 9..=11 => 1e-9,
            _ => 1e-6,
        };
        let fp = outputs(
            &joint
                .geometry(&base.moved(k, h))
                .unwrap()
                .forces(&laws, &vdm),
        );
        let fm = outputs(
            &joint
                .geometry(&base.moved(k, -h))
                .unwrap()
                .forces(&laws, &vdm),
        );
        for i in 0..9 {
            cd[i][k] = (fp[i] - fm[i]) / (2.0 * h);
        }
    }
    let mut worst: f64 = 0.0;
    for i in 0..9 {
        for block in [0..12, 12..24] {
            let scale = block.clone().map(|k| cd[i][k].abs()).fold(0.0, f64::max);
            for k in block {
                let err = (dual_rows[i][k] - cd[i][k]).abs() / scale;
                worst = worst.max(err);
                assert!(
                    err <= 1e-6,
                    "output {i}, direction {k}: dual {} vs cd {}",
                    dual_rows[i][k],
                    cd[i][k]
                );
            }
        }
    }
    println!("worst relative gradient error {worst:e}");
}

/// The contact memory: `forces_with_memory` takes each group's δ̇⁻ from `ContactMemory`
/// (rule 2 of `memory`: a contact without history that penetrates gets its current rate, floored)
/// and equals `forces` with those impact velocities bit for bit; `commit` opens exactly the
/// penetrating groups (radial A and B and the thrust face here; the other face stays closed).
#[test]
fn memory_slots_follow_the_groups() {
    let joint = JournalClearance::revolute(RB, L, RJ, L, 2e-4, Some(4e-3)).unwrap();
    let laws = laws(hertz_ln(), None);
    let st = state(
        v3(0.1 * C, -0.2 * C, 1.5e-4),
        tilted(0.02, 0.3),
        v3(0.01, 0.0, 0.002),
        v3(0.0, 0.0, 3.0),
    );
    let g = joint.geometry(&st).unwrap();
    let mut memory = clr_contact::ContactMemory::new(3 + GROUPS, 1e-4).unwrap();
    let with_memory = g.forces_with_memory(&laws, &mut memory, 3);
    let vdm: [f64; GROUPS] = std::array::from_fn(|k| g.gap(k).1.max(1e-4));
    assert_eq!(with_memory, g.forces(&laws, &vdm));
    g.commit(&mut memory, 3);
    for k in 0..GROUPS {
        let open = g.gap(k).0 > 0.0;
        assert_eq!(memory.committed(3 + k).is_some(), open, "group {k}");
    }
    assert!(g.gap(RADIAL_A).0 > 0.0 && g.gap(RADIAL_B).0 > 0.0 && g.gap(THRUST_PLUS).0 > 0.0);
    assert!(g.gap(THRUST_MINUS).0 < 0.0);
    assert_eq!(memory.committed(0), None);
}
