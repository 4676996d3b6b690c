//! Spatial shape contact (`clr_contact::shapes3d`) against closed forms: every depth, normal
//! and contact point below is derived by hand from the geometry of the two shapes (distance of
//! a point to a plane, an edge or a corner; heights of box corners and rims under a rotation),
//! and the in-plane cases against the planar module (`clr_contact::shapes`), an independent
//! formulation (parry2d on the planar shapes).
//!
//! Tolerances: depths 1e-9 relative (δ is the difference of lengths of order 0.1 m, so
//! rounding leaves ~1e-12 of a 1e-4 m depth; 1e-9 leaves room for parry's clipping
//! arithmetic); unit normals and points 1e-12 absolute (metre-sized coordinates, a few
//! roundings); the planar comparison 1e-12 absolute, as the brief asks.

use clr_contact::body::BodyState;
use clr_contact::shapes::{contact_points, ContactShape, Shape, ShapeContactWorkspace};
use clr_contact::shapes3d::{
    boxes_gap3, boxes_overlap3, contact_points3, shape_distance3, BodyState3, ContactShape3,
    Feature3, PartPose3, Shape3, ShapeContactPoint3, ShapeContactWorkspace3,
};
use clr_contact::ContactError;
use nalgebra::{UnitQuaternion, Vector2, Vector3};
use std::f64::consts::{FRAC_PI_2, PI};

fn v3(x: f64, y: f64, z: f64) -> Vector3<f64> {
    Vector3::new(x, y, z)
}

/// A body at rest at `p` turned by the rotation vector `rv` (rad).
fn at(p: Vector3<f64>, rv: Vector3<f64>) -> BodyState3 {
    BodyState3::fixed(p, UnitQuaternion::from_scaled_axis(rv))
}

fn shape(s: Result<Shape3, ContactError>) -> ContactShape3 {
    ContactShape3::new(s.unwrap()).unwrap()
}

/// The eight corners (±s, ±s, ±s) of a cube of half width `s`, m.
fn cube_points(s: f64) -> Vec<[f64; 3]> {
    (0..8)
        .map(|k| {
            let sg = |b: usize| if k & b == 0 { -s } else { s };
            [sg(1), sg(2), sg(4)]
        })
        .collect()
}

