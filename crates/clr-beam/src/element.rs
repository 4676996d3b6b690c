//! The 2-node planar frame element: linear axial displacement plus Hermite-cubic bending.
//!
//! Local DOF order (u₁, v₁, θ₁, u₂, v₂, θ₂): u along the element axis from node 1 to node 2, v
//! normal to it (the axis rotated by +90°), θ = dv/dx counter-clockwise. Matrices are the closed
//! forms of J. S. Przemieniecki, *Theory of Matrix Structural Analysis*, McGraw-Hill 1968
//! (§5.6 stiffness, §11.4 consistent mass, §15.3 geometric stiffness), also in R. D. Cook,
//! D. S. Malkus, M. E. Plesha, R. J. Witt, *Concepts and Applications of Finite Element
//! Analysis*, 4th ed., Wiley 2002 (eqs. 2.3-5, 11.3-5, 18.3-5). The lumped mass is the HRZ
//! diagonal scaling (Hinton, Rock, Zienkiewicz, *Earthq. Eng. Struct. Dyn.* 4 (1976) 245–249).

use nalgebra::{SMatrix, SVector};

/// 6×6 element matrix.
pub type Mat6 = SMatrix<f64, 6, 6>;
/// 6-vector of element DOF.
pub type Vec6 = SVector<f64, 6>;

/// Mass discretization of the elements.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MassKind {
    /// Consistent mass ∫ρA NᵀN dx (Przemieniecki 1968 §11.4).
    #[default]
    Consistent,
    /// HRZ lumped (diagonal) mass: translational ρAL/2 per node, rotational ρAL³/78 per node.
    Lumped,
}

/// Geometry and section data of one element, all SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameElement {
    /// Node indices (start, end).
    pub nodes: [usize; 2],
    /// Length L (m).
    pub length: f64,
    /// cos α of the element axis angle α to the global x axis.
    pub cos: f64,
    /// sin α.
    pub sin: f64,
    /// Axial rigidity EA (N).
    pub ea: f64,
    /// Bending rigidity EI (N·m²).
    pub ei: f64,
    /// Mass per unit length ρA (kg/m).
    pub rho_a: f64,
    /// Section depth h (m).
    pub depth: f64,
    /// Axial force P (N, tension positive) used by the geometric stiffness.
    pub axial_force: f64,
}

impl FrameElement {
    /// Global DOF indices of the element (3 per node: u, v, θ).
    pub fn dofs(&self) -> [usize; 6] {
        let [a, b] = self.nodes;
        [3 * a, 3 * a + 1, 3 * a + 2, 3 * b, 3 * b + 1, 3 * b + 2]
    }

    /// Local elastic stiffness (Przemieniecki 1968 eq. 5.116 reduced to the plane).
    pub fn local_stiffness(&self) -> Mat6 {
        let l = self.length;
        let a = self.ea / l;
        let b = self.ei / l.powi(3);
        let mut k = Mat6::zeros();
        k[(0, 0)] = a;
        k[(0, 3)] = -a;
        k[(3, 0)] = -a;
        k[(3, 3)] = a;
        let kb = [
            [12.0, 6.0 * l, -12.0, 6.0 * l],
            [6.0 * l, 4.0 * l * l, -6.0 * l, 2.0 * l * l],
            [-12.0, -6.0 * l, 12.0, -6.0 * l],
            [6.0 * l, 2.0 * l * l, -6.0 * l, 4.0 * l * l],
        ];
        scatter_bending(&mut k, &kb, b);
        k
    }

    /// Local geometric stiffness for the axial force P (tension positive), consistent with the
    /// Hermite shape functions (Przemieniecki 1968 eq. 15.46; Cook et al. 2002 eq. 18.3-5).
    pub fn local_geometric_stiffness(&self) -> Mat6 {
        let l = self.length;
        let mut k = Mat6::zeros();
        let kg = [
            [36.0, 3.0 * l, -36.0, 3.0 * l],
            [3.0 * l, 4.0 * l * l, -3.0 * l, -l * l],
            [-36.0, -3.0 * l, 36.0, -3.0 * l],
            [3.0 * l, -l * l, -3.0 * l, 4.0 * l * l],
        ];
        scatter_bending(&mut k, &kg, self.axial_force / (30.0 * l));
        k
    }

