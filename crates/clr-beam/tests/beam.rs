//! Tests of clr-beam against Euler–Bernoulli closed forms (../shared/spec/verification.md,
//! Beams; Blevins, *Formulas for Natural Frequency and Mode Shape*, 1979, Table 8-1) and
//! against independent formulations.

use approx::assert_relative_eq;
use clr_beam::{
    BeamError, BeamModel, Face, Loads, MassKind, Material, Path, Section, Support, TransientSystem,
};
use proptest::prelude::*;

const L: f64 = 1.0;

fn mat() -> Material {
    Material::new(210e9, 7850.0, 0.3).unwrap()
}

/// 20 mm × 10 mm steel strip (slender: L/r ≈ 346, axial modes far above the first bending ones).
fn sec() -> Section {
    Section::rectangular(0.02, 0.01).unwrap()
}

fn scale() -> f64 {
    let (m, s) = (mat(), sec());
    (m.youngs_modulus * s.second_moment / (m.density * s.area * L.powi(4))).sqrt()
}

fn cantilever(n: usize) -> BeamModel {
    let mut b = BeamModel::straight([0.0, 0.0], [L, 0.0], n, mat(), sec()).unwrap();
    b.support(0, Support::Clamped).unwrap();
    b
}

/// Indices of modes whose largest component is transverse (v) or rotational, not axial.
fn bending_modes(b: &BeamModel, n: usize) -> Vec<f64> {
    let m = b.modes(n).unwrap();
    (0..n)
        .filter(|&j| {
            let (mut ua, mut va) = (0.0f64, 0.0f64);
            for i in 0..b.nodes().len() {
                ua = ua.max(m.shapes[(3 * i, j)].abs());
                va = va.max(m.shapes[(3 * i + 1, j)].abs());
            }
            va > ua
        })
        .map(|j| m.omega[j])
        .collect()
}

#[test]
fn cantilever_frequencies_within_0_1_percent_with_20_elements() {
    let beta = [
        1.875104069,
        4.694091133,
        7.854757438,
        10.99554073,
        14.13716839,
    ];
    let w = bending_modes(&cantilever(20), 6);
    for (k, b) in beta.iter().enumerate() {
        assert_relative_eq!(w[k], b * b * scale(), max_relative = 1e-3);
    }
}

#[test]
fn simply_supported_and_free_free() {
    let mut ss = BeamModel::straight([0.0, 0.0], [L, 0.0], 20, mat(), sec()).unwrap();
    ss.support(0, Support::Pinned).unwrap();
    ss.support(20, Support::RollerX).unwrap();
    let w = bending_modes(&ss, 4);
    for n in 1..=3 {
        let b = n as f64 * std::f64::consts::PI;
        assert_relative_eq!(w[n - 1], b * b * scale(), max_relative = 1e-4);
    }
    let ff = BeamModel::straight([0.0, 0.0], [L, 0.0], 20, mat(), sec()).unwrap();
    let m = ff.modes(6).unwrap();
    assert_eq!(m.rigid_body_modes, 3);
    assert_eq!(&m.omega[..3], &[0.0, 0.0, 0.0]);
    for (k, b) in [4.730040745, 7.853204624, 10.99560784].iter().enumerate() {
        assert_relative_eq!(m.omega[3 + k], b * b * scale(), max_relative = 1e-4);
    }
}

#[test]
fn axial_rod_frequencies() {
    // Only axial DOF free: v = θ = 0 at every node; clamped at x = 0.
    let n = 100;
    let mut b = BeamModel::straight([0.0, 0.0], [L, 0.0], n, mat(), sec()).unwrap();
    for i in 0..=n {
        b.prescribe(i, 1, 0.0)
            .unwrap()
            .prescribe(i, 2, 0.0)
            .unwrap();
    }
    b.prescribe(0, 0, 0.0).unwrap();
    let m = b.modes(2).unwrap();
    let c = (mat().youngs_modulus / mat().density).sqrt();
    for k in 1..=2 {
        // Linear elements with consistent mass: error ≈ (kh)²/24 ≈ 9e-5 for mode 2.
        let w = (2 * k - 1) as f64 * std::f64::consts::PI / (2.0 * L) * c;
        assert_relative_eq!(m.omega[k - 1], w, max_relative = 2e-4);
    }
}

