//! The independent formulation of the clearance slider–crank of issue 5 (minimal coordinates,
//! contact force written by hand), the reference of `cargo xtask verify
//! mbd.clearance_slider_crank.early` and of `cargo xtask bench mbd`.

use clr_contact::{Material, NormalLaw};
use clr_ode::{Direction, Dopri5, OdeSystem, Options, Output, StopReason};

/// Crank length of the benchmark slider–crank of issue 5 (Flores-style studies), m.
pub const CRANK: f64 = 0.05;
/// Connecting-rod length, m.
pub const ROD: f64 = 0.30;
/// Crank mass, kg.
pub const M_CRANK: f64 = 0.343;
/// Rod mass, kg.
pub const M_ROD: f64 = 1.072;
/// Slider mass, kg.
pub const M_SLIDER: f64 = 0.347;
/// Crank inertia about its centre of mass, kg·m².
pub const I_CRANK: f64 = 0.000216;
/// Rod inertia about its centre of mass, kg·m².
pub const I_ROD: f64 = 0.034;
/// Slider inertia about its centre of mass, kg·m².
pub const I_SLIDER: f64 = 0.000115;
/// Bearing radius of the benchmark clearance joint, m.
pub const R_BEARING: f64 = 10.0e-3;
/// Journal radius of the benchmark clearance joint, m.
pub const R_JOURNAL: f64 = 9.5e-3;
/// Gravity, m/s².
pub const G: f64 = 9.81;

/// The independent formulation of `mbd.clearance_slider_crank.early`: minimal coordinates
/// y = (φ, x, φ̇, ẋ) with φ the rod angle and x the slider position; the crank pin A(t) is
/// prescribed, the rod is a body pinned at a moving point (Lagrange's equation
/// J_A φ̈ = −m₂(l/2) u⊥·Ä + m₂(l/2) u⊥·g + l u⊥·F_j, J_A = I₂ + m₂l²/4), the slider
/// m₃ẍ = F_N n_x, and the contact force written here by hand: Hertz internal cylinder
/// K = (4/3)E*√(R_iR_j/(R_i − R_j)) (Flores et al. 2004) with the Lankarani–Nikravesh factor
/// χ = 3(1 − c_e²)/4, F_N = max(0, Kδ^{3/2}(1 + χδ̇/δ̇⁻)). Onsets (δ rising through 0) and
/// separations (falling) are terminal events; δ̇⁻ is δ̇ at the located onset.
struct MinimalSliderCrank {
    omega: f64,
    k: f64,
    chi: f64,
    clearance: f64,
    v_floor: f64,
    active: bool,
    v_minus: f64,
}

impl MinimalSliderCrank {
    /// (δ, δ̇, n) at (t, y).
    fn contact(&self, t: f64, y: &[f64]) -> (f64, f64, [f64; 2]) {
        let th = self.omega * t;
        let (st, ct) = th.sin_cos();
        let (sp, cp) = y[0].sin_cos();
        let a = [CRANK * ct, CRANK * st];
        let ad = [-CRANK * self.omega * st, CRANK * self.omega * ct];
        let bx = a[0] + ROD * cp - y[1];
        let by = a[1] + ROD * sp;
        let bdx = ad[0] - ROD * y[2] * sp - y[3];
        let bdy = ad[1] + ROD * y[2] * cp;
        let e = (bx * bx + by * by).sqrt();
        let n = if e > 0.0 {
            [bx / e, by / e]
        } else {
            [1.0, 0.0]
        };
        (e - self.clearance, n[0] * bdx + n[1] * bdy, n)
    }
}

impl OdeSystem for MinimalSliderCrank {
    fn dim(&self) -> usize {
        4
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        let (delta, rate, n) = self.contact(t, y);
        let mut f_n = 0.0;
        if delta > 0.0 {
            let vm = if self.active {
                self.v_minus
            } else {
                rate.max(self.v_floor)
            };
            f_n = (self.k * delta.powf(1.5) * (1.0 + self.chi * rate / vm)).max(0.0);
        }
        let th = self.omega * t;
        let acc = [
            -CRANK * self.omega.powi(2) * th.cos(),
            -CRANK * self.omega.powi(2) * th.sin(),
        ];
        let (sp, cp) = y[0].sin_cos();
        let up = [-sp, cp];
        let fj = [-f_n * n[0], -f_n * n[1]];
        let j_a = I_ROD + M_ROD * ROD * ROD / 4.0;
        let moment = -M_ROD * ROD / 2.0 * (up[0] * acc[0] + up[1] * acc[1])
            + M_ROD * ROD / 2.0 * (-G * up[1])
            + ROD * (up[0] * fj[0] + up[1] * fj[1]);
        dy[0] = y[2];
        dy[1] = y[3];
        dy[2] = moment / j_a;
        dy[3] = f_n * n[0] / M_SLIDER;
    }
    fn n_events(&self) -> usize {
        2
    }
    fn events(&mut self, t: f64, y: &[f64], g: &mut [f64]) {
        let (delta, _, _) = self.contact(t, y);
        g[0] = delta;
        g[1] = delta;
    }
    fn event_direction(&self, i: usize) -> Direction {
        if i == 0 {
            Direction::Rising
        } else {
            Direction::Falling
        }
    }
    fn event_terminal(&self, _i: usize) -> bool {
        true
    }
}

/// Slider positions of the minimal formulation at `times` (DOPRI5, rtol 1e-12).
pub fn minimal_slider_positions(
    omega: f64,
    c_e: f64,
    times: &[f64],
) -> Result<(Vec<f64>, usize), String> {
    let e_star = Material::steel().composite_modulus(&Material::steel());
    let k = 4.0 / 3.0 * e_star * (R_BEARING * R_JOURNAL / (R_BEARING - R_JOURNAL)).sqrt();
    let mut sys = MinimalSliderCrank {
        omega,
        k,
        chi: 0.75 * (1.0 - c_e * c_e),
        clearance: R_BEARING - R_JOURNAL,
        v_floor: NormalLaw::DEFAULT_MIN_IMPACT_VELOCITY,
        active: false,
        v_minus: 0.0,
    };
    let t_end = *times.last().ok_or("no output times")?;
    let mut solver = Dopri5::new(
        Options::default()
            .rtol(1e-12)
            .atol(1e-15)
            .output(Output::Times(times.to_vec())),
    );
    let y0 = [0.0, CRANK + ROD, -omega * CRANK / ROD, 0.0];
    solver
        .start(&mut sys, 0.0, &y0, t_end)
        .map_err(|e| e.to_string())?;
    let mut onsets = 0;
    while let StopReason::TerminalEvent(i) = solver.advance(&mut sys).map_err(|e| e.to_string())? {
        let t = solver.solution().t_final;
        let y = solver.solution().y_final.clone();
        if i == 0 {
            let (_, rate, _) = sys.contact(t, &y);
            sys.active = true;
            sys.v_minus = rate.max(sys.v_floor);
            onsets += 1;
        } else {
            sys.active = false;
        }
        solver.restart(&mut sys, t, &y).map_err(|e| e.to_string())?;
    }
    let sol = solver.solution();
    Ok(((0..sol.len()).map(|k| sol.state(k)[1]).collect(), onsets))
}
