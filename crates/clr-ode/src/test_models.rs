//! Stiff test problems of the *Test Set for IVP Solvers* (F. Mazzia, C. Magherini et al.,
//! University of Bari; problem descriptions `hires`, `rober`, `vdpol`, `orego`) with analytic
//! Jacobians, end times and reference solutions y(t_end) as tabulated there (and in
//! shared/spec/verification.md).

use crate::system::{MassKind, OdeSystem};

/// Mixed-error significant correct digits of the Test Set:
/// scd = −log10(max_i |y_i − ref_i| / (1 + |ref_i|)).
pub fn scd(y: &[f64], reference: &[f64]) -> f64 {
    let e = y
        .iter()
        .zip(reference)
        .map(|(a, r)| (a - r).abs() / (1.0 + r.abs()))
        .fold(0.0f64, f64::max);
    -e.log10()
}

/// The test problems, for loops over all of them (benchmarks, verification).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Problem {
    /// HIRES, 8 equations.
    Hires,
    /// Robertson as an ODE, 3 equations.
    Robertson,
    /// Robertson as an index-1 DAE with y1 + y2 + y3 = 1 (singular mass matrix).
    RobertsonDae,
    /// Stiff Van der Pol, ε = 1e-6.
    VanDerPol,
    /// OREGO (Oregonator), 3 equations.
    Orego,
}

impl Problem {
    /// The four ODE problems of the verification table.
    pub const ODES: [Problem; 4] = [
        Problem::Hires,
        Problem::Robertson,
        Problem::VanDerPol,
        Problem::Orego,
    ];

    /// Short name (`hires`, `robertson`, `robertson_dae`, `vdpol`, `orego`).
    pub fn name(self) -> &'static str {
        match self {
            Problem::Hires => "hires",
            Problem::Robertson => "robertson",
            Problem::RobertsonDae => "robertson_dae",
            Problem::VanDerPol => "vdpol",
            Problem::Orego => "orego",
        }
    }

    /// Initial state y(0) (t0 = 0 for all).
    pub fn y0(self) -> Vec<f64> {
        match self {
            Problem::Hires => Hires::Y0.to_vec(),
            Problem::Robertson | Problem::RobertsonDae => Robertson::Y0.to_vec(),
            Problem::VanDerPol => VanDerPol::Y0.to_vec(),
            Problem::Orego => Orego::Y0.to_vec(),
        }
    }

    /// End time.
    pub fn t_end(self) -> f64 {
        match self {
            Problem::Hires => Hires::T_END,
            Problem::Robertson | Problem::RobertsonDae => Robertson::T_END,
            Problem::VanDerPol => VanDerPol::T_END,
            Problem::Orego => Orego::T_END,
        }
    }

    /// Reference y(t_end) of the Test Set.
    pub fn reference(self) -> &'static [f64] {
        match self {
            Problem::Hires => &Hires::REFERENCE,
            Problem::Robertson | Problem::RobertsonDae => &Robertson::REFERENCE,
            Problem::VanDerPol => &VanDerPol::REFERENCE,
            Problem::Orego => &Orego::REFERENCE,
        }
    }

    /// The system (boxed, for loops over problems; solvers also accept `&mut dyn OdeSystem`).
    pub fn system(self) -> Box<dyn OdeSystem> {
        match self {
            Problem::Hires => Box::new(Hires),
            Problem::Robertson => Box::new(Robertson::ode()),
            Problem::RobertsonDae => Box::new(Robertson::dae()),
            Problem::VanDerPol => Box::new(VanDerPol::stiff()),
            Problem::Orego => Box::new(Orego),
        }
    }
}

/// HIRES: high irradiance response of photomorphogenesis (Schäfer 1975; Test Set `hires`).
#[derive(Debug, Clone, Copy, Default)]
pub struct Hires;

impl Hires {
    /// Initial state.
    pub const Y0: [f64; 8] = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0057];
    /// End time.
    pub const T_END: f64 = 321.8122;
    /// Reference y(t_end).
    pub const REFERENCE: [f64; 8] = [
        0.7371312573325668e-3,
        0.1442485726316185e-3,
        0.5888729740967575e-4,
        0.1175651343283149e-2,
        0.2386356198831331e-2,
        0.6238968252742796e-2,
        0.2849998395185769e-2,
        0.2850001604814231e-2,
    ];
}