#[test]
fn static_tip_load_and_uniform_load_exact_at_nodes() {
    let n = 8;
    let b = cantilever(n);
    let ei = mat().youngs_modulus * sec().second_moment;
    let p = -150.0;
    let sol = b
        .solve_static(&Loads::new().nodal(n, [0.0, p, 0.0]))
        .unwrap();
    assert_relative_eq!(
        sol.displacements[3 * n + 1],
        p * L.powi(3) / (3.0 * ei),
        max_relative = 1e-10
    );
    assert_relative_eq!(
        sol.displacements[3 * n + 2],
        p * L.powi(2) / (2.0 * ei),
        max_relative = 1e-10
    );
    // Reactions: force −P, moment −P L at the clamp.
    assert_relative_eq!(sol.reactions[1], -p, max_relative = 1e-10);
    assert_relative_eq!(sol.reactions[2], -p * L, max_relative = 1e-10);
    // Queries on the deformed beam: w(s) = P s²(3L − s)/(6EI), M(s) = EI w'' = P (L − s), exact
    // everywhere because the exact solution is cubic.
    let path = b.path().unwrap();
    let zero = vec![0.0; b.n_dof()];
    for s in [0.0, 0.123, 0.5, 0.77, L] {
        let pt = path.point(s, &sol.displacements, &zero).unwrap();
        assert_relative_eq!(
            pt.displacement[1],
            p * s * s * (3.0 * L - s) / (6.0 * ei),
            max_relative = 1e-9,
            epsilon = 1e-15
        );
        assert_relative_eq!(
            pt.bending_moment,
            p * (L - s),
            max_relative = 1e-9,
            epsilon = 1e-9
        );
        assert_relative_eq!(
            pt.slope,
            p * s * (2.0 * L - s) / (2.0 * ei),
            max_relative = 1e-9,
            epsilon = 1e-15
        );
    }
    // Uniform load q: w(x) = q x²(6L² − 4Lx + x²)/(24EI), exact at the nodes.
    let q = -80.0;
    let sol = b
        .solve_static(&Loads::new().uniform_global_all(&b, [0.0, q]))
        .unwrap();
    for i in 0..=n {
        let x = i as f64 * L / n as f64;
        let w = q * x * x * (6.0 * L * L - 4.0 * L * x + x * x) / (24.0 * ei);
        assert_relative_eq!(
            sol.displacements[3 * i + 1],
            w,
            max_relative = 1e-10,
            epsilon = 1e-18
        );
    }
    assert_relative_eq!(sol.reactions[2], -q * L * L / 2.0, max_relative = 1e-10);
}

/// Self weight of a cantilever inclined at 30° (clamped at the lower end, gravity −9.81 m/s²
/// along y): the transverse component q = −ρAg cos α gives the tip deflection qL⁴/(8EI) normal
/// to the axis (Roark 8th ed. Table 8.1 case 2a) and the axial component p = −ρAg sin α the tip
/// shortening pL²/(2EA) (a bar under a uniform axial load). Hermite cubics and linear axial
/// elements with consistent loads are exact at the nodes: tolerance 1e-9 (round-off).
#[test]
fn self_weight_of_an_inclined_cantilever() {
    let n = 4;
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let mut b = BeamModel::straight([0.0, 0.0], [L * c, L * s], n, mat(), sec()).unwrap();
    b.support(0, Support::Clamped).unwrap();
    let g = 9.81;
    let sol = b
        .solve_static(&Loads::new().self_weight(&b, [0.0, -g]))
        .unwrap();
    let w = mat().density * sec().area * g;
    let (ei, ea) = (
        mat().youngs_modulus * sec().second_moment,
        mat().youngs_modulus * sec().area,
    );
    let (q, p) = (-w * c, -w * s);
    let (ux, uy) = (sol.displacements[3 * n], sol.displacements[3 * n + 1]);
    // axial along (c, s), transverse along (−s, c)
    assert_relative_eq!(ux * c + uy * s, p * L * L / (2.0 * ea), max_relative = 1e-9);
    assert_relative_eq!(
        -ux * s + uy * c,
        q * L.powi(4) / (8.0 * ei),
        max_relative = 1e-9
    );
    // the support carries the whole weight ρA g L
    assert_relative_eq!(sol.reactions[1], w * L, max_relative = 1e-9);
}

