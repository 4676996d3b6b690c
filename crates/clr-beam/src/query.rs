//! Queries of a deformed beam at arc length s along a chain of elements: displacement, slope,
//! curvature, bending moment, surface point and outward normal on either face, their velocities,
//! and the rows mapping a point force at s to generalized nodal forces.
//!
//! Linear (small-deflection) Euler–Bernoulli kinematics with the element interpolation of
//! [`crate::element`]: on an element of axis angle α, the local displacements are u(ξ) (linear)
//! and v(ξ) (Hermite cubic), the cross-section rotation is θ = dv/dx, the curvature κ = d²v/dx²
//! and the bending moment M = EI κ (Cook et al. 2002 §2.3). The face at signed offset e = ±h/2
//! along the normal n = (−sin(α+θ), cos(α+θ)) is at r₀ + d + e n, its outward normal is ±n.
//!
//! Each query allocates nothing and finds the element by binary search, O(log n).

use crate::element::FrameElement;
use crate::error::BeamError;
use crate::model::BeamModel;

/// A chain of elements traversed from arc length 0 to its length.
#[derive(Debug, Clone)]
pub struct Path {
    /// Elements oriented along the path.
    elements: Vec<FrameElement>,
    /// Start position (undeformed) of each element (m).
    start: Vec<[f64; 2]>,
    /// Arc length at the start of each element (m).
    s_start: Vec<f64>,
    /// Model index of each element.
    ids: Vec<usize>,
    length: f64,
    n_dof: usize,
}

/// Which face of the beam (for a section of depth h).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Face {
    /// The face at +h/2 along the path's left normal (the axis rotated by +90°).
    Upper,
    /// The face at −h/2.
    Lower,
}

impl Face {
    fn sign(self) -> f64 {
        match self {
            Face::Upper => 1.0,
            Face::Lower => -1.0,
        }
    }
}

/// State of the centerline at an arc length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeamPoint {
    /// Element index (in the model) containing the point.
    pub element: usize,
    /// Local coordinate ξ ∈ [0, 1] along that element (in the path direction).
    pub xi: f64,
    /// Undeformed centerline position (m).
    pub reference: [f64; 2],
    /// Displacement (m), global axes.
    pub displacement: [f64; 2],
    /// Velocity (m/s), global axes.
    pub velocity: [f64; 2],
    /// Cross-section rotation θ = dv/ds (rad, counter-clockwise).
    pub slope: f64,
    /// dθ/dt (rad/s).
    pub slope_rate: f64,
    /// Curvature κ = d²v/ds² (1/m).
    pub curvature: f64,
    /// Bending moment M = EI κ (N·m).
    pub bending_moment: f64,
    /// Axial strain du/ds (–).
    pub axial_strain: f64,
}

/// A point on a face of the deformed beam.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// Position (m).
    pub position: [f64; 2],
    /// Velocity (m/s).
    pub velocity: [f64; 2],
    /// Outward unit normal.
    pub normal: [f64; 2],
    /// Time derivative of the outward normal (1/s).
    pub normal_rate: [f64; 2],
}

/// Generalized nodal forces of a point force (F_x, F_y):
/// `Q[dofs[j]] += fx[j] * F_x + fy[j] * F_y`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadRow {
    /// Full DOF indices.
    pub dofs: [usize; 6],
    /// Coefficients of F_x.
    pub fx: [f64; 6],
    /// Coefficients of F_y.
    pub fy: [f64; 6],
}