/// The square [−1, 1]² at height `z` as a mesh of two triangles.
fn flat_mesh(z: f64) -> ContactShape3 {
    shape(Shape3::trimesh(
        vec![
            [-1.0, -1.0, z],
            [1.0, -1.0, z],
            [1.0, 1.0, z],
            [-1.0, 1.0, z],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    ))
}

fn query(
    a: &ContactShape3,
    pa: &BodyState3,
    b: &ContactShape3,
    pb: &BodyState3,
    prediction: f64,
) -> Vec<ShapeContactPoint3> {
    let mut ws = ShapeContactWorkspace3::new();
    contact_points3(a, pa, b, pb, prediction, &mut ws)
        .unwrap()
        .to_vec()
}

#[track_caller]
fn assert_depth(got: f64, want: f64) {
    assert!(
        (got - want).abs() <= 1e-9 * want.abs(),
        "depth {got:e}, expected {want:e}"
    );
}

#[track_caller]
fn assert_vec(got: Vector3<f64>, want: Vector3<f64>) {
    assert!(
        (got - want).amax() <= 1e-12,
        "{got:?}, expected {want:?} (diff {:e})",
        (got - want).amax()
    );
}

/// The point's geometry is consistent: point_b = point_a − δ n, |n| = 1.
#[track_caller]
fn assert_consistent(p: &ShapeContactPoint3) {
    assert!((p.normal.norm() - 1.0).abs() <= 1e-12, "{p:?}");
    assert_vec(p.point_b, p.point_a - p.depth * p.normal);
}

// ------------------------------------------------------------------------------ balls

/// Two spheres: δ = r₁ + r₂ − |c₂ − c₁|, n along the line of centres, points at the surfaces.
#[test]
fn ball_ball_closed_form() {
    let (r1, r2) = (0.03, 0.02);
    let a = shape(Shape3::ball(r1));
    let b = shape(Shape3::ball(r2));
    let ca = v3(0.1, -0.2, 0.3);
    let dir = v3(2.0, -3.0, 6.0) / 7.0;
    let delta = 1e-4;
    let cb = ca + dir * (r1 + r2 - delta);
    let pa = at(ca, v3(0.3, -0.2, 0.1));
    let pb = at(cb, v3(-1.0, 0.5, 2.0));
    let pts = query(&a, &pa, &b, &pb, 0.0);
    assert_eq!(pts.len(), 1);
    let p = pts[0];
    assert_depth(p.depth, delta);
    assert_vec(p.normal, dir);
    assert_vec(p.point_a, ca + dir * r1);
    assert_vec(p.point_b, cb - dir * r2);
    assert_eq!(
        (p.feature_a, p.feature_b),
        (Feature3::Vertex, Feature3::Vertex)
    );
    assert_eq!((p.radius_a, p.radius_b), (r1, r2));
    // Separated by 1 mm: nothing without prediction, a depth of −1 mm with it; the distance
    // query gives the gap.
    let sep = at(ca + dir * (r1 + r2 + 1e-3), v3(0.0, 0.0, 0.0));
    assert!(query(&a, &pa, &b, &sep, 0.0).is_empty());
    let pts = query(&a, &pa, &b, &sep, 2e-3);
    assert_depth(pts[0].depth, -1e-3);
    let d = shape_distance3(&a, &pa, &b, &sep).unwrap();
    assert!((d - 1e-3).abs() <= 1e-12, "{d}");
}

/// A sphere against a box turned by `rv` at `o`, the ball centre at `local` in the box frame.
fn ball_on_box(local: Vector3<f64>) -> (Vec<ShapeContactPoint3>, BodyState3) {
    let cub = shape(Shape3::cuboid(0.05, 0.03, 0.02));
    let ball = shape(Shape3::ball(0.01));
    let pc = at(v3(1.0, 2.0, -0.5), v3(0.4, -0.3, 0.7));
    let pb = at(pc.point(local), v3(0.1, 0.2, 0.3));
    (query(&cub, &pc, &ball, &pb, 0.0), pc)
}

/// Sphere of radius r pressing δ into a box face, an edge and a corner: the centre lies at
/// distance r − δ from the face plane, the edge line or the corner point, along the outward
/// normal n (face normal; edge and corner bisectors (0, 1, 1)/√2, (1, 1, 1)/√3).
#[test]
fn ball_cuboid_face_edge_corner() {
    let (h, r, delta) = (v3(0.05, 0.03, 0.02), 0.01, 2e-4);
    let cases = [
        // (point on the box, outward unit normal), box frame.
        (v3(0.02, -0.01, h.z), v3(0.0, 0.0, 1.0)),
        (v3(0.01, h.y, h.z), v3(0.0, 1.0, 1.0) / 2f64.sqrt()),
        (h, v3(1.0, 1.0, 1.0) / 3f64.sqrt()),
    ];
    for (on_box, n_local) in cases {
        let (pts, pc) = ball_on_box(on_box + n_local * (r - delta));
        assert_eq!(pts.len(), 1, "{pts:?}");
        let p = pts[0];
        let n = pc.rotate(n_local);
        assert_depth(p.depth, delta);
        assert_vec(p.normal, n);
        assert_vec(p.point_a, pc.point(on_box));
        assert_vec(p.point_b, pc.point(on_box) - n * delta);
    }
    // Swapped order: the normal points from the ball to the box.
    let cub = shape(Shape3::cuboid(0.05, 0.03, 0.02));
    let ball = shape(Shape3::ball(r));
    let pc = at(v3(0.0, 0.0, 0.0), v3(0.0, 0.0, 0.0));
    let pb = at(v3(0.0, 0.0, h.z + r - delta), v3(0.0, 0.0, 0.0));
    let p = query(&ball, &pb, &cub, &pc, 0.0)[0];
    assert_depth(p.depth, delta);
    assert_vec(p.normal, v3(0.0, 0.0, -1.0));
}

// ------------------------------------------------------------------------------ capsule

/// A capsule (half length L, radius r, axis x) over a box top face z = h_z, turned by θ about
/// y: its core ends sit at x_c ± L cos θ, z_c ∓ L sin θ, so the end depths are
/// δ± = h_z + r − (z_c ∓ L sin θ). Flat (θ = 0): two points of equal depth at the core ends.
#[test]
fn capsule_cuboid_flat_and_tilted() {
    let (len, r) = (0.04, 0.005);
    let hz = 0.02;
    let cub = shape(Shape3::cuboid(0.2, 0.1, hz));
    let cap = shape(Shape3::capsule(len, r));
    let ground = at(v3(0.0, 0.0, 0.0), v3(0.0, 0.0, 0.0));
    let delta = 1e-4;
    let (xc, yc) = (0.03, -0.02);
    let pts = query(
        &cub,
        &ground,
        &cap,
        &at(v3(xc, yc, hz + r - delta), v3(0.0, 0.0, 0.0)),
        0.0,
    );
    assert_eq!(pts.len(), 2, "{pts:?}");
    let mut xs: Vec<f64> = pts.iter().map(|p| p.point_b.x).collect();
    xs.sort_by(f64::total_cmp);
    assert!((xs[0] - (xc - len)).abs() <= 1e-12 && (xs[1] - (xc + len)).abs() <= 1e-12);
    for p in &pts {
        assert_depth(p.depth, delta);
        assert_vec(p.normal, v3(0.0, 0.0, 1.0));
        assert_vec(p.point_a, v3(p.point_b.x, yc, hz));
        assert_eq!(p.radius_b, r);
        assert_consistent(p);
    }
    // Tilted by θ about y, both ends in: δ± = h_z + r − z_c ± L sin θ.
    let theta: f64 = 0.01;
    let zc = hz + r - 1e-3;
    let pts = query(
        &cub,
        &ground,
        &cap,
        &at(v3(xc, yc, zc), v3(0.0, theta, 0.0)),
        0.0,
    );
    assert_eq!(pts.len(), 2, "{pts:?}");
    for p in &pts {
        // Ry(θ) sends the +x end down: x = x_c + L cos θ, z = z_c − L sin θ.
        let s = if p.point_b.x > xc { 1.0 } else { -1.0 };
        assert_depth(p.depth, hz + r - zc + s * len * theta.sin());
        assert!((p.point_b.x - (xc + s * len * theta.cos())).abs() <= 1e-12);
        assert_vec(p.normal, v3(0.0, 0.0, 1.0));
        assert_consistent(p);
    }
}

// ------------------------------------------------------------------------------ cylinder

/// A cylinder (half length L, radius R) standing on its end on a box top face z = h_z (body x
/// turned to world z by −π/2 about y): parry's contact polygon of the end is an inscribed
/// square, four points on the rim at distance R from the axis, each at depth δ.
#[test]
fn cylinder_flat_on_cuboid() {
    let (len, rad, hz, delta) = (0.03, 0.02, 0.05, 1e-4);
    let cub = shape(Shape3::cuboid(0.3, 0.3, hz));
    let cyl = shape(Shape3::cylinder(len, rad));
    let ground = at(v3(0.0, 0.0, 0.0), v3(0.0, 0.0, 0.0));
    let c = v3(0.1, -0.05, hz + len - delta);
    let pose = at(c, v3(0.0, -FRAC_PI_2, 0.0));
    assert_vec(pose.rotate(v3(1.0, 0.0, 0.0)), v3(0.0, 0.0, 1.0));
    let pts = query(&cub, &ground, &cyl, &pose, 0.0);
    assert_eq!(pts.len(), 4, "{pts:?}");
    for p in &pts {
        assert_depth(p.depth, delta);
        assert_vec(p.normal, v3(0.0, 0.0, 1.0));
        let radial = (p.point_b - c).xy().norm();
        assert!((radial - rad).abs() <= 1e-12, "{radial}");
        assert!((p.point_b.z - (hz - delta)).abs() <= 1e-12);
        assert_consistent(p);
    }
}

/// The same cylinder tilted by α from the vertical about world y: the lowest rim point is
/// c − L a + R u, a = (sin α, 0, cos α) the axis, u = (cos α, 0, −sin α) the in-end direction
/// that falls fastest, so z_low = z_c − L cos α − R sin α and δ = h_z − z_low; one point.
#[test]
fn cylinder_edge_on_cuboid() {
    let (len, rad, hz) = (0.03, 0.02, 0.05);
    let cub = shape(Shape3::cuboid(0.3, 0.3, hz));
    let cyl = shape(Shape3::cylinder(len, rad));
    let ground = at(v3(0.0, 0.0, 0.0), v3(0.0, 0.0, 0.0));
    let alpha: f64 = 0.3;
    let delta = 1e-4;
    let zc = hz + len * alpha.cos() + rad * alpha.sin() - delta;
    let c = v3(0.1, -0.05, zc);
    // Body x → world z, then tilt by α about world y.
    let q = UnitQuaternion::from_scaled_axis(v3(0.0, alpha, 0.0))
        * UnitQuaternion::from_scaled_axis(v3(0.0, -FRAC_PI_2, 0.0));
    let pose = BodyState3::fixed(c, q);
    let axis = v3(alpha.sin(), 0.0, alpha.cos());
    assert_vec(pose.rotate(v3(1.0, 0.0, 0.0)), axis);
    let u = v3(alpha.cos(), 0.0, -alpha.sin());
    let low = c - len * axis + rad * u;
    let pts = query(&cub, &ground, &cyl, &pose, 0.0);
    assert_eq!(pts.len(), 1, "{pts:?}");
    let p = pts[0];
    assert_depth(p.depth, delta);
    assert_vec(p.normal, v3(0.0, 0.0, 1.0));
    assert!((p.point_b.z - low.z).abs() <= 1e-12, "{p:?}");
    // parry places its square on the rim at GJK's contact azimuth (GJK stops at a relative
    // 1.5e-7 on the support distance), so the point lies on the rim within about 1e-6 R of
    // the lowest point (3.0e-8 m = 1.5e-6 R here); the depth error is second order,
    // R(1 − cos Δφ) ~ 1e-14 m. Tolerance 1e-5 R along the rim.
    assert!((p.point_b - low).norm() <= 1e-5 * rad, "{p:?} {low:?}");
    assert_consistent(&p);
}

/// A cylinder lying on its side on a box top face z = h_z, axis horizontal at azimuth ψ:
/// line contact along the bottom generatrix; parry's side feature is that segment, so two
/// points at its ends c ± L a − R e_z, each at depth δ (the segment's azimuth comes from GJK:
/// along the rim within 1e-5 R, as for the tilted rim).
#[test]
fn cylinder_side_on_cuboid() {
    let (len, rad, hz, delta) = (0.03, 0.01, 0.05, 1e-4);
    let cub = shape(Shape3::cuboid(0.3, 0.3, hz));
    let cyl = shape(Shape3::cylinder(len, rad));
    let ground = at(v3(0.0, 0.0, 0.0), v3(0.0, 0.0, 0.0));
    let psi: f64 = 0.4;
    let c = v3(-0.1, 0.05, hz + rad - delta);
    let pose = at(c, v3(0.0, 0.0, psi));
    let axis = v3(psi.cos(), psi.sin(), 0.0);
    let pts = query(&cub, &ground, &cyl, &pose, 0.0);
    assert_eq!(pts.len(), 2, "{pts:?}");
    for p in &pts {
        let s = if (p.point_b - c).dot(&axis) > 0.0 {
            1.0
        } else {
            -1.0
        };
        let end = c + s * len * axis - rad * v3(0.0, 0.0, 1.0);
        assert_depth(p.depth, delta);
        assert_vec(p.normal, v3(0.0, 0.0, 1.0));
        assert!((p.point_b - end).norm() <= 1e-5 * rad, "{p:?} {end:?}");
        assert!((p.point_b.z - end.z).abs() <= 1e-12, "{p:?}");
        assert_consistent(p);
    }
}

/// A compound: a box with a cylinder part below it, the part's pose turning its axis (body x)
/// to body z (rotation vector (0, −π/2, 0)) and placing it at (0, 0, −0.03). Its lower end at
/// body z = −0.03 − L rests δ deep on a floor: four rim points of part 1 at distance R from
/// the part's axis; the box part stays clear.
#[test]
fn compound_part_pose_applies() {
    let (len, rad, delta) = (0.01, 0.015, 1e-4);
    let comp = shape(Shape3::compound(vec![
        (
            PartPose3::IDENTITY,
            Shape3::cuboid(0.04, 0.03, 0.02).unwrap(),
        ),
        (
            PartPose3::new([0.0, 0.0, -0.03], [0.0, -FRAC_PI_2, 0.0]),
            Shape3::cylinder(len, rad).unwrap(),
        ),
    ]));
    let floor = shape(Shape3::cuboid(1.0, 1.0, 0.1));
    let ground = at(v3(0.0, 0.0, 0.0), v3(0.0, 0.0, 0.0));
    let c = v3(0.2, 0.1, 0.1 + 0.03 + len - delta);
    let pose = at(c, v3(0.0, 0.0, 0.5));
    let pts = query(&floor, &ground, &comp, &pose, 0.0);
    assert_eq!(pts.len(), 4, "{pts:?}");
    for p in &pts {
        assert_eq!(p.part_b, 1);
        assert_depth(p.depth, delta);
        assert_vec(p.normal, v3(0.0, 0.0, 1.0));
        assert!(((p.point_b - c).xy().norm() - rad).abs() <= 1e-12, "{p:?}");
        assert!((p.point_b.z - (0.1 - delta)).abs() <= 1e-12, "{p:?}");
    }
}

// ------------------------------------------------------------------------------ cone

/// A cone (half height L, base radius R) standing on its apex on a plane (a large box top
/// face z = 0): body x turned to world −z by π/2 about y puts the apex at c − L e_z, so
/// δ = L − z_c, one point at the apex.
#[test]
fn cone_tip_on_plane() {
    let (len, rad, delta) = (0.04, 0.015, 1e-4);
    let plane = shape(Shape3::cuboid(1.0, 1.0, 0.1));
    let cone = shape(Shape3::cone(len, rad));
    let ground = at(v3(0.0, 0.0, -0.1), v3(0.0, 0.0, 0.0));
    let c = v3(0.2, 0.1, len - delta);
    let pose = at(c, v3(0.0, FRAC_PI_2, 0.0));
    assert_vec(pose.rotate(v3(1.0, 0.0, 0.0)), v3(0.0, 0.0, -1.0));
    for pts in [
        query(&plane, &ground, &cone, &pose, 0.0),
        query(&plane, &ground, &cone, &pose, 1e-3),
    ] {
        assert_eq!(pts.len(), 1, "{pts:?}");
        let p = pts[0];
        assert_depth(p.depth, delta);
        assert_vec(p.normal, v3(0.0, 0.0, 1.0));
        assert_vec(p.point_b, v3(c.x, c.y, -delta));
        assert_vec(p.point_a, v3(c.x, c.y, 0.0));
    }
}

// ------------------------------------------------------------------------------ boxes

/// A box (half extents h) on a large box whose top face is z = H, turned by ψ about z and
/// tilted by small angles about x and y: corner k of the bottom face sits at
/// z_k = z_c + (R (±h_x, ±h_y, −h_z))_z and penetrates by δ_k = H − z_k. All four corners
/// are in: four points, each at its corner with its own depth.
#[test]
fn box_on_box_four_corners() {
    let big_h = 0.1;
    let h = v3(0.04, 0.03, 0.02);
    let big = shape(Shape3::cuboid(1.0, 1.0, big_h));
    let small = shape(Shape3::cuboid(h.x, h.y, h.z));
    let ground = at(v3(0.0, 0.0, 0.0), v3(0.0, 0.0, 0.0));
    for (tilt, psi) in [((0.0, 0.0), 0.0), ((0.0, 0.0), 0.7), ((2e-3, -1e-3), 0.7)] {
        let q = UnitQuaternion::from_scaled_axis(v3(tilt.0, tilt.1, 0.0))
            * UnitQuaternion::from_scaled_axis(v3(0.0, 0.0, psi));
        let c = v3(0.1, -0.2, big_h + h.z - 2e-4);
        let pose = BodyState3::fixed(c, q);
        let pts = query(&big, &ground, &small, &pose, 0.0);
        assert_eq!(pts.len(), 4, "tilt {tilt:?} ψ {psi}: {pts:?}");
        for p in &pts {
            let corner = [-1.0, 1.0]
                .iter()
                .flat_map(|&sx| [-1.0, 1.0].map(|sy| pose.point(v3(sx * h.x, sy * h.y, -h.z))))
                .min_by(|a, b| (a - p.point_b).norm().total_cmp(&(b - p.point_b).norm()))
                .unwrap();
            assert_vec(p.point_b, corner);
            assert_depth(p.depth, big_h - corner.z);
            assert_vec(p.normal, v3(0.0, 0.0, 1.0));
            assert_consistent(p);
            assert_eq!(p.feature_a, Feature3::Face);
        }
    }
}

// ------------------------------------------------------------------------------ convex

/// An octahedron (vertices ±a on each axis) given as a convex polyhedron, apex down on a cube
/// given as a convex polyhedron (top face z = s): δ = s − (z_c − a), one point at the apex
/// (parry's duplicate GJK point is dropped), the cube's face below it.
#[test]
fn convex_convex_vertex_on_face() {
    let (a, s) = (0.02, 0.05);
    let octa = shape(Shape3::convex_polyhedron(vec![
        [a, 0.0, 0.0],
        [-a, 0.0, 0.0],
        [0.0, a, 0.0],
        [0.0, -a, 0.0],
        [0.0, 0.0, a],
        [0.0, 0.0, -a],
    ]));
    let cube = shape(Shape3::convex_polyhedron(cube_points(s)));
    let ground = at(v3(0.0, 0.0, 0.0), v3(0.0, 0.0, 0.0));
    let delta = 1e-4;
    // Turned about z only: the apex stays at the bottom.
    let c = v3(0.01, 0.02, s + a - delta);
    let pose = at(c, v3(0.0, 0.0, 0.3));
    let pts = query(&cube, &ground, &octa, &pose, 0.0);
    assert_eq!(pts.len(), 1, "{pts:?}");
    let p = pts[0];
    assert_depth(p.depth, delta);
    assert_vec(p.normal, v3(0.0, 0.0, 1.0));
    assert_vec(p.point_b, c - v3(0.0, 0.0, a));
    assert_eq!(p.feature_b, Feature3::Vertex);
    assert_consistent(&p);
    // The same cube written as a cuboid gives the same point.
    let cub = shape(Shape3::cuboid(s, s, s));
    let q = query(&cub, &ground, &octa, &pose, 0.0);
    assert_eq!(q.len(), 1);
    assert_depth(q[0].depth, delta);
    assert_vec(q[0].point_b, p.point_b);
}

/// Two cubes (half width s) written as convex polyhedra, crossed edge on edge: A turned by
/// π/4 about y has its top edge along y at z = s√2; B turned by π/4 about x, centred at
/// (x_B, y_B, z_B), has its bottom edge along x at z_B − s√2. The edges cross at (0, y_B):
/// δ = 2 s√2 − z_B, one point (parry's duplicate GJK point dropped) between two edges.
#[test]
fn convex_convex_edge_on_edge() {
    let s = 0.02;
    let cube = shape(Shape3::convex_polyhedron(cube_points(s)));
    let delta = 1e-4;
    let r2 = 2f64.sqrt();
    let pa = at(v3(0.0, 0.0, 0.0), v3(0.0, PI / 4.0, 0.0));
    let (xb, yb) = (0.005, -0.003);
    let pb = at(v3(xb, yb, 2.0 * s * r2 - delta), v3(PI / 4.0, 0.0, 0.0));
    let pts = query(&cube, &pa, &cube, &pb, 0.0);
    assert_eq!(pts.len(), 1, "{pts:?}");
    let p = pts[0];
    assert_depth(p.depth, delta);
    assert_vec(p.normal, v3(0.0, 0.0, 1.0));
    assert_vec(p.point_a, v3(0.0, yb, s * r2));
    assert_vec(p.point_b, v3(0.0, yb, s * r2 - delta));
    assert_eq!((p.feature_a, p.feature_b), (Feature3::Edge, Feature3::Edge));
}

// ------------------------------------------------------------------------------ trimesh

/// A ball over a triangle mesh: a flat square of two triangles (z = 0) and a tent of two
/// faces through the ridge x = 0, z = t, falling with slope m. Over a face away from the
/// edges: δ = r − d, d the distance of the centre to the face plane, n the face normal.
#[test]
fn trimesh_ball() {
    let r = 0.01;
    let ball = shape(Shape3::ball(r));
    let ground = at(v3(0.0, 0.0, 0.0), v3(0.0, 0.0, 0.0));
    let flat = flat_mesh(0.0);
    let delta = 2e-4;
    let c = v3(0.3, -0.4, r - delta);
    let pts = query(&flat, &ground, &ball, &at(c, v3(0.0, 0.0, 0.0)), 0.0);
    assert_eq!(pts.len(), 1, "{pts:?}");
    assert_depth(pts[0].depth, delta);
    assert_vec(pts[0].normal, v3(0.0, 0.0, 1.0));
    assert_vec(pts[0].point_a, v3(c.x, c.y, 0.0));
    assert_eq!(pts[0].part_a, 0);
    // Tent: faces z = t − m|x|; the +x face has unit normal (m, 0, 1)/√(1 + m²).
    let (t, m) = (0.1, 0.5);
    let tent = shape(Shape3::trimesh(
        vec![
            [-1.0, -1.0, t - m],
            [0.0, -1.0, t],
            [0.0, 1.0, t],
            [-1.0, 1.0, t - m],
            [1.0, -1.0, t - m],
            [1.0, 1.0, t - m],
        ],
        vec![[0, 1, 2], [0, 2, 3], [1, 4, 5], [1, 5, 2]],
    ));
    let n = v3(m, 0.0, 1.0) / (1.0 + m * m).sqrt();
    let foot = v3(0.4, 0.1, t - m * 0.4);
    let c = foot + n * (r - delta);
    let pts = query(&tent, &ground, &ball, &at(c, v3(0.0, 0.0, 0.0)), 0.0);
    assert_eq!(pts.len(), 1, "{pts:?}");
    assert_depth(pts[0].depth, delta);
    assert_vec(pts[0].normal, n);
    assert_vec(pts[0].point_a, foot);
    assert!(pts[0].part_a == 2 || pts[0].part_a == 3, "{pts:?}");
}

// ------------------------------------------------------------------------------ history

/// The answer is a pure function of the poses: the same query after other queries (other
/// poses, other depths) gives the same bits, for every kind of parry path (convex manifold,
/// polygonal-feature manifold with GJK, composite trimesh and compound).
#[test]
fn queries_are_history_free() {
    let big = shape(Shape3::cuboid(1.0, 1.0, 0.1));
    let mesh = flat_mesh(0.1);
    let others = [
        shape(Shape3::cuboid(0.04, 0.03, 0.02)),
        shape(Shape3::cylinder(0.02, 0.03)),
        shape(Shape3::capsule(0.03, 0.01)),
        shape(Shape3::compound(vec![
            (
                PartPose3::IDENTITY,
                Shape3::cuboid(0.04, 0.03, 0.02).unwrap(),
            ),
            (
                PartPose3::new([0.05, 0.0, 0.0], [0.0, 0.3, 0.0]),
                Shape3::cylinder(0.02, 0.01).unwrap(),
            ),
        ])),
    ];
    let ground = at(v3(0.0, 0.0, 0.0), v3(0.0, 0.0, 0.0));
    for a in [&big, &mesh] {
        for b in &others {
            // B's lowest point 0.5 mm, then 0.2 mm, below the top face z = 0.1.
            let rv = v3(0.01, -0.02, 0.3);
            let bottom = b.aabb3(&at(v3(0.0, 0.0, 0.0), rv)).unwrap()[2];
            let p1 = at(v3(0.0, 0.0, 0.1 - bottom - 5e-4), rv);
            let p2 = at(
                v3(1e-5, 2e-5, 0.1 - bottom - 2e-4),
                v3(0.011, -0.019, 0.3001),
            );
            let fresh = query(a, &ground, b, &p2, 1e-3);
            assert!(!fresh.is_empty(), "{b:?}");
            let mut ws = ShapeContactWorkspace3::new();
            contact_points3(a, &ground, b, &p1, 1e-3, &mut ws).unwrap();
            contact_points3(a, &ground, b, &p2, 0.0, &mut ws).unwrap();
            contact_points3(a, &ground, b, &p1, 1e-3, &mut ws).unwrap();
            let after = contact_points3(a, &ground, b, &p2, 1e-3, &mut ws)
                .unwrap()
                .to_vec();
            assert_eq!(fresh, after, "{b:?}");
        }
    }
}

// ------------------------------------------------------------------------------ errors

/// Every bad input is refused with a typed error naming the field.
#[test]
fn invalid_inputs_refused_with_the_field() {
    let tetra = || vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let cases: Vec<(Result<Shape3, ContactError>, &str, &str)> = vec![
        (Shape3::ball(0.0), "ball radius", "> 0"),
        (Shape3::ball(f64::NAN), "ball radius", "finite"),
        (Shape3::capsule(-0.1, 0.1), "capsule half_length", "> 0"),
        (
            Shape3::capsule(0.1, f64::INFINITY),
            "capsule radius",
            "finite",
        ),
        (Shape3::cuboid(0.1, 0.1, 0.0), "half_extents[2]", "> 0"),
        (Shape3::cylinder(0.1, -1.0), "cylinder radius", "> 0"),
        (Shape3::cone(0.0, 1.0), "cone half_length", "> 0"),
        (
            Shape3::convex_polyhedron(tetra()[..3].to_vec()),
            "convex polyhedron points",
            "at least 4",
        ),
        (
            Shape3::convex_polyhedron(vec![
                [0.0; 3],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [1.0, 1.0, 0.0],
            ]),
            "convex polyhedron points",
            "one plane",
        ),
        (
            Shape3::convex_polyhedron({
                let mut p = tetra();
                p.push([0.1, 0.1, 0.1]);
                p
            }),
            "convex polyhedron points",
            "point 4 lies inside",
        ),
        (
            Shape3::convex_polyhedron({
                let mut p = tetra();
                p[2][1] = f64::NAN;
                p
            }),
            "convex polyhedron points",
            "point 2",
        ),
        (
            Shape3::trimesh(tetra(), vec![]),
            "trimesh indices",
            "at least one triangle",
        ),
        (
            Shape3::trimesh(tetra(), vec![[1, 2, 3], [2, 3, 4]]),
            "trimesh indices",
            "count from 0",
        ),
        (
            Shape3::trimesh(tetra(), vec![[0, 1, 1]]),
            "trimesh indices",
            "zero area",
        ),
        (
            Shape3::trimesh(
                vec![[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]],
                vec![[0, 1, 2]],
            ),
            "trimesh indices",
            "zero area",
        ),
        (
            Shape3::trimesh(
                vec![[0.0; 3], [f64::NAN, 0.0, 0.0], [2.0, 0.0, 0.0]],
                vec![[0, 1, 2]],
            ),
            "trimesh vertices",
            "point 1",
        ),
        (Shape3::compound(vec![]), "compound parts", "at least one"),
        (
            Shape3::compound(vec![(
                PartPose3::IDENTITY,
                Shape3::TriMesh {
                    vertices: tetra(),
                    indices: vec![[0, 1, 2]],
                },
            )]),
            "compound parts",
            "triangle mesh or a compound",
        ),
        (
            Shape3::compound(vec![(
                PartPose3::new([0.0; 3], [0.0, 0.0, 90.0]),
                Shape3::Ball { radius: 1.0 },
            )]),
            "compound part rotation vector",
            "degrees",
        ),
        (
            Shape3::compound(vec![(
                PartPose3::new([f64::NAN, 0.0, 0.0], [0.0; 3]),
                Shape3::Ball { radius: 1.0 },
            )]),
            "compound part position",
            "finite",
        ),
        (
            Shape3::compound(vec![(PartPose3::IDENTITY, Shape3::Ball { radius: -1.0 })]),
            "ball radius",
            "> 0",
        ),
    ];
    for (i, (r, field, says)) in cases.into_iter().enumerate() {
        let e = r.expect_err(&format!("case {i} accepted"));
        let ContactError::InvalidParameter { name, .. } = &e else {
            panic!("case {i}: {e}");
        };
        assert!(
            name.contains(field),
            "case {i}: field {name}, expected {field}"
        );
        assert!(e.to_string().contains(says), "case {i}: {e}");
    }
    // Hand-written variants are checked again when built.
    assert!(ContactShape3::new(Shape3::Ball { radius: -1.0 }).is_err());
    // Bad poses and prediction are refused at the query, with the field.
    let b = shape(Shape3::ball(1.0));
    let ok = at(v3(0.0, 0.0, 0.0), v3(0.0, 0.0, 0.0));
    let mut ws = ShapeContactWorkspace3::new();
    let field = |e: ContactError| match e {
        ContactError::InvalidParameter { name, .. } => name,
        e => panic!("{e}"),
    };
    let nan = at(v3(0.0, f64::NAN, 0.0), v3(0.0, 0.0, 0.0));
    let e = contact_points3(&b, &nan, &b, &ok, 0.0, &mut ws).unwrap_err();
    assert_eq!(field(e), "body position y (m)");
    let e = contact_points3(&b, &ok, &b, &ok, -1.0, &mut ws).unwrap_err();
    assert_eq!(field(e), "prediction (m)");
    let skew = BodyState3::fixed(
        Vector3::zeros(),
        UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(1.1, 0.0, 0.0, 0.0)),
    );
    let e = contact_points3(&b, &skew, &b, &ok, 0.0, &mut ws).unwrap_err();
    assert_eq!(field(e), "body rotation quaternion norm");
    assert!(b.aabb3(&skew).is_err());
    // A point on a face of the hull is accepted (it is on the boundary).
    let mut p = tetra();
    p.push([0.5, 0.5, 0.0]);
    Shape3::convex_polyhedron(p).unwrap();
}