#[test]
fn point_force_inside_an_element_via_load_row() {
    // Tip deflection of a cantilever under P at a: P a²(3L − a)/(6EI) (Roark, Table 8.1 case 1a).
    let n = 5;
    let b = cantilever(n);
    let ei = mat().youngs_modulus * sec().second_moment;
    let (a, p) = (0.63, 40.0);
    let row = b.path().unwrap().load_row(a).unwrap();
    let mut loads = Loads::new();
    for j in 0..6 {
        let d = row.dofs[j];
        let mut f = [0.0; 3];
        f[d % 3] = row.fy[j] * p;
        loads = loads.nodal(d / 3, f);
    }
    let sol = b.solve_static(&loads).unwrap();
    assert_relative_eq!(
        sol.displacements[3 * n + 1],
        p * a * a * (3.0 * L - a) / (6.0 * ei),
        max_relative = 1e-10
    );
}

#[test]
fn tension_stiffens_simply_supported_beam() {
    // ω₁² = (π/L)⁴ EI/ρA + (π/L)² P/ρA for a simply supported beam under tension P.
    let mut b = BeamModel::straight([0.0, 0.0], [L, 0.0], 20, mat(), sec()).unwrap();
    b.support(0, Support::Pinned).unwrap();
    b.support(20, Support::RollerX).unwrap();
    let p = 2000.0;
    for e in 0..20 {
        b.set_axial_force(e, p).unwrap();
    }
    let ra = mat().density * sec().area;
    let ei = mat().youngs_modulus * sec().second_moment;
    let k = std::f64::consts::PI / L;
    let w = bending_modes(&b, 2)[0];
    assert_relative_eq!(
        w,
        (k.powi(4) * ei / ra + k * k * p / ra).sqrt(),
        max_relative = 1e-4
    );
}

#[test]
fn lumped_mass_converges_to_the_same_frequency() {
    let mut b = cantilever(40);
    b.set_mass_kind(MassKind::Lumped);
    let w = bending_modes(&b, 2)[0];
    assert_relative_eq!(w, 1.875104069f64.powi(2) * scale(), max_relative = 1e-3);
}

#[test]
fn orientation_does_not_change_frequencies() {
    let a = 0.7f64;
    let mut b = BeamModel::straight(
        [0.3, -0.2],
        [0.3 + L * a.cos(), -0.2 + L * a.sin()],
        10,
        mat(),
        sec(),
    )
    .unwrap();
    b.support(0, Support::Clamped).unwrap();
    let w0 = cantilever(10).modes(4).unwrap().omega;
    let w1 = b.modes(4).unwrap().omega;
    for k in 0..4 {
        assert_relative_eq!(w0[k], w1[k], max_relative = 1e-9);
    }
}

#[test]
fn sparse_equals_dense() {
    let b = cantilever(7);
    let kd = b.stiffness_dense().unwrap();
    let ks = b.stiffness_sparse().unwrap().to_dense();
    let md = b.mass_dense().unwrap();
    let ms = b.mass_sparse().unwrap().to_dense();
    assert!((&kd - &ks).norm_max() <= 1e-12 * kd.norm_max());
    assert!((&md - &ms).norm_max() <= 1e-12 * md.norm_max());
}

/// A portal frame: two columns (clamped bases) and a beam, rigid corners.
fn portal() -> BeamModel {
    let mut f = BeamModel::new();
    let n0 = f.add_node([0.0, 0.0]);
    let n1 = f.add_node([0.0, 1.0]);
    let n2 = f.add_node([1.5, 1.0]);
    let n3 = f.add_node([1.5, 0.0]);
    f.add_member(n0, n1, 10, mat(), sec()).unwrap();
    f.add_member(n1, n2, 15, mat(), sec()).unwrap();
    f.add_member(n2, n3, 10, mat(), sec()).unwrap();
    f.support(n0, Support::Clamped).unwrap();
    f.support(n3, Support::Clamped).unwrap();
    f
}