    /// Local mass matrix of the chosen kind (consistent: Przemieniecki 1968 eq. 11.40).
    pub fn local_mass(&self, kind: MassKind) -> Mat6 {
        let l = self.length;
        let m = self.rho_a * l;
        let mut mm = Mat6::zeros();
        match kind {
            MassKind::Consistent => {
                mm[(0, 0)] = m / 3.0;
                mm[(3, 3)] = m / 3.0;
                mm[(0, 3)] = m / 6.0;
                mm[(3, 0)] = m / 6.0;
                let mb = [
                    [156.0, 22.0 * l, 54.0, -13.0 * l],
                    [22.0 * l, 4.0 * l * l, 13.0 * l, -3.0 * l * l],
                    [54.0, 13.0 * l, 156.0, -22.0 * l],
                    [-13.0 * l, -3.0 * l * l, -22.0 * l, 4.0 * l * l],
                ];
                scatter_bending(&mut mm, &mb, m / 420.0);
            }
            MassKind::Lumped => {
                // HRZ: consistent diagonal scaled so that the translational mass is m.
                for i in [0, 1, 3, 4] {
                    mm[(i, i)] = m / 2.0;
                }
                mm[(2, 2)] = m * l * l / 78.0;
                mm[(5, 5)] = m * l * l / 78.0;
            }
        }
        mm
    }

    /// Transformation T with local = T · global (block diagonal rotation by −α).
    pub fn rotation(&self) -> Mat6 {
        let (c, s) = (self.cos, self.sin);
        let mut t = Mat6::zeros();
        for b in [0, 3] {
            t[(b, b)] = c;
            t[(b, b + 1)] = s;
            t[(b + 1, b)] = -s;
            t[(b + 1, b + 1)] = c;
            t[(b + 2, b + 2)] = 1.0;
        }
        t
    }

    /// Global stiffness Tᵀ (K_e + K_g) T (geometric part included when P ≠ 0).
    pub fn global_stiffness(&self) -> Mat6 {
        let t = self.rotation();
        let mut k = self.local_stiffness();
        if self.axial_force != 0.0 {
            k += self.local_geometric_stiffness();
        }
        t.transpose() * k * t
    }

    /// Global mass Tᵀ M T.
    pub fn global_mass(&self, kind: MassKind) -> Mat6 {
        let t = self.rotation();
        t.transpose() * self.local_mass(kind) * t
    }

    /// Local shape functions at ξ = x/L ∈ [0, 1]: rows (u, v) of the 2×6 matrix N with
    /// (u, v)ᵀ = N d_local; u linear, v Hermite cubic (Cook et al. 2002 eq. 3.2-6).
    pub fn local_shape(&self, xi: f64) -> [[f64; 6]; 2] {
        let l = self.length;
        let (h1, h2, h3, h4) = hermite(xi);
        [
            [1.0 - xi, 0.0, 0.0, xi, 0.0, 0.0],
            [0.0, h1, l * h2, 0.0, h3, l * h4],
        ]
    }

    /// Rows mapping local DOF to (du/dx, dv/dx, d²v/dx²) at ξ.
    pub fn local_derivative_rows(&self, xi: f64) -> [[f64; 6]; 3] {
        let l = self.length;
        let d1 = [
            -6.0 * xi + 6.0 * xi * xi,
            1.0 - 4.0 * xi + 3.0 * xi * xi,
            6.0 * xi - 6.0 * xi * xi,
            -2.0 * xi + 3.0 * xi * xi,
        ];
        let d2 = [
            -6.0 + 12.0 * xi,
            -4.0 + 6.0 * xi,
            6.0 - 12.0 * xi,
            -2.0 + 6.0 * xi,
        ];
        [
            [-1.0 / l, 0.0, 0.0, 1.0 / l, 0.0, 0.0],
            [0.0, d1[0] / l, d1[1], 0.0, d1[2] / l, d1[3]],
            [
                0.0,
                d2[0] / (l * l),
                d2[1] / l,
                0.0,
                d2[2] / (l * l),
                d2[3] / l,
            ],
        ]
    }

    /// Consistent nodal loads (global) of a uniform load with local components (axial p,
    /// transverse q) in N/m: (pL/2, qL/2, qL²/12, pL/2, qL/2, −qL²/12) rotated to global.
    pub fn uniform_load(&self, axial: f64, transverse: f64) -> Vec6 {
        let l = self.length;
        let f = Vec6::from([
            axial * l / 2.0,
            transverse * l / 2.0,
            transverse * l * l / 12.0,
            axial * l / 2.0,
            transverse * l / 2.0,
            -transverse * l * l / 12.0,
        ]);
        self.rotation().transpose() * f
    }
}

/// Hermite cubics H₁…H₄ at ξ ∈ [0, 1] (v = H₁v₁ + H₂Lθ₁ + H₃v₂ + H₄Lθ₂).
pub fn hermite(xi: f64) -> (f64, f64, f64, f64) {
    let x2 = xi * xi;
    let x3 = x2 * xi;
    (
        1.0 - 3.0 * x2 + 2.0 * x3,
        xi - 2.0 * x2 + x3,
        3.0 * x2 - 2.0 * x3,
        -x2 + x3,
    )
}