impl OdeSystem for Hires {
    fn dim(&self) -> usize {
        8
    }
    #[inline]
    fn rhs(&mut self, _t: f64, y: &[f64], f: &mut [f64]) {
        f[0] = -1.71 * y[0] + 0.43 * y[1] + 8.32 * y[2] + 0.0007;
        f[1] = 1.71 * y[0] - 8.75 * y[1];
        f[2] = -10.03 * y[2] + 0.43 * y[3] + 0.035 * y[4];
        f[3] = 8.32 * y[1] + 1.71 * y[2] - 1.12 * y[3];
        f[4] = -1.745 * y[4] + 0.43 * y[5] + 0.43 * y[6];
        f[5] = -280.0 * y[5] * y[7] + 0.69 * y[3] + 1.71 * y[4] - 0.43 * y[5] + 0.69 * y[6];
        f[6] = 280.0 * y[5] * y[7] - 1.81 * y[6];
        f[7] = -f[6];
    }
    fn has_jacobian(&self) -> bool {
        true
    }
    fn jacobian(&mut self, _t: f64, y: &[f64], j: &mut [f64]) {
        let mut s = |r: usize, c: usize, v: f64| j[r + 8 * c] = v;
        s(0, 0, -1.71);
        s(0, 1, 0.43);
        s(0, 2, 8.32);
        s(1, 0, 1.71);
        s(1, 1, -8.75);
        s(2, 2, -10.03);
        s(2, 3, 0.43);
        s(2, 4, 0.035);
        s(3, 1, 8.32);
        s(3, 2, 1.71);
        s(3, 3, -1.12);
        s(4, 4, -1.745);
        s(4, 5, 0.43);
        s(4, 6, 0.43);
        s(5, 3, 0.69);
        s(5, 4, 1.71);
        s(5, 5, -280.0 * y[7] - 0.43);
        s(5, 6, 0.69);
        s(5, 7, -280.0 * y[5]);
        s(6, 5, 280.0 * y[7]);
        s(6, 6, -1.81);
        s(6, 7, 280.0 * y[5]);
        s(7, 5, -280.0 * y[7]);
        s(7, 6, 1.81);
        s(7, 7, -280.0 * y[5]);
    }
}

/// Robertson's chemical kinetics (Test Set `rober`), as an ODE or as an index-1 DAE where the
/// third equation is replaced by the conservation law y1 + y2 + y3 = 1 (mass matrix
/// diag(1, 1, 0)).
#[derive(Debug, Clone, Copy)]
pub struct Robertson {
    dae: bool,
}

impl Robertson {
    /// Initial state.
    pub const Y0: [f64; 3] = [1.0, 0.0, 0.0];
    /// End time.
    pub const T_END: f64 = 1e11;
    /// Reference y(t_end) (digits as published).
    #[allow(clippy::excessive_precision)]
    pub const REFERENCE: [f64; 3] = [
        0.2083340149701255e-7,
        0.8333360770334713e-13,
        0.9999999791665050,
    ];
    /// The ODE form.
    pub fn ode() -> Self {
        Robertson { dae: false }
    }
    /// The index-1 DAE form.
    pub fn dae() -> Self {
        Robertson { dae: true }
    }
}

impl OdeSystem for Robertson {
    fn dim(&self) -> usize {
        3
    }
    #[inline]
    fn rhs(&mut self, _t: f64, y: &[f64], f: &mut [f64]) {
        let r1 = 0.04 * y[0];
        let r2 = 1e4 * y[1] * y[2];
        let r3 = 3e7 * y[1] * y[1];
        f[0] = -r1 + r2;
        f[1] = r1 - r2 - r3;
        f[2] = if self.dae {
            y[0] + y[1] + y[2] - 1.0
        } else {
            r3
        };
    }
    fn has_jacobian(&self) -> bool {
        true
    }
    fn jacobian(&mut self, _t: f64, y: &[f64], j: &mut [f64]) {
        j[0] = -0.04;
        j[1] = 0.04;
        j[3] = 1e4 * y[2];
        j[4] = -1e4 * y[2] - 6e7 * y[1];
        j[6] = 1e4 * y[1];
        j[7] = -1e4 * y[1];
        if self.dae {
            j[2] = 1.0;
            j[5] = 1.0;
            j[8] = 1.0;
        } else {
            j[5] = 6e7 * y[1];
        }
    }
    fn mass_kind(&self) -> MassKind {
        if self.dae {
            MassKind::Constant
        } else {
            MassKind::Identity
        }
    }
    fn mass(&mut self, _t: f64, _y: &[f64], m: &mut [f64]) {
        m[0] = 1.0;
        m[4] = 1.0;
        if !self.dae {
            m[8] = 1.0;
        }
    }
}

/// Van der Pol oscillator in the stiff scaling of the Test Set `vdpol`:
/// y1' = y2, y2' = ((1 − y1²) y2 − y1)/ε.
#[derive(Debug, Clone, Copy)]
pub struct VanDerPol {
    /// Stiffness parameter ε.
    pub eps: f64,
}