#[test]
fn craig_bampton_reproduces_the_frame_frequencies() {
    let f = portal();
    let full = f.modes(4).unwrap().omega;
    let cb = f.craig_bampton(&[1, 2], 8).unwrap();
    assert_eq!(cb.mass.nrows(), 6 + 8);
    let (lam, _) =
        clr_beam::modal::lowest_modes(cb.stiffness.as_ref(), cb.mass.as_ref(), 4, f.lambda_ref())
            .unwrap();
    for k in 0..4 {
        assert_relative_eq!(lam[k].sqrt(), full[k], max_relative = 5e-3);
    }
    // Reduced M, K reproduce T ᵀ M T for the boundary identity block: boundary rows of T.
    for (c, &d) in cb.boundary_dofs.iter().enumerate() {
        assert_eq!(cb.transformation[(d, c)], 1.0);
    }
    // Modal truncation: M_r = I, K_r = diag ω².
    let mt = f.modal_truncation(3).unwrap();
    for (i, w) in full.iter().take(3).enumerate() {
        assert_relative_eq!(mt.mass[(i, i)], 1.0, max_relative = 1e-10);
        assert_relative_eq!(mt.stiffness[(i, i)], w * w, max_relative = 1e-8);
    }
}

/// Simpson integral of g over [0, L] with 2000 intervals.
fn simpson(g: impl Fn(f64) -> f64) -> f64 {
    let n = 2000;
    let h = L / n as f64;
    (0..=n)
        .map(|i| {
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            w * g(i as f64 * h)
        })
        .sum::<f64>()
        * h
        / 3.0
}

#[test]
fn floating_frame_invariants_against_quadrature_of_queries() {
    let b = cantilever(10);
    let red = b.modal_truncation(2).unwrap();
    let inv = &red.invariants;
    let ra = mat().density * sec().area;
    assert_relative_eq!(inv.mass, ra * L, max_relative = 1e-12);
    assert_relative_eq!(inv.first_moment[0], ra * L * L / 2.0, max_relative = 1e-12);
    assert!(inv.first_moment[1].abs() < 1e-14);
    assert_relative_eq!(
        inv.polar_inertia,
        ra * L.powi(3) / 3.0,
        max_relative = 1e-12
    );
    // Shape integrals by Simpson quadrature of the interpolated mode shapes (path queries).
    let path = b.path().unwrap();
    let zero = vec![0.0; b.n_dof()];
    let shape =
        |k: usize| -> Vec<f64> { (0..b.n_dof()).map(|d| red.transformation[(d, k)]).collect() };
    let (p0, p1) = (shape(0), shape(1));
    let disp = |p: &Vec<f64>, s: f64| path.point(s, p, &zero).unwrap().displacement;
    for (k, p) in [&p0, &p1].into_iter().enumerate() {
        let sy = simpson(|s| ra * disp(p, s)[1]);
        assert_relative_eq!(inv.shape_first_moment[k][1], sy, max_relative = 1e-8);
        let rc = simpson(|s| ra * (s * disp(p, s)[1] - 0.0 * disp(p, s)[0]));
        assert_relative_eq!(inv.rotation_coupling[k], rc, max_relative = 1e-8);
    }
    let m01 =
        simpson(|s| ra * (disp(&p0, s)[0] * disp(&p1, s)[0] + disp(&p0, s)[1] * disp(&p1, s)[1]));
    assert!((inv.modal_mass[(0, 1)] - m01).abs() < 1e-8);
    assert_relative_eq!(inv.modal_mass[(0, 0)], 1.0, max_relative = 1e-10);
    // Skew integrals: ∫ρ φ_k × φ_l with axial and transverse parts (add axial motion).
    let mut q = p0.clone();
    for i in 0..=10 {
        q[3 * i] = 0.01 * (i as f64 / 10.0).powi(1);
    }
    let t2 = faer::Mat::from_fn(b.n_dof(), 2, |d, c| if c == 0 { q[d] } else { p1[d] });
    let inv2 = b.invariants(t2.as_ref()).unwrap();
    let sk = simpson(|s| {
        let (a, c) = (disp(&q, s), disp(&p1, s));
        ra * (a[0] * c[1] - a[1] * c[0])
    });
    assert_relative_eq!(inv2.modal_skew[(0, 1)], sk, max_relative = 1e-8);
    assert_relative_eq!(inv2.modal_skew[(1, 0)], -sk, max_relative = 1e-8);
}