/// Interpolation rows of a path at an arc length s, for Jacobians of surface queries (e.g. the
/// derivative of a contact point on a face with respect to s and to the nodal displacements q):
/// the centerline displacement is d = (x·q_e, y·q_e), the cross-section rotation θ = slope·q_e,
/// with q_e = `q[dofs]` (global axes); `dx`, `dy`, `curvature` are the derivatives of `x`, `y`,
/// `slope` with respect to s (the rows of du/ds, dv/ds and κ = d²v/ds² in global axes). On the
/// face at offset e = ±h/2 the point is `reference + d + e n(α + θ)` with n(φ) = (−sin φ,
/// cos φ) and α the axis angle (`axis` = (cos α, sin α) = d reference/ds), as in
/// [`Path::surface`]. At a node the rows are those of the element [`Path::surface`] uses there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeRows {
    /// Full DOF indices of the element's six DOF.
    pub dofs: [usize; 6],
    /// Undeformed centerline position at s (m).
    pub reference: [f64; 2],
    /// Unit axis direction (cos α, sin α) of the element (the derivative of `reference`).
    pub axis: [f64; 2],
    /// Global x displacement row (m per unit DOF).
    pub x: [f64; 6],
    /// Global y displacement row.
    pub y: [f64; 6],
    /// d`x`/ds (1/m).
    pub dx: [f64; 6],
    /// d`y`/ds (1/m).
    pub dy: [f64; 6],
    /// Cross-section rotation row θ = dv/ds (rad per unit DOF).
    pub slope: [f64; 6],
    /// d`slope`/ds: the curvature row (1/m).
    pub curvature: [f64; 6],
    /// Section depth h of the element (m).
    pub depth: f64,
}

struct Local {
    k: usize,
    xi: f64,
}

impl Path {
    /// The path through `elements` of `model`, in order; consecutive elements must share a
    /// node (each is oriented along the path).
    pub fn new(model: &BeamModel, elements: &[usize]) -> Result<Self, BeamError> {
        if elements.is_empty() {
            return Err(BeamError::NoElements);
        }
        let mut out: Vec<FrameElement> = Vec::with_capacity(elements.len());
        for (idx, &e) in elements.iter().enumerate() {
            let el = *model.element(e)?;
            let next = elements
                .get(idx + 1)
                .map(|&n| model.element(n))
                .transpose()?;
            let flip = match out.last() {
                Some(prev) => {
                    if el.nodes[0] == prev.nodes[1] {
                        false
                    } else if el.nodes[1] == prev.nodes[1] {
                        true
                    } else {
                        return Err(BeamError::NotAChain(elements[idx - 1], e));
                    }
                }
                // First element: orient towards the next one.
                None => {
                    next.is_some_and(|n| el.nodes[0] == n.nodes[0] || el.nodes[0] == n.nodes[1])
                }
            };
            let mut el = el;
            if flip {
                el.nodes.swap(0, 1);
                el.cos = -el.cos;
                el.sin = -el.sin;
            }
            out.push(el);
        }
        let mut s_start = Vec::with_capacity(out.len());
        let mut start = Vec::with_capacity(out.len());
        let mut s = 0.0;
        for el in &out {
            s_start.push(s);
            start.push(model.nodes()[el.nodes[0]]);
            s += el.length;
        }
        Ok(Self {
            elements: out,
            start,
            s_start,
            length: s,
            n_dof: model.n_dof(),
            ids: elements.to_vec(),
        })
    }

    /// Undeformed arc length at the start of each element along the path, m.
    pub fn element_starts(&self) -> &[f64] {
        &self.s_start
    }

    /// Path length (m).
    pub fn length(&self) -> f64 {
        self.length
    }

    fn locate(&self, s: f64, q_len: usize, qd_len: usize) -> Result<Local, BeamError> {
        let tol = 1e-12 * self.length;
        if !(s >= -tol && s <= self.length + tol) {
            return Err(BeamError::OutsideBeam {
                s,
                length: self.length,
            });
        }
        for (what, got) in [("displacement vector", q_len), ("velocity vector", qd_len)] {
            if got != self.n_dof {
                return Err(BeamError::Length {
                    what,
                    got,
                    expected: self.n_dof,
                });
            }
        }
        let k = self
            .s_start
            .partition_point(|&x| x <= s)
            .clamp(1, self.elements.len())
            - 1;
        let el = &self.elements[k];
        let xi = ((s - self.s_start[k]) / el.length).clamp(0.0, 1.0);
        Ok(Local { k, xi })
    }

