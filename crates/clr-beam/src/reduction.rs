//! Reduction for multibody use: modal truncation and Craig–Bampton, and the invariants of a
//! floating-frame-of-reference formulation.
//!
//! Craig–Bampton (R. R. Craig, M. C. C. Bampton, *AIAA J.* 6 (1968) 1313–1319): the free DOF are
//! split into boundary DOF b (the free DOF of the interface nodes) and interior DOF i. The
//! reduced coordinates are q_r = (u_b, η), and the full displacements are u = T q_r with
//! T = [I 0; Ψ Φ], Ψ = −K_ii⁻¹ K_ib the static constraint modes and Φ the lowest fixed-interface
//! normal modes (M_ii-normalized). M_r = Tᵀ M T, K_r = Tᵀ K T, C_r = α M_r + β K_r.
//!
//! Floating-frame invariants (A. A. Shabana, *Dynamics of Multibody Systems*, 4th ed. 2020,
//! §5.5, planar case): with the translational field r = N q of the elements, the consistent mass
//! M_t = ∫ρA NᵀN dx and the skew mass S = ∫ρA Nᵀ J N dx (aᵀJb = a_x b_y − a_y b_x), the
//! invariants follow exactly from the interpolation (which reproduces rigid translations,
//! rotations and the undeformed straight elements):
//! m = t_xᵀ M_t t_x, first moment (t_xᵀ M_t q₀, t_yᵀ M_t q₀), polar inertia q₀ᵀ M_t q₀ about the
//! model origin, modal first moments t_{x,y}ᵀ M_t T, rotation coupling ∫ρ r₀ × φ_k = q_rotᵀ M_t T,
//! modal mass Tᵀ M_t T and modal skew integrals ∫ρ φ_k × φ_l = Tᵀ S T, where q₀ = (x, y, 0) and
//! q_rot = (−y, x, 1) per node.

use faer::linalg::solvers::Solve;
use faer::{Mat, MatRef};

use crate::element::Mat6;
use crate::error::BeamError;
use crate::modal::lowest_modes;
use crate::model::{checked_cholesky, restrict, BeamModel};

/// A reduced model: q_r ↦ full nodal displacements u = T q_r.
#[derive(Debug, Clone)]
pub struct ReducedModel {
    /// Reduced mass Tᵀ M T.
    pub mass: Mat<f64>,
    /// Reduced stiffness Tᵀ K T.
    pub stiffness: Mat<f64>,
    /// Reduced Rayleigh damping α M_r + β K_r.
    pub damping: Mat<f64>,
    /// T: full DOF (3 per node) × reduced coordinates; rows of constrained DOF are zero.
    pub transformation: Mat<f64>,
    /// Full DOF indices of the boundary coordinates (the first entries of q_r); empty for
    /// modal truncation.
    pub boundary_dofs: Vec<usize>,
    /// Circular frequencies (rad/s) of the kept modes (free modes for modal truncation,
    /// fixed-interface modes for Craig–Bampton).
    pub mode_omega: Vec<f64>,
    /// Floating-frame invariants of the reduced coordinates.
    pub invariants: FloatingFrameInvariants,
}

/// Inertia invariants of a flexible body for the floating-frame formulation, with respect to
/// the model's coordinate origin and axes (Shabana 2020 §5.5, planar).
#[derive(Debug, Clone)]
pub struct FloatingFrameInvariants {
    /// Mass m = ∫ρ dV (kg).
    pub mass: f64,
    /// First moment ∫ρ r₀ dV (kg·m).
    pub first_moment: [f64; 2],
    /// Polar moment of inertia ∫ρ |r₀|² dV about the origin (kg·m²).
    pub polar_inertia: f64,
    /// Modal first moments ∫ρ φ_k dV, one [x, y] pair per reduced coordinate.
    pub shape_first_moment: Vec<[f64; 2]>,
    /// Rotation coupling ∫ρ r₀ × φ_k dV per reduced coordinate.
    pub rotation_coupling: Vec<f64>,
    /// ∫ρ φ_kᵀ φ_l dV (translational modal mass, r × r).
    pub modal_mass: Mat<f64>,
    /// ∫ρ φ_k × φ_l dV (skew-symmetric, r × r).
    pub modal_skew: Mat<f64>,
}