#[test]
fn surface_points_and_velocities() {
    let b = cantilever(4);
    let path = b.path().unwrap();
    let mut q = vec![0.0; b.n_dof()];
    let mut qd = vec![0.0; b.n_dof()];
    // Rigid rotation by a small angle a about the origin: u = −a y, v = a x, θ = a.
    let (a, ad) = (1e-3, 2.0);
    for (i, p) in b.nodes().iter().enumerate() {
        q[3 * i] = -a * p[1];
        q[3 * i + 1] = a * p[0];
        q[3 * i + 2] = a;
        qd[3 * i + 1] = ad * p[0];
        qd[3 * i + 2] = ad;
    }
    let h = sec().depth;
    let s = 0.61;
    let up = path.surface(s, Face::Upper, &q, &qd).unwrap();
    assert_relative_eq!(up.normal[0], -a.sin(), max_relative = 1e-12);
    assert_relative_eq!(up.normal[1], a.cos(), max_relative = 1e-12);
    assert_relative_eq!(
        up.position[1],
        a * s + 0.5 * h * a.cos(),
        max_relative = 1e-12
    );
    assert_relative_eq!(up.position[0], s - 0.5 * h * a.sin(), max_relative = 1e-12);
    // Velocity of the surface point: ḋ − e θ̇ t with t = (cos a, sin a).
    assert_relative_eq!(
        up.velocity[0],
        -0.5 * h * ad * a.cos(),
        max_relative = 1e-12
    );
    assert_relative_eq!(
        up.velocity[1],
        ad * s - 0.5 * h * ad * a.sin(),
        max_relative = 1e-12
    );
    let lo = path.surface(s, Face::Lower, &q, &qd).unwrap();
    assert_relative_eq!(lo.normal[1], -a.cos(), max_relative = 1e-12);
    assert_relative_eq!(lo.normal_rate[0], ad * a.cos(), max_relative = 1e-12);
}

#[test]
fn transient_rhs_is_in_equilibrium_at_the_static_solution_and_jacobian_matches() {
    let mut b = cantilever(6);
    b.set_rayleigh(0.5, 1e-4);
    let loads = Loads::new().nodal(6, [3.0, -10.0, 0.5]);
    let st = b.solve_static(&loads).unwrap();
    let mut sys = TransientSystem::new(&b)
        .unwrap()
        .with_load_pattern(&b, &loads, |_| 1.0)
        .unwrap();
    let n = sys.dim() / 2;
    let mut y = vec![0.0; 2 * n];
    for (i, &d) in sys.dofs().free.clone().iter().enumerate() {
        y[i] = st.displacements[d];
    }
    let mut dy = vec![0.0; 2 * n];
    sys.rhs(0.0, &y, &mut dy);
    let acc_scale = 10.0 / b.total_mass();
    assert!(dy.iter().all(|v| v.abs() < 1e-6 * acc_scale), "{dy:?}");
    // Jacobian against central differences of the (linear) right-hand side.
    let mut jac = vec![0.0; 4 * n * n];
    sys.jacobian(&mut jac);
    let (mut fp, mut fm) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
    for j in [0, n - 1, n, 2 * n - 1] {
        let h = 1e-6;
        let mut yp = y.clone();
        yp[j] += h;
        let mut ym = y.clone();
        ym[j] -= h;
        sys.rhs(0.0, &yp, &mut fp);
        sys.rhs(0.0, &ym, &mut fm);
        for i in 0..2 * n {
            let fd = (fp[i] - fm[i]) / (2.0 * h);
            let an = jac[i + j * 2 * n];
            assert!(
                (fd - an).abs() <= 1e-6 * an.abs().max(1.0),
                "J[{i},{j}] {fd} vs {an}"
            );
        }
    }
    assert_eq!(sys.free_index(0), None);
    assert_eq!(sys.free_index(3), Some(0));
}