    /// Local DOF of element k from global vector q.
    fn local_dofs(&self, k: usize, q: &[f64]) -> [f64; 6] {
        let el = &self.elements[k];
        let d = el.dofs();
        let (c, s) = (el.cos, el.sin);
        let mut out = [0.0; 6];
        for b in [0, 3] {
            let (x, y) = (q[d[b]], q[d[b + 1]]);
            out[b] = c * x + s * y;
            out[b + 1] = -s * x + c * y;
            out[b + 2] = q[d[b + 2]];
        }
        out
    }

    /// Centerline state at arc length s (m) for nodal displacements `q` and velocities `qd`
    /// (full DOF ordering, 3 per node).
    pub fn point(&self, s: f64, q: &[f64], qd: &[f64]) -> Result<BeamPoint, BeamError> {
        let Local { k, xi } = self.locate(s, q.len(), qd.len())?;
        let el = &self.elements[k];
        let n = el.local_shape(xi);
        let dr = el.local_derivative_rows(xi);
        let dl = self.local_dofs(k, q);
        let vl = self.local_dofs(k, qd);
        let dotp = |r: &[f64; 6], v: &[f64; 6]| r.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
        let (c, sn) = (el.cos, el.sin);
        let to_global = |u: f64, v: f64| [c * u - sn * v, sn * u + c * v];
        let curvature = dotp(&dr[2], &dl);
        let p0 = self.start[k];
        Ok(BeamPoint {
            element: self.ids[k],
            xi,
            reference: [p0[0] + xi * el.length * c, p0[1] + xi * el.length * sn],
            displacement: to_global(dotp(&n[0], &dl), dotp(&n[1], &dl)),
            velocity: to_global(dotp(&n[0], &vl), dotp(&n[1], &vl)),
            slope: dotp(&dr[1], &dl),
            slope_rate: dotp(&dr[1], &vl),
            curvature,
            bending_moment: el.ei * curvature,
            axial_strain: dotp(&dr[0], &dl),
        })
    }

    /// Point on a face of the deformed beam at arc length s, for the section depth h of the
    /// element there (m).
    pub fn surface(
        &self,
        s: f64,
        face: Face,
        q: &[f64],
        qd: &[f64],
    ) -> Result<SurfacePoint, BeamError> {
        let h = self.elements[self.locate(s, q.len(), qd.len())?.k].depth;
        self.surface_with_depth(s, face, h, q, qd)
    }

    /// Point on a face at offset ±h/2 from the centerline, for a given thickness h (m).
    pub fn surface_with_depth(
        &self,
        s: f64,
        face: Face,
        h: f64,
        q: &[f64],
        qd: &[f64],
    ) -> Result<SurfacePoint, BeamError> {
        let p = self.point(s, q, qd)?;
        let k = self.locate(s, q.len(), qd.len())?.k;
        let el = &self.elements[k];
        let e = face.sign() * 0.5 * h;
        let phi = el.sin.atan2(el.cos) + p.slope;
        let (sp, cp) = phi.sin_cos();
        let nrm = [-sp, cp];
        let tan = [cp, sp];
        Ok(SurfacePoint {
            position: [
                p.reference[0] + p.displacement[0] + e * nrm[0],
                p.reference[1] + p.displacement[1] + e * nrm[1],
            ],
            velocity: [
                p.velocity[0] - e * p.slope_rate * tan[0],
                p.velocity[1] - e * p.slope_rate * tan[1],
            ],
            normal: [face.sign() * nrm[0], face.sign() * nrm[1]],
            normal_rate: [
                -face.sign() * p.slope_rate * tan[0],
                -face.sign() * p.slope_rate * tan[1],
            ],
        })
    }

    /// Rows of global shape functions at s: (x, y displacement rows, rotation row), each over
    /// the element's 6 global DOF.
    fn global_rows(&self, k: usize, xi: f64) -> ([f64; 6], [f64; 6], [f64; 6]) {
        let el = &self.elements[k];
        let n = el.local_shape(xi);
        let dr = el.local_derivative_rows(xi);
        let (c, s) = (el.cos, el.sin);
        let mut rx = [0.0; 6];
        let mut ry = [0.0; 6];
        for j in 0..6 {
            rx[j] = c * n[0][j] - s * n[1][j];
            ry[j] = s * n[0][j] + c * n[1][j];
        }
        (
            to_global_dofs(el, rx),
            to_global_dofs(el, ry),
            to_global_dofs(el, dr[1]),
        )
    }