// ------------------------------------------------------------------------------ planar

fn planar(s: Shape) -> ContactShape {
    ContactShape::new(s).unwrap()
}

/// The planar pose (x, y, θ) as a spatial one (z = 0, rotation θ about z).
fn lift(x: f64, y: f64, theta: f64) -> (BodyState, BodyState3) {
    (
        BodyState::fixed(Vector2::new(x, y), theta),
        at(v3(x, y, 0.0), v3(0.0, 0.0, theta)),
    )
}

/// With the motion in one plane (z = 0, rotations about z), balls, cuboids and capsules give
/// the planar module's points (an independent formulation: parry2d on planar shapes) to
/// 1e-12. A box–box face contact in space is the planar one extruded: each planar point
/// appears twice, at z = ±h_z (the ends of the prism's edge), with the same depth.
#[test]
fn in_plane_motion_equals_planar_module() {
    let hz = 0.05;
    let pairs: Vec<((Shape, Shape3), (Shape, Shape3))> = vec![
        (
            (Shape::ball(0.03).unwrap(), Shape3::ball(0.03).unwrap()),
            (Shape::ball(0.02).unwrap(), Shape3::ball(0.02).unwrap()),
        ),
        (
            (
                Shape::cuboid(0.05, 0.02).unwrap(),
                Shape3::cuboid(0.05, 0.02, hz).unwrap(),
            ),
            (Shape::ball(0.01).unwrap(), Shape3::ball(0.01).unwrap()),
        ),
        (
            (
                Shape::cuboid(0.3, 0.1).unwrap(),
                Shape3::cuboid(0.3, 0.1, hz).unwrap(),
            ),
            (
                Shape::capsule(0.04, 0.01).unwrap(),
                Shape3::capsule(0.04, 0.01).unwrap(),
            ),
        ),
        (
            (
                Shape::capsule(0.05, 0.02).unwrap(),
                Shape3::capsule(0.05, 0.02).unwrap(),
            ),
            (
                Shape::capsule(0.04, 0.01).unwrap(),
                Shape3::capsule(0.04, 0.01).unwrap(),
            ),
        ),
        (
            (
                Shape::cuboid(0.3, 0.1).unwrap(),
                Shape3::cuboid(0.3, 0.1, hz).unwrap(),
            ),
            (
                Shape::cuboid(0.04, 0.02).unwrap(),
                Shape3::cuboid(0.04, 0.02, hz).unwrap(),
            ),
        ),
    ];
    let mut n_compared = 0;
    for ((a2, a3), (b2, b3)) in pairs {
        let (a2, a3, b2, b3) = (planar(a2), shape(Ok(a3)), planar(b2), shape(Ok(b3)));
        let extruded = matches!(a3.desc(), Shape3::Cuboid { .. })
            && matches!(b3.desc(), Shape3::Cuboid { .. });
        let reach = a3.bounding_radius() + b3.bounding_radius();
        for (k, theta_b) in [0.0, 0.02, -0.3, 1.2].into_iter().enumerate() {
            let (pa2, pa3) = lift(0.1, -0.2, 0.25);
            // B approaches A's centre from above-right until they overlap a little.
            let dir = Vector2::new(0.3 + 0.1 * k as f64, 1.0).normalize();
            let mut ws2 = ShapeContactWorkspace::new();
            let (mut lo, mut hi) = (0.0, reach);
            // Bisection on the distance for a first contact, then 1e-4 m deeper.
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                let (p, _) = lift(0.1 + mid * dir.x, -0.2 + mid * dir.y, theta_b);
                if contact_points(&a2, &pa2, &b2, &p, 0.0, &mut ws2)
                    .unwrap()
                    .is_empty()
                {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let s = lo - 1e-4;
            let (pb2, pb3) = lift(0.1 + s * dir.x, -0.2 + s * dir.y, theta_b);
            let p2 = contact_points(&a2, &pa2, &b2, &pb2, 0.0, &mut ws2)
                .unwrap()
                .to_vec();
            let p3 = query(&a3, &pa3, &b3, &pb3, 0.0);
            assert!(!p2.is_empty());
            let copies = if extruded { 2 } else { 1 };
            assert_eq!(p3.len(), copies * p2.len(), "{p2:?}\n{p3:?}");
            for q in &p3 {
                let z = if extruded {
                    hz.copysign(q.point_a.z)
                } else {
                    0.0
                };
                let p = p2
                    .iter()
                    .min_by(|u, w| {
                        (u.point_a - q.point_a.xy())
                            .norm()
                            .total_cmp(&(w.point_a - q.point_a.xy()).norm())
                    })
                    .unwrap();
                assert!((q.depth - p.depth).abs() <= 1e-12, "{q:?} {p:?}");
                assert_vec(q.normal, v3(p.normal.x, p.normal.y, 0.0));
                assert_vec(q.point_a, v3(p.point_a.x, p.point_a.y, z));
                assert_vec(q.point_b, v3(p.point_b.x, p.point_b.y, z));
                n_compared += 1;
            }
        }
    }
    assert!(n_compared >= 20, "{n_compared}");
}

// ------------------------------------------------------------------------------ bounds

/// Bounding boxes, their gap and the distance query against closed forms: a box turned by
/// π/4 about z has half widths (h_x + h_y)/√2 in x and y; two balls 1 m apart along x are
/// 1 − r₁ − r₂ apart, their boxes too.
#[test]
fn bounding_boxes_gap_and_distance() {
    let cub = shape(Shape3::cuboid(0.3, 0.1, 0.2));
    let pose = at(v3(1.0, 2.0, 3.0), v3(0.0, 0.0, PI / 4.0));
    let b = cub.aabb3(&pose).unwrap();
    let w = 0.4 / 2f64.sqrt();
    let want = [1.0 - w, 2.0 - w, 2.8, 1.0 + w, 2.0 + w, 3.2];
    for (g, e) in b.iter().zip(want) {
        assert!((g - e).abs() <= 1e-12, "{b:?}");
    }
    let r = (0.3f64 * 0.3 + 0.1 * 0.1 + 0.2 * 0.2).sqrt();
    assert!((cub.bounding_radius() - r).abs() <= 1e-15);
    // A cylinder along x: its box is [−L, L] × [−R, R]².
    let cyl = shape(Shape3::cylinder(0.5, 0.1));
    let b = cyl.aabb3(&BodyState3::default()).unwrap();
    for (g, e) in b.iter().zip([-0.5, -0.1, -0.1, 0.5, 0.1, 0.1]) {
        assert!((g - e).abs() <= 1e-12, "{b:?}");
    }
    let (r1, r2) = (0.1, 0.2);
    let (s1, s2) = (shape(Shape3::ball(r1)), shape(Shape3::ball(r2)));
    let (p1, p2) = (
        BodyState3::default(),
        at(v3(1.0, 0.0, 0.0), v3(0.0, 0.0, 0.0)),
    );
    let (b1, b2) = (s1.aabb3(&p1).unwrap(), s2.aabb3(&p2).unwrap());
    let gap = 1.0 - r1 - r2;
    assert!((boxes_gap3(&b1, &b2) - gap).abs() <= 1e-12);
    assert!((shape_distance3(&s1, &p1, &s2, &p2).unwrap() - gap).abs() <= 1e-12);
    assert!(!boxes_overlap3(&b1, &b2, 0.69) && boxes_overlap3(&b1, &b2, 0.71));
    // A cylinder standing 1 mm above a box top face, tilted by α about y: its lowest rim
    // point is L cos α + R sin α below its centre, so the gap is z_c − that − h_z; the box gap
    // is a lower bound of it.
    let (len, rad, hz, alpha) = (0.03, 0.02, 0.05, 0.3_f64);
    let cub = shape(Shape3::cuboid(0.3, 0.3, hz));
    let cyl = shape(Shape3::cylinder(len, rad));
    let ground = BodyState3::default();
    let q = UnitQuaternion::from_scaled_axis(v3(0.0, alpha, 0.0))
        * UnitQuaternion::from_scaled_axis(v3(0.0, -FRAC_PI_2, 0.0));
    let zc = hz + len * alpha.cos() + rad * alpha.sin() + 1e-3;
    let pose = BodyState3::fixed(v3(0.1, -0.05, zc), q);
    let d = shape_distance3(&cub, &ground, &cyl, &pose).unwrap();
    // GJK on a curved rim: 2.1e-13 m off here; tolerance 1e-11 m (1e-8 of the gap).
    assert!((d - 1e-3).abs() <= 1e-11, "{d}");
    let gap = boxes_gap3(&cub.aabb3(&ground).unwrap(), &cyl.aabb3(&pose).unwrap());
    assert!(gap <= d && gap > 0.0, "{gap} {d}");
}

/// The relative velocity of the contact points: B spinning at ω about z and translating at
/// v, A at rest; the point of B at p moves with v + ω × (p − c_B) (rigid-body kinematics).
#[test]
fn relative_velocity_of_the_contact_points() {
    let (r, delta) = (0.01, 1e-4);
    let floor = shape(Shape3::cuboid(1.0, 1.0, 0.1));
    let ball = shape(Shape3::ball(r));
    let a = at(v3(0.0, 0.0, -0.1), v3(0.0, 0.0, 0.0));
    let c = v3(0.2, 0.0, r - delta);
    let b = BodyState3::new(
        c,
        UnitQuaternion::identity(),
        v3(0.5, 0.0, -0.2),
        v3(0.0, 30.0, 0.0),
    );
    let p = query(&floor, &a, &ball, &b, 0.0)[0];
    let v = p.relative_velocity(&a, &b);
    // The ball's contact point is its bottom c − r e_z: ω × (−r e_z) = −30 r e_x for
    // ω = 30 e_y (e_y × e_z = e_x).
    let want = v3(0.5 - 30.0 * r, 0.0, -0.2);
    assert_vec(v, want);
    // δ̇ = −v·n = 0.2 m/s approaching.
    assert!((-v.dot(&p.normal) - 0.2).abs() <= 1e-12);
}

// ------------------------------------------------------------------------------ allocation

/// Counts the allocations of the current thread (tests run in parallel threads), so that a
/// test can check that a hot path allocates nothing.
struct CountingAllocator;

thread_local! {
    static ALLOCATIONS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

// SAFETY: forwards every call to the system allocator unchanged; the counter is a
// const-initialized thread-local without destructor, so touching it never allocates.
unsafe impl std::alloc::GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: std::alloc::Layout) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        unsafe { std::alloc::System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: std::alloc::Layout) {
        unsafe { std::alloc::System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: std::alloc::Layout, size: usize) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        unsafe { std::alloc::System.realloc(ptr, layout, size) }
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

/// Allocations of 49 queries of `b` resting on a large box, each moved 0.1 mm from the last,
/// after one warm-up query; B's lowest point at `gap` above the box (negative: penetrating).
fn allocations_of_queries(b: &ContactShape3, gap: f64) -> usize {
    let big = shape(Shape3::cuboid(1.0, 1.0, 0.1));
    let ground = BodyState3::default();
    let rv = v3(0.01, -0.02, 0.3);
    let bottom = b.aabb3(&at(v3(0.0, 0.0, 0.0), rv)).unwrap()[2];
    let poses: Vec<BodyState3> = (0..50)
        .map(|k| at(v3(1e-4 * k as f64, 0.0, 0.1 - bottom + gap), rv))
        .collect();
    let mut ws = ShapeContactWorkspace3::new();
    contact_points3(&big, &ground, b, &poses[0], 1e-3, &mut ws).unwrap();
    let before = ALLOCATIONS.with(|c| c.get());
    let mut n = 0;
    for pose in &poses[1..] {
        n += contact_points3(&big, &ground, b, pose, 1e-3, &mut ws)
            .unwrap()
            .len();
    }
    let allocations = ALLOCATIONS.with(|c| c.get()) - before;
    assert!(n >= 49, "{b:?}: {n} points");
    allocations
}

/// The force evaluation's hot path allocates nothing once the workspace has seen the pair:
/// the exact ball path, the box–box manifold and the capsule's segment in contact, and every
/// convex pair within the prediction distance (GJK). A penetrating cylinder, cone or
/// polyhedron goes through parry's EPA, which builds its polytope on the heap at each call (10 and 12
/// allocations per query here): a parry limit, documented in docs/contact.md.
#[test]
fn convex_queries_do_not_allocate_after_warm_up() {
    let penetrating_free = [
        shape(Shape3::ball(0.02)),
        shape(Shape3::cuboid(0.04, 0.03, 0.02)),
        shape(Shape3::capsule(0.03, 0.01)),
    ];
    for b in &penetrating_free {
        assert_eq!(allocations_of_queries(b, -2e-4), 0, "{b:?}");
    }
    let tetra = vec![
        [0.02, 0.0, -0.01],
        [-0.01, 0.02, -0.01],
        [-0.01, -0.02, -0.01],
        [0.0, 0.0, 0.02],
    ];
    let epa = [
        shape(Shape3::cylinder(0.02, 0.03)),
        shape(Shape3::cone(0.02, 0.03)),
        shape(Shape3::convex_polyhedron(tetra)),
    ];
    for b in penetrating_free.iter().chain(&epa) {
        assert_eq!(allocations_of_queries(b, 2e-4), 0, "{b:?}");
    }
    for b in &epa {
        assert!(
            allocations_of_queries(b, -2e-4) > 0,
            "{b:?}: EPA no longer allocates"
        );
    }
}

/// Composite pairs (parry's composite–composite query): a compound box resting δ deep on a
/// flat mesh gives points at depth δ, normal +z; a small triangle mesh held δ *below* a flat
/// mesh (meshes have no solid side) is a gap of δ seen from below: its three vertices at depth
/// −δ within the prediction distance, normal −z (from GJK on a 0.1 mm gap: 1.3e-12 off,
/// tolerance 1e-10).
#[test]
fn composite_pairs_find_points() {
    let floor = flat_mesh(0.0);
    let ground = at(v3(0.0, 0.0, 0.0), v3(0.0, 0.0, 0.0));
    let comp = shape(Shape3::compound(vec![(
        PartPose3::IDENTITY,
        Shape3::cuboid(0.04, 0.03, 0.02).unwrap(),
    )]));
    let delta = 1e-4;
    let pose = at(v3(0.1, 0.2, 0.02 - delta), v3(0.0, 0.0, 0.3));
    let pts = query(&floor, &ground, &comp, &pose, 0.0);
    assert!(!pts.is_empty());
    for p in &pts {
        assert_depth(p.depth, delta);
        assert_vec(p.normal, v3(0.0, 0.0, 1.0));
        assert!((p.point_b.z + delta).abs() <= 1e-12, "{p:?}");
    }
    let corners = [v3(0.0, 0.0, 0.0), v3(0.05, 0.0, 0.0), v3(0.0, 0.05, 0.0)];
    let tri = shape(Shape3::trimesh(
        corners.iter().map(|c| [c.x, c.y, c.z]).collect(),
        vec![[0, 1, 2]],
    ));
    let o = v3(0.1, 0.2, -delta);
    let pts = query(&floor, &ground, &tri, &at(o, v3(0.0, 0.0, 0.0)), 2e-4);
    assert_eq!(pts.len(), 3, "{pts:?}");
    for (p, c) in pts.iter().zip(corners) {
        assert_depth(p.depth, -delta);
        assert!((p.normal - v3(0.0, 0.0, -1.0)).amax() <= 1e-10, "{p:?}");
        assert_vec(p.point_b, o + c);
    }
}

/// Volume enclosed by a triangulated surface, Σ v₀·(v₁ × v₂)/6 (divergence theorem): positive
/// when the triangles turn counter-clockwise seen from outside.
fn enclosed_volume(v: &[[f64; 3]], t: &[[u32; 3]]) -> f64 {
    let p = |k: u32| Vector3::from(v[k as usize]);
    t.iter()
        .map(|&[a, b, c]| p(a).dot(&p(b).cross(&p(c))) / 6.0)
        .sum()
}

/// The drawing surfaces against closed forms: a cuboid's eight corners and volume 8·hx·hy·hz
/// exactly (to rounding), a cylinder along x as an n-gon prism (volume (n/2) r² sin(2π/n)·2h,
/// every vertex within |x| ≤ h and at radius r from the x axis), a ball inscribed (every vertex at
/// r, volume below 4πr³/3 and within 2 % at 32 segments: the inscribed UV polyhedron of 32
/// meridians and 16 latitude steps encloses 98.40 % of the sphere, summed independently over its
/// triangles), a compound as its parts' sum with the
/// parts' poses applied.
#[test]
fn drawing_surfaces_enclose_the_closed_form_volumes() {
    let b = shape(Shape3::cuboid(0.1, 0.2, 0.3));
    let (v, t) = b.surface(16);
    assert_eq!((v.len(), t.len()), (8, 12));
    assert!(v
        .iter()
        .all(|p| (p[0].abs() - 0.1).abs() < 1e-15 && (p[2].abs() - 0.3).abs() < 1e-15));
    let exact = 8.0 * 0.1 * 0.2 * 0.3;
    assert!(
        (enclosed_volume(&v, &t) - exact).abs() < 1e-15,
        "{}",
        enclosed_volume(&v, &t)
    );

    let (h, r, n) = (0.05, 0.02, 24u32);
    let c = shape(Shape3::cylinder(h, r));
    let (v, t) = c.surface(n);
    let prism = 0.5 * n as f64 * r * r * (2.0 * PI / n as f64).sin() * 2.0 * h;
    assert!(
        (enclosed_volume(&v, &t) - prism).abs() < 1e-12 * prism,
        "cylinder volume"
    );
    for p in &v {
        assert!(p[0].abs() <= h * (1.0 + 1e-12), "{p:?} beyond the ends");
        let rho = p[1].hypot(p[2]);
        assert!(
            rho < 1e-15 || (rho - r).abs() < 1e-12 * r,
            "{p:?} off the radius"
        );
    }

    let ball = shape(Shape3::ball(0.01));
    let (v, t) = ball.surface(32);
    assert!(v
        .iter()
        .all(|p| (Vector3::from(*p).norm() - 0.01).abs() < 1e-15));
    let sphere = 4.0 / 3.0 * PI * 1e-6;
    let vol = enclosed_volume(&v, &t);
    assert!(vol < sphere && vol > 0.98 * sphere, "{vol} vs {sphere}");

    let parts = vec![
        (
            PartPose3::new([0.0, 0.0, -0.013], [0.0, 0.0, 0.0]),
            Shape3::Cuboid {
                half_extents: [0.2, 0.0155, 0.0025],
            },
        ),
        (
            PartPose3::new([0.0, 0.013, 0.0], [0.0, 0.0, 0.0]),
            Shape3::Cuboid {
                half_extents: [0.2, 0.0025, 0.0105],
            },
        ),
    ];
    let g = shape(Shape3::compound(parts));
    let (v, t) = g.surface(8);
    assert_eq!((v.len(), t.len()), (16, 24));
    let exact = 8.0 * (0.2 * 0.0155 * 0.0025 + 0.2 * 0.0025 * 0.0105);
    assert!(
        (enclosed_volume(&v, &t) - exact).abs() < 1e-15,
        "compound volume"
    );
    assert!(v[..8].iter().all(|p| (p[2] + 0.013).abs() - 0.0025 < 1e-15));
    assert!(v[8..]
        .iter()
        .all(|p| ((p[1] - 0.013).abs() - 0.0025).abs() < 1e-15));
}