#[test]
fn invalid_input_gives_typed_errors() {
    assert!(matches!(
        BeamModel::new().modes(1),
        Err(BeamError::NoElements)
    ));
    let ff = BeamModel::straight([0.0, 0.0], [L, 0.0], 3, mat(), sec()).unwrap();
    assert!(matches!(
        ff.solve_static(&Loads::new().nodal(3, [0.0, 1.0, 0.0])),
        Err(BeamError::SingularStiffness { .. })
    ));
    let c = cantilever(2);
    assert!(matches!(
        c.modes(7),
        Err(BeamError::TooManyModes {
            requested: 7,
            available: 6
        })
    ));
    assert!(matches!(c.modes(0), Err(BeamError::ZeroModes)));
    let z = vec![0.0; c.n_dof()];
    assert!(matches!(
        c.path().unwrap().point(1.5, &z, &z),
        Err(BeamError::OutsideBeam { .. })
    ));
    assert!(matches!(
        BeamModel::straight([0.0, 0.0], [0.0, 0.0], 3, mat(), sec()),
        Err(BeamError::ZeroLength(0, 3))
    ));
    assert!(matches!(
        BeamModel::straight([0.0, 0.0], [1.0, 0.0], 0, mat(), sec()),
        Err(BeamError::NoElements)
    ));
    let bad = Material {
        youngs_modulus: -1.0,
        ..mat()
    };
    assert!(matches!(
        BeamModel::straight([0.0, 0.0], [1.0, 0.0], 2, bad, sec()),
        Err(BeamError::NonPositive { .. })
    ));
    // Compression beyond the Euler load P_cr = π² EI / L² (pinned–pinned) makes K indefinite.
    let mut ss = BeamModel::straight([0.0, 0.0], [L, 0.0], 10, mat(), sec()).unwrap();
    ss.support(0, Support::Pinned).unwrap();
    ss.support(10, Support::RollerX).unwrap();
    let pcr = std::f64::consts::PI.powi(2) * mat().youngs_modulus * sec().second_moment / (L * L);
    for e in 0..10 {
        ss.set_axial_force(e, -1.5 * pcr).unwrap();
    }
    assert!(matches!(ss.modes(2), Err(BeamError::Indefinite { .. })));
    // CB with a floating interior (interface at the clamp of a cantilever is constrained).
    assert!(matches!(
        cantilever(3).craig_bampton(&[0], 2),
        Err(BeamError::NoInterface)
    ));
    // Path through disconnected elements.
    let p = portal();
    assert!(matches!(
        Path::new(&p, &[0, 20]),
        Err(BeamError::NotAChain(0, 20))
    ));
}

proptest! {
    /// The load row is the transpose of the interpolation: F · d(s) = Σ row · q for any q
    /// (virtual work), on elements of any orientation.
    #[test]
    fn load_row_is_work_conjugate(angle in -3.0f64..3.0, s in 0.0f64..1.0, seed in 0u64..1000, fx in -5.0f64..5.0, fy in -5.0f64..5.0) {
        let b = BeamModel::straight([0.1, 0.2], [0.1 + angle.cos(), 0.2 + angle.sin()], 3, mat(), sec()).unwrap();
        let path = b.path().unwrap();
        let q: Vec<f64> = (0..b.n_dof()).map(|i| (((i as u64 + 1) * (seed + 7)) % 13) as f64 / 13.0 - 0.5).collect();
        let z = vec![0.0; b.n_dof()];
        let d = path.point(s, &q, &z).unwrap().displacement;
        let r = path.load_row(s).unwrap();
        let w: f64 = (0..6).map(|j| (r.fx[j] * fx + r.fy[j] * fy) * q[r.dofs[j]]).sum();
        prop_assert!((w - (fx * d[0] + fy * d[1])).abs() < 1e-12);
        // Surface row at zero deformation: lever arm ±h/2 on the rotation row.
        let su = path.surface_load_row(s, Face::Upper, &z).unwrap();
        let sp = path.surface(s, Face::Upper, &q, &z).unwrap();
        let p0 = path.surface(s, Face::Upper, &z, &z).unwrap();
        let ws: f64 = (0..6).map(|j| (su.fx[j] * fx + su.fy[j] * fy) * q[su.dofs[j]] * 1e-6).sum();
        let mut qs = q.clone();
        qs.iter_mut().for_each(|x| *x *= 1e-6);
        let sp_small = path.surface(s, Face::Upper, &qs, &z).unwrap();
        let lin = fx * (sp_small.position[0] - p0.position[0]) + fy * (sp_small.position[1] - p0.position[1]);
        prop_assert!((ws - lin).abs() < 1e-10, "{ws} {lin} {:?}", sp.position);
    }
}