impl VanDerPol {
    /// Initial state.
    pub const Y0: [f64; 2] = [2.0, 0.0];
    /// End time.
    pub const T_END: f64 = 2.0;
    /// Reference y(t_end) for ε = 1e-6.
    pub const REFERENCE: [f64; 2] = [0.1706167732170469e1, -0.8928097010248125];
    /// ε = 1e-6 (the Test Set value).
    pub fn stiff() -> Self {
        VanDerPol { eps: 1e-6 }
    }
}

impl OdeSystem for VanDerPol {
    fn dim(&self) -> usize {
        2
    }
    #[inline]
    fn rhs(&mut self, _t: f64, y: &[f64], f: &mut [f64]) {
        f[0] = y[1];
        f[1] = ((1.0 - y[0] * y[0]) * y[1] - y[0]) / self.eps;
    }
    fn has_jacobian(&self) -> bool {
        true
    }
    fn jacobian(&mut self, _t: f64, y: &[f64], j: &mut [f64]) {
        j[2] = 1.0;
        j[1] = (-2.0 * y[0] * y[1] - 1.0) / self.eps;
        j[3] = (1.0 - y[0] * y[0]) / self.eps;
    }
}

/// The Oregonator (Field & Noyes; Test Set `orego`).
#[derive(Debug, Clone, Copy, Default)]
pub struct Orego;

impl Orego {
    /// Initial state.
    pub const Y0: [f64; 3] = [1.0, 2.0, 3.0];
    /// End time.
    pub const T_END: f64 = 360.0;
    /// Reference y(t_end).
    pub const REFERENCE: [f64; 3] = [
        0.1000814870318523e1,
        0.1228178521549917e4,
        0.1320554942846706e3,
    ];
}

const S: f64 = 77.27;
const Q: f64 = 8.375e-6;
const W: f64 = 0.161;

impl OdeSystem for Orego {
    fn dim(&self) -> usize {
        3
    }
    #[inline]
    fn rhs(&mut self, _t: f64, y: &[f64], f: &mut [f64]) {
        f[0] = S * (y[1] + y[0] * (1.0 - Q * y[0] - y[1]));
        f[1] = (y[2] - (1.0 + y[0]) * y[1]) / S;
        f[2] = W * (y[0] - y[2]);
    }
    fn has_jacobian(&self) -> bool {
        true
    }
    fn jacobian(&mut self, _t: f64, y: &[f64], j: &mut [f64]) {
        j[0] = S * (1.0 - 2.0 * Q * y[0] - y[1]);
        j[1] = -y[1] / S;
        j[2] = W;
        j[3] = S * (1.0 - y[0]);
        j[4] = -(1.0 + y[0]) / S;
        j[6] = 0.0;
        j[7] = 1.0 / S;
        j[8] = -W;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Analytic Jacobians against central differences of f (an independent formulation).
    #[test]
    fn jacobians_match_finite_differences() {
        for p in [
            Problem::Hires,
            Problem::Robertson,
            Problem::RobertsonDae,
            Problem::VanDerPol,
            Problem::Orego,
        ] {
            let mut sys = p.system();
            let n = sys.dim();
            // a state near the initial one with every component non-zero
            let y: Vec<f64> = p
                .y0()
                .iter()
                .enumerate()
                .map(|(i, v)| v * (1.0 + 0.01 * i as f64) + 1e-3 * (i + 1) as f64)
                .collect();
            let mut ja = vec![0.0; n * n];
            sys.jacobian(0.0, &y, &mut ja);
            let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
            for j in 0..n {
                let h = 1e-6 * (1.0 + y[j].abs());
                let mut yp = y.clone();
                yp[j] += h;
                sys.rhs(0.0, &yp, &mut fp);
                yp[j] -= 2.0 * h;
                sys.rhs(0.0, &yp, &mut fm);
                for i in 0..n {
                    let fd = (fp[i] - fm[i]) / (2.0 * h);
                    let a = ja[i + j * n];
                    assert!(
                        (fd - a).abs() <= 1e-6 * (1.0 + a.abs()),
                        "{} J[{i},{j}] analytic {a} vs fd {fd}",
                        p.name()
                    );
                }
            }
        }
    }

    #[test]
    fn scd_is_the_mixed_error_digits() {
        // |y − ref| / (1 + |ref|) = 1e-6 exactly for ref = 1, y = 1 + 2e-6
        assert!((scd(&[1.0 + 2e-6], &[1.0]) - 6.0).abs() < 1e-9);
    }
}