impl BeamModel {
    /// Modal truncation onto the lowest `n` modes (M_r = I, K_r = diag ω² up to round-off).
    pub fn modal_truncation(&self, n: usize) -> Result<ReducedModel, BeamError> {
        let modes = self.modes(n)?;
        self.reduce_with(modes.shapes, Vec::new(), modes.omega)
    }

    /// Craig–Bampton reduction keeping every free DOF of `interface_nodes` as boundary DOF and
    /// `n_modes` fixed-interface normal modes. Errors: no free interface DOF, more modes than
    /// interior DOF, interior stiffness singular (a part that floats when the interface is fixed).
    pub fn craig_bampton(
        &self,
        interface_nodes: &[usize],
        n_modes: usize,
    ) -> Result<ReducedModel, BeamError> {
        let map = self.dof_map()?;
        for &n in interface_nodes {
            self.check_node(n)?;
        }
        let is_b = |d: usize| interface_nodes.contains(&(d / 3));
        let b: Vec<usize> = map.free.iter().copied().filter(|&d| is_b(d)).collect();
        let i: Vec<usize> = map.free.iter().copied().filter(|&d| !is_b(d)).collect();
        if b.is_empty() {
            return Err(BeamError::NoInterface);
        }
        if n_modes > i.len() {
            return Err(BeamError::TooManyInteriorModes {
                requested: n_modes,
                available: i.len(),
            });
        }
        let k = self.stiffness_dense()?;
        let m = self.mass_dense()?;
        let (nb, ni) = (b.len(), i.len());
        let mut t = Mat::<f64>::zeros(self.n_dof(), nb + n_modes);
        for (c, &d) in b.iter().enumerate() {
            t[(d, c)] = 1.0;
        }
        let mut omega = Vec::new();
        if ni > 0 {
            let kii = restrict(k.as_ref(), &i, &i);
            let kib = restrict(k.as_ref(), &i, &b);
            let llt = checked_cholesky(kii.as_ref(), &i)?;
            let mut psi = -kib;
            llt.solve_in_place(psi.as_mut());
            for (r, &d) in i.iter().enumerate() {
                for c in 0..nb {
                    t[(d, c)] = psi[(r, c)];
                }
            }
            if n_modes > 0 {
                let mii = restrict(m.as_ref(), &i, &i);
                let (lam, phi) =
                    lowest_modes(kii.as_ref(), mii.as_ref(), n_modes, self.lambda_ref())?;
                omega = lam.iter().map(|l| l.sqrt()).collect();
                for (r, &d) in i.iter().enumerate() {
                    for c in 0..n_modes {
                        t[(d, nb + c)] = phi[(r, c)];
                    }
                }
            }
        }
        self.reduce_with(t, b, omega)
    }

    fn reduce_with(
        &self,
        t: Mat<f64>,
        boundary_dofs: Vec<usize>,
        mode_omega: Vec<f64>,
    ) -> Result<ReducedModel, BeamError> {
        let k = self.stiffness_dense()?;
        let m = self.mass_dense()?;
        let mass = project(m.as_ref(), t.as_ref());
        let stiffness = project(k.as_ref(), t.as_ref());
        let (a, bb) = self.rayleigh();
        let damping = Mat::from_fn(mass.nrows(), mass.ncols(), |i, j| {
            a * mass[(i, j)] + bb * stiffness[(i, j)]
        });
        let invariants = self.invariants(t.as_ref())?;
        Ok(ReducedModel {
            mass,
            stiffness,
            damping,
            transformation: t,
            boundary_dofs,
            mode_omega,
            invariants,
        })
    }