/// The sparse subspace iteration and the dense solver are independent formulations of the
/// same eigenproblem: frequencies agree to 1e-7 (both are round-off limited near 3e-8 for 150
/// elements, where λ_max/λ₁ ≈ 1e11), mode shapes to 1e-5.
#[test]
fn subspace_iteration_matches_dense_solver() {
    use clr_beam::EigenMethod;
    let cases = [
        cantilever(150),
        BeamModel::straight([0.0, 0.0], [L, 0.0], 60, mat(), sec()).unwrap(),
        portal(),
    ];
    for b in &cases {
        let d = b.modes_with(10, EigenMethod::Dense).unwrap();
        let s = b.modes_with(10, EigenMethod::Subspace).unwrap();
        assert_eq!(d.rigid_body_modes, s.rigid_body_modes);
        for k in 0..10 {
            if d.omega[k] == 0.0 {
                assert_eq!(s.omega[k], 0.0);
                continue;
            }
            assert_relative_eq!(s.omega[k], d.omega[k], max_relative = 1e-7);
            // Distinct eigenvalues: the same shape up to sign.
            let dist = |sg: f64| {
                (0..b.n_dof())
                    .map(|i| (s.shapes[(i, k)] - sg * d.shapes[(i, k)]).abs())
                    .fold(0.0, f64::max)
            };
            let diff = dist(1.0).min(dist(-1.0));
            let size = (0..b.n_dof())
                .map(|i| d.shapes[(i, k)].abs())
                .fold(0.0, f64::max);
            assert!(diff <= 1e-5 * size, "mode {k}: {diff} vs {size}");
        }
    }
}

/// Prescribed tip displacement δ of a cantilever (support settlement): the tip reaction is
/// 3EIδ/L³ and the clamp moment 3EIδ/L² (Roark 8th ed. Table 8.1 case 1a with P = 3EIδ/L³).
#[test]
fn prescribed_displacement_and_reactions() {
    let n = 6;
    let mut b = cantilever(n);
    let delta = 2e-3;
    b.prescribe(n, 1, delta).unwrap();
    let sol = b.solve_static(&Loads::new()).unwrap();
    let ei = mat().youngs_modulus * sec().second_moment;
    assert_eq!(sol.displacements[3 * n + 1], delta);
    assert_relative_eq!(
        sol.reactions[3 * n + 1],
        3.0 * ei * delta / L.powi(3),
        max_relative = 1e-10
    );
    assert_relative_eq!(
        sol.reactions[1],
        -3.0 * ei * delta / L.powi(3),
        max_relative = 1e-10
    );
    assert_relative_eq!(
        sol.reactions[2],
        -3.0 * ei * delta / L.powi(2),
        max_relative = 1e-10
    );
    assert_relative_eq!(
        sol.displacements[3 * n + 2],
        1.5 * delta / L,
        max_relative = 1e-10
    );
    // The transient system sees the prescribed value as a constant load: at rest in the static
    // state, the accelerations vanish.
    let mut sys = TransientSystem::new(&b).unwrap();
    let n_free = sys.dim() / 2;
    let mut y = vec![0.0; 2 * n_free];
    for (i, &d) in sys.dofs().free.clone().iter().enumerate() {
        y[i] = sol.displacements[d];
    }
    let mut dy = vec![0.0; 2 * n_free];
    sys.rhs(0.0, &y, &mut dy);
    let scale = 3.0 * ei * delta / L.powi(3) / b.total_mass();
    assert!(dy.iter().all(|v| v.abs() < 1e-6 * scale));
    assert_eq!(sys.displacements(&b, &y), sol.displacements);
}

