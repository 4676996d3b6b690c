//! The storage of the spatial reduced Newton systems ([`super::newton`] fills and solves it;
//! the model only owns it, so this data sits below both).

use clr_ode::linalg::DenseLu;
use nalgebra::Vector3;

/// Workspace of the reduced Newton systems, sized at the first use (nothing allocates after).
#[derive(Debug, Default)]
pub(crate) struct SpatialNewton {
    /// Whether the integrator uses these systems (NDF, analytic, no LuGre bristles).
    pub(crate) on: bool,
    /// Q at the Jacobian's state (before the solve) and the accelerations a.
    pub(crate) q: Vec<f64>,
    pub(crate) acc: Vec<f64>,
    /// ∂Q/∂x, ∂Q/∂v (nv × nv, row-major).
    pub(crate) qx: Vec<f64>,
    pub(crate) qv: Vec<f64>,
    /// ∂(Gᵀλ)/∂x and the effective stiffness Q_x − ∂(Gᵀλ)/∂x of the Newton matrix (nv × nv).
    pub(crate) gtl_x: Vec<f64>,
    pub(crate) qx_eff: Vec<f64>,
    /// G, ∂(Gv)/∂x, ∂(Ga)/∂x, ∂Φ_t/∂x, ∂γ/∂x, ∂γ/∂v, b_x, b_v (m × nv, row-major).
    pub(crate) g: Vec<f64>,
    pub(crate) gv_x: Vec<f64>,
    pub(crate) ga_x: Vec<f64>,
    pub(crate) phit_x: Vec<f64>,
    pub(crate) gamma_x: Vec<f64>,
    pub(crate) gamma_v: Vec<f64>,
    pub(crate) bx: Vec<f64>,
    pub(crate) bv: Vec<f64>,
    /// Q_x D and b_x D of the last factorization.
    pub(crate) qxd: Vec<f64>,
    pub(crate) bxd: Vec<f64>,
    /// Quaternion and body angular velocity of each body at the Jacobian's state.
    pub(crate) quat: Vec<[f64; 4]>,
    pub(crate) omega: Vec<Vector3<f64>>,
    pub(crate) rhs: Vec<f64>,
    pub(crate) rho: Vec<f64>,
    pub(crate) lu: DenseLu,
    pub(crate) c: f64,
}