    /// Floating-frame invariants for shape functions given as the columns of `t` (full DOF ×
    /// r), e.g. [`ReducedModel::transformation`] or [`crate::Modes::shapes`].
    pub fn invariants(&self, t: MatRef<'_, f64>) -> Result<FloatingFrameInvariants, BeamError> {
        let n = self.n_dof();
        if t.nrows() != n {
            return Err(BeamError::Length {
                what: "shape matrix rows",
                got: t.nrows(),
                expected: n,
            });
        }
        let mt = self.consistent_mass_dense()?;
        let skew = self.skew_mass_dense();
        let nodes = self.nodes();
        let vec_of = |f: &dyn Fn(usize, usize) -> f64| Mat::from_fn(n, 1, |d, _| f(d / 3, d % 3));
        let tx = vec_of(&|_, c| if c == 0 { 1.0 } else { 0.0 });
        let ty = vec_of(&|_, c| if c == 1 { 1.0 } else { 0.0 });
        let q0 = vec_of(&|i, c| if c < 2 { nodes[i][c] } else { 0.0 });
        let qr = vec_of(&|i, c| match c {
            0 => -nodes[i][1],
            1 => nodes[i][0],
            _ => 1.0,
        });
        let mtx = &mt * &tx;
        let mty = &mt * &ty;
        let mtq0 = &mt * &q0;
        let mtqr = &mt * &qr;
        let dot = |a: &Mat<f64>, b: &Mat<f64>| (0..n).map(|d| a[(d, 0)] * b[(d, 0)]).sum::<f64>();
        let r = t.ncols();
        let col = |a: &Mat<f64>, k: usize| (0..n).map(|d| a[(d, 0)] * t[(d, k)]).sum::<f64>();
        Ok(FloatingFrameInvariants {
            mass: dot(&tx, &mtx),
            first_moment: [dot(&q0, &mtx), dot(&q0, &mty)],
            polar_inertia: dot(&q0, &mtq0),
            shape_first_moment: (0..r).map(|k| [col(&mtx, k), col(&mty, k)]).collect(),
            rotation_coupling: (0..r).map(|k| col(&mtqr, k)).collect(),
            modal_mass: project(mt.as_ref(), t),
            modal_skew: t.transpose() * &skew * t,
        })
    }

    /// Dense skew mass S = Σ ∫ρA Nᵀ J N dx (full DOF), J = [[0, 1], [−1, 0]], by 4-point
    /// Gauss–Legendre quadrature (exact: the integrand is a polynomial of degree 6).
    pub fn skew_mass_dense(&self) -> Mat<f64> {
        let n = self.n_dof();
        let mut s = Mat::<f64>::zeros(n, n);
        let a = (3.0 / 7.0 - 2.0 / 7.0 * (6.0f64 / 5.0).sqrt()).sqrt();
        let b = (3.0 / 7.0 + 2.0 / 7.0 * (6.0f64 / 5.0).sqrt()).sqrt();
        let wa = (18.0 + 30f64.sqrt()) / 36.0;
        let wb = (18.0 - 30f64.sqrt()) / 36.0;
        let gauss = [(-b, wb), (-a, wa), (a, wa), (b, wb)];
        for e in self.elements() {
            let mut se = Mat6::zeros();
            for (x, w) in gauss {
                let nl = e.local_shape(0.5 + 0.5 * x);
                let wl = 0.5 * w * e.length * e.rho_a;
                for i in 0..6 {
                    for j in 0..6 {
                        se[(i, j)] += wl * (nl[0][i] * nl[1][j] - nl[1][i] * nl[0][j]);
                    }
                }
            }
            let tr = e.rotation();
            let sg = tr.transpose() * se * tr;
            let d = e.dofs();
            for i in 0..6 {
                for j in 0..6 {
                    s[(d[i], d[j])] += sg[(i, j)];
                }
            }
        }
        s
    }
}

/// Tᵀ A T, symmetrized.
fn project(a: MatRef<'_, f64>, t: MatRef<'_, f64>) -> Mat<f64> {
    let p = t.transpose() * a * t;
    Mat::from_fn(p.nrows(), p.ncols(), |i, j| 0.5 * (p[(i, j)] + p[(j, i)]))
}