/// Craig–Bampton on a free–free beam with the interface at one end is fine (the interior is
/// held by the interface); with an interior piece that floats it is a typed error.
#[test]
fn craig_bampton_free_free_and_floating_interior() {
    let ff = BeamModel::straight([0.0, 0.0], [L, 0.0], 12, mat(), sec()).unwrap();
    let cb = ff.craig_bampton(&[0], 6).unwrap();
    // The reduced model keeps the three rigid-body modes and the lowest elastic frequency.
    let (lam, _) =
        clr_beam::modal::lowest_modes(cb.stiffness.as_ref(), cb.mass.as_ref(), 4, ff.lambda_ref())
            .unwrap();
    assert_eq!(&lam[..3], &[0.0, 0.0, 0.0]);
    assert_relative_eq!(
        lam[3].sqrt(),
        4.730040745f64.powi(2) * scale(),
        max_relative = 1e-3
    );
    // Two separate members, interface only on the first: the second one floats.
    let mut two = BeamModel::new();
    let (a, b) = (two.add_node([0.0, 0.0]), two.add_node([1.0, 0.0]));
    let (c, d) = (two.add_node([0.0, 1.0]), two.add_node([1.0, 1.0]));
    two.add_member(a, b, 2, mat(), sec()).unwrap();
    two.add_member(c, d, 2, mat(), sec()).unwrap();
    assert!(matches!(
        two.craig_bampton(&[a], 2),
        Err(BeamError::SingularStiffness { .. })
    ));
}

/// `Path::shape_rows` reproduces `Path::surface` (reference + d + e n(α + θ)) and its `dx`,
/// `dy`, `curvature` rows are the s-derivatives of `x`, `y`, `slope` (central differences in
/// s inside an element, step 1e-6 m: truncation O(h²) of cubic rows, tolerance 1e-7 of the
/// rows' scale), on an oblique beam with an arbitrary deformation.
#[test]
fn shape_rows_reproduce_the_surface_and_their_derivatives() {
    let angle = 0.7f64;
    let b = BeamModel::straight(
        [0.1, 0.2],
        [0.1 + angle.cos(), 0.2 + angle.sin()],
        3,
        mat(),
        sec(),
    )
    .unwrap();
    let path = b.path().unwrap();
    let q: Vec<f64> = (0..b.n_dof())
        .map(|i| 1e-3 * ((i * 7 % 11) as f64 - 5.0))
        .collect();
    let z = vec![0.0; b.n_dof()];
    let s = 0.41;
    let r = path.shape_rows(s).unwrap();
    let dot = |row: &[f64; 6]| (0..6).map(|j| row[j] * q[r.dofs[j]]).sum::<f64>();
    let phi = angle + dot(&r.slope);
    let e = 0.5 * r.depth;
    let up = path.surface(s, Face::Upper, &q, &z).unwrap();
    let expect = [
        r.reference[0] + dot(&r.x) - e * phi.sin(),
        r.reference[1] + dot(&r.y) + e * phi.cos(),
    ];
    for k in 0..2 {
        assert!(
            (up.position[k] - expect[k]).abs() < 1e-14,
            "{:?} {expect:?}",
            up.position
        );
    }
    assert!((r.axis[0] - angle.cos()).abs() < 1e-14 && (r.axis[1] - angle.sin()).abs() < 1e-14);
    let h = 1e-6;
    let (p, m) = (
        path.shape_rows(s + h).unwrap(),
        path.shape_rows(s - h).unwrap(),
    );
    for (row, rp, rm, scale) in [
        (r.dx, p.x, m.x, 1.0),
        (r.dy, p.y, m.y, 1.0),
        (r.curvature, p.slope, m.slope, 10.0),
    ] {
        for j in 0..6 {
            let fd = (rp[j] - rm[j]) / (2.0 * h);
            assert!(
                (row[j] - fd).abs() < 1e-7 * scale,
                "{j}: {} vs {fd}",
                row[j]
            );
        }
    }
}