    /// Interpolation rows at arc length s (m) and their s-derivatives ([`ShapeRows`]).
    pub fn shape_rows(&self, s: f64) -> Result<ShapeRows, BeamError> {
        let Local { k, xi } = self.locate(s, self.n_dof, self.n_dof)?;
        let el = &self.elements[k];
        let (x, y, slope) = self.global_rows(k, xi);
        let dr = el.local_derivative_rows(xi);
        let (c, sn) = (el.cos, el.sin);
        // d/ds of the local (u, v) rows are the (du/dx, dv/dx) rows; rotate them as `x`, `y`
        let mut dl = [[0.0; 6]; 2];
        for j in 0..6 {
            dl[0][j] = c * dr[0][j] - sn * dr[1][j];
            dl[1][j] = sn * dr[0][j] + c * dr[1][j];
        }
        let p0 = self.start[k];
        Ok(ShapeRows {
            dofs: el.dofs(),
            reference: [p0[0] + xi * el.length * c, p0[1] + xi * el.length * sn],
            axis: [c, sn],
            x,
            y,
            dx: to_global_dofs(el, dl[0]),
            dy: to_global_dofs(el, dl[1]),
            slope,
            curvature: to_global_dofs(el, dr[2]),
            depth: el.depth,
        })
    }

    /// Shape-function rows mapping a point force on the centerline at s to generalized nodal
    /// forces (Q = Nᵀ F, the work-equivalent loads).
    pub fn load_row(&self, s: f64) -> Result<LoadRow, BeamError> {
        let Local { k, xi } = self.locate(s, self.n_dof, self.n_dof)?;
        let (fx, fy, _) = self.global_rows(k, xi);
        Ok(LoadRow {
            dofs: self.elements[k].dofs(),
            fx,
            fy,
        })
    }

    /// Rows mapping a point force applied on a face (offset ±h/2, h the element's section
    /// depth) at s to generalized nodal forces, linearized about the deformed state `q`: the
    /// force also acts through the lever arm e n(θ), δr = N δq − e t δθ.
    pub fn surface_load_row(&self, s: f64, face: Face, q: &[f64]) -> Result<LoadRow, BeamError> {
        let Local { k, xi } = self.locate(s, q.len(), q.len())?;
        let el = &self.elements[k];
        let (mut fx, mut fy, rt) = self.global_rows(k, xi);
        let dl = self.local_dofs(k, q);
        let slope: f64 = el.local_derivative_rows(xi)[1]
            .iter()
            .zip(&dl)
            .map(|(a, b)| a * b)
            .sum();
        let phi = el.sin.atan2(el.cos) + slope;
        let (sp, cp) = phi.sin_cos();
        let e = face.sign() * 0.5 * el.depth;
        for j in 0..6 {
            fx[j] -= e * cp * rt[j];
            fy[j] -= e * sp * rt[j];
        }
        Ok(LoadRow {
            dofs: el.dofs(),
            fx,
            fy,
        })
    }
}

/// A row over an element's local DOF → the same row over its global DOF via T (local = T
/// global).
fn to_global_dofs(el: &FrameElement, r: [f64; 6]) -> [f64; 6] {
    let (c, s) = (el.cos, el.sin);
    let mut g = [0.0; 6];
    for b in [0, 3] {
        g[b] = r[b] * c - r[b + 1] * s;
        g[b + 1] = r[b] * s + r[b + 1] * c;
        g[b + 2] = r[b + 2];
    }
    g
}

impl BeamModel {
    /// The path through all elements in model order (e.g. a beam made by
    /// [`BeamModel::straight`]).
    pub fn path(&self) -> Result<Path, BeamError> {
        let ids: Vec<usize> = (0..self.elements().len()).collect();
        Path::new(self, &ids)
    }
}