fn scatter_bending(m: &mut Mat6, b: &[[f64; 4]; 4], scale: f64) {
    const IDX: [usize; 4] = [1, 2, 4, 5];
    for (i, row) in b.iter().enumerate() {
        for (j, v) in row.iter().enumerate() {
            m[(IDX[i], IDX[j])] += scale * v;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn element(angle: f64) -> FrameElement {
        FrameElement {
            nodes: [0, 1],
            length: 0.7,
            cos: angle.cos(),
            sin: angle.sin(),
            ea: 3.0e6,
            ei: 2.0e3,
            rho_a: 1.3,
            depth: 0.01,
            axial_force: 250.0,
        }
    }

    /// 4-point Gauss–Legendre on [0, 1] (exact for polynomials up to degree 7).
    fn gauss4() -> [(f64, f64); 4] {
        let a = (3.0 / 7.0 - 2.0 / 7.0 * (6.0f64 / 5.0).sqrt()).sqrt();
        let b = (3.0 / 7.0 + 2.0 / 7.0 * (6.0f64 / 5.0).sqrt()).sqrt();
        let wa = (18.0 + 30f64.sqrt()) / 36.0;
        let wb = (18.0 - 30f64.sqrt()) / 36.0;
        [
            (0.5 - 0.5 * b, 0.5 * wb),
            (0.5 - 0.5 * a, 0.5 * wa),
            (0.5 + 0.5 * a, 0.5 * wa),
            (0.5 + 0.5 * b, 0.5 * wb),
        ]
    }

    /// The closed-form matrices equal the integrals ∫EA u'ᵀu' + EI v''ᵀv'', ∫ρA NᵀN and
    /// ∫P v'ᵀv' evaluated by exact Gauss quadrature of the shape functions (an independent
    /// formulation of the same element).
    #[test]
    fn closed_forms_equal_quadrature_of_shape_functions() {
        let e = element(0.0);
        let (mut k, mut m, mut kg) = (Mat6::zeros(), Mat6::zeros(), Mat6::zeros());
        for (xi, w) in gauss4() {
            let n = e.local_shape(xi);
            let d = e.local_derivative_rows(xi);
            let wl = w * e.length;
            for i in 0..6 {
                for j in 0..6 {
                    k[(i, j)] += wl * (e.ea * d[0][i] * d[0][j] + e.ei * d[2][i] * d[2][j]);
                    m[(i, j)] += wl * e.rho_a * (n[0][i] * n[0][j] + n[1][i] * n[1][j]);
                    kg[(i, j)] += wl * e.axial_force * d[1][i] * d[1][j];
                }
            }
        }
        assert_relative_eq!(k, e.local_stiffness(), max_relative = 1e-12, epsilon = 1e-9);
        assert_relative_eq!(
            m,
            e.local_mass(MassKind::Consistent),
            max_relative = 1e-12,
            epsilon = 1e-15
        );
        assert_relative_eq!(
            kg,
            e.local_geometric_stiffness(),
            max_relative = 1e-12,
            epsilon = 1e-12
        );
    }

    /// Rigid-body motions of a rotated element produce no elastic force; the total mass of a
    /// rigid translation is ρAL in any orientation.
    #[test]
    fn rigid_body_modes_and_mass() {
        let e = FrameElement {
            axial_force: 0.0,
            ..element(0.83)
        };
        let k = e.global_stiffness();
        let (x1, y1) = (0.2, -0.1);
        let (x2, y2) = (x1 + e.length * e.cos, y1 + e.length * e.sin);
        let tx = Vec6::from([1.0, 0.0, 0.0, 1.0, 0.0, 0.0]);
        let ty = Vec6::from([0.0, 1.0, 0.0, 0.0, 1.0, 0.0]);
        let rot = Vec6::from([-y1, x1, 1.0, -y2, x2, 1.0]);
        let scale = k.amax();
        for q in [tx, ty, rot] {
            assert!((k * q).amax() < 1e-12 * scale);
        }
        for kind in [MassKind::Consistent, MassKind::Lumped] {
            let m = e.global_mass(kind);
            assert_relative_eq!(
                (tx.transpose() * m * tx)[0],
                e.rho_a * e.length,
                max_relative = 1e-13
            );
            assert_relative_eq!(
                (ty.transpose() * m * ty)[0],
                e.rho_a * e.length,
                max_relative = 1e-13
            );
        }
    }

    /// Uniform load vector equals ∫ Nᵀ q dx by quadrature.
    #[test]
    fn uniform_load_is_consistent() {
        let e = element(0.0);
        let (p, q) = (3.0, -7.0);
        let mut f = [0.0; 6];
        for (xi, w) in gauss4() {
            let n = e.local_shape(xi);
            for i in 0..6 {
                f[i] += w * e.length * (n[0][i] * p + n[1][i] * q);
            }
        }
        let fe = e.uniform_load(p, q);
        for i in 0..6 {
            assert_relative_eq!(fe[i], f[i], max_relative = 1e-13, epsilon = 1e-14);
        }
    }
}
