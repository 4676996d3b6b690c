//! Initial conditions of floating flexible bodies ([`crate::floating`]): their part of the
//! assembly metric, of the fixed/solved bookkeeping and of the report.
//!
//! A floating body's coordinates are of three kinds, weighted differently in the assembly of
//! consistent initial conditions ([`Model::assemble_initial_state`]; the drift projection during
//! a run keeps its own metric):
//!
//! - the frame (R_x, R_y, θ) and its velocity: like a rigid body's centre-of-mass coordinates,
//!   W = 1/m for R and 1/J₀ for θ (J₀ = ∫ρ|ū₀|² about the frame origin), times the solved
//!   weight when the description left them out ([`crate::desc::Body`] does the same);
//! - the elastic coordinates q_f and rates q̇_f: W = 0, so the assembly never moves them: they
//!   keep the given state (undeformed and at rest: strain energy ½q_fᵀK q_f = 0 exactly at t0),
//!   and the constraint correction goes to the frames and the other bodies;
//! - the node-frame coordinates of node ties (p, ψ): massless and tied to the frame, they
//!   weigh as the frame's own coordinates (translations as R, the angle as θ, solved with it),
//!   so a solved frame carries its tie nodes along; they are not part of the report.
//!
//! When the joints cannot be closed by the frames and the other bodies alone (a rod pinned at
//! both ends a distance apart other than its length), the position correction has no
//! solution with q_f held; [`Model::flexible_assembly_error`] then checks that closing them
//! elastically would work and names the body ([`MbdError::FlexibleBodyDeformed`]).

use crate::error::MbdError;
use crate::init::{BodyInitialState, CoordinateInitialState, CORRECTION_TOL, SOLVED_WEIGHT};
use crate::system::Model;

/// The kind of a floating body's coordinate in the assembly metric.
enum Role {
    /// Frame coordinate (0: R_x, 1: R_y, 2: θ) of a body.
    Frame(usize, usize),
    /// Elastic coordinate (never moved).
    Elastic,
    /// Node-frame coordinate (0: p_x, 1: p_y, 2: ψ) of a node tie of a body.
    Tie(usize, usize),
}

impl Model {
    /// The role of coordinate c when a floating body owns it (`None` for rigid bodies and
    /// ground-fixed beams).
    fn flexible_role(&self, c: usize) -> Option<Role> {
        for (k, f) in self.floating.iter().enumerate() {
            let o = f.offset;
            if (o..o + 3).contains(&c) {
                return Some(Role::Frame(k, c - o));
            }
            if (o + 3..o + 3 + f.r).contains(&c) {
                return Some(Role::Elastic);
            }
            if let Some(&(_, col)) = f.ties.iter().find(|(_, col)| (*col..*col + 3).contains(&c)) {
                return Some(Role::Tie(k, c - col));
            }
        }
        None
    }

    /// W^{1/2} of coordinate c of a floating body in the assembly of initial conditions (see
    /// the module docs), for positions or velocities (`velocity`), with solved coordinates
    /// weighted [`SOLVED_WEIGHT`] times more when `fixed_first`; `None` when no floating body
    /// owns c.
    pub(crate) fn flexible_weight_sqrt(
        &self,
        c: usize,
        velocity: bool,
        fixed_first: bool,
    ) -> Option<f64> {
        let inertia = |k: usize, slot: usize| {
            let f = &self.floating[k];
            let m = if slot < 2 { f.mass } else { f.j0 };
            1.0 / m.max(f64::MIN_POSITIVE).sqrt()
        };
        Some(match self.flexible_role(c)? {
            Role::Frame(k, slot) | Role::Tie(k, slot) => {
                let fixed = self.floating[k].fixed[slot + if velocity { 3 } else { 0 }];
                if fixed_first && !fixed {
                    SOLVED_WEIGHT.sqrt() * inertia(k, slot)
                } else {
                    inertia(k, slot)
                }
            }
            Role::Elastic => 0.0,
        })
    }

    /// True when every floating body's frame pose and velocity are given.
    pub(crate) fn flexible_all_fixed(&self) -> bool {
        self.floating.iter().all(|f| f.fixed.iter().all(|&x| x))
    }

    /// The given and assembled frame coordinates of every floating body (x, y, θ of the frame
    /// origin and their rates, in the order of [`crate::COORDINATE_NAMES`]).
    pub(crate) fn flexible_corrections(&self, given: &[f64], y: &[f64]) -> Vec<BodyInitialState> {
        let n = self.n;
        self.floating
            .iter()
            .map(|f| BodyInitialState {
                body: f.name.clone(),
                coordinates: std::array::from_fn(|slot| {
                    let i = if slot < 3 {
                        f.offset + slot
                    } else {
                        n + f.offset + slot - 3
                    };
                    CoordinateInitialState {
                        fixed: f.fixed[slot],
                        given: given[i],
                        assembled: y[i],
                    }
                }),
            })
            .collect()
    }

    /// The error of an assembly that failed with the elastic coordinates held (`err`): when
    /// the kinetic projection, which may deform the bodies, closes the joints from `given` at
    /// t0 and has to move elastic coordinates of a floating body to do so, the joints cannot
    /// be closed without deforming that body ([`MbdError::FlexibleBodyDeformed`], naming the
    /// body that would store the most strain energy); otherwise `err`.
    pub(crate) fn flexible_assembly_error(
        &mut self,
        t0: f64,
        given: &[f64],
        err: MbdError,
    ) -> MbdError {
        if self.floating.is_empty() {
            return err;
        }
        let mut y = given.to_vec();
        if self.project(t0, &mut y, 1e-12).is_err() {
            return err;
        }
        let n = self.n;
        let g = self.gravity;
        let deformed = self
            .floating
            .iter()
            .filter(|f| {
                (f.offset + 3..f.offset + 3 + f.r)
                    .flat_map(|c| [c, n + c])
                    .any(|i| (y[i] - given[i]).abs() > CORRECTION_TOL * given[i].abs().max(1.0))
            })
            .map(|f| (f.name.clone(), f.energies(&y[..n], &y[n..2 * n], g)[2]))
            .max_by(|a, b| a.1.total_cmp(&b.1));
        match deformed {
            Some((body, strain_energy)) => MbdError::FlexibleBodyDeformed {
                body,
                strain_energy,
            },
            None => err,
        }
    }
}

impl crate::init::InitialConditions {
    /// The description field of a coordinate of the report (`crank.position`, `rod.pose`):
    /// what to change when `initial_conditions = "exact"` refuses a correction.
    pub fn field_of(&self, body: &str, coordinate: &str) -> String {
        let flexible = self.flexible.iter().any(|b| b.body == body);
        let field = match (coordinate, flexible) {
            ("x" | "y" | "theta", true) => "pose",
            (_, true) => "velocity",
            ("x" | "y", false) => "position",
            ("theta", false) => "angle",
            ("vx" | "vy", false) => "velocity",
            _ => "angular_velocity",
        };
        format!("{body}.{field}")
    }
}

#[cfg(test)]
mod tests {
    use crate::{
        InitialConditionsMode, MbdError, Model, ModelBuilder, ModelDesc, Reduction, SimOptions,
    };

    /// The Simeon-style flexible slider–crank of tests/data (crank at dead centre, rod along x
    /// from the crank pin at (0.15, 0) to the slider at (0.45, 0)), with `edit` applied.
    fn slider_crank(edit: impl FnOnce(&mut ModelDesc)) -> Model {
        let text = include_str!("../../../tests/data/flexible_slider_crank.toml");
        let mut desc = ModelDesc::from_toml_table(toml::from_str(text).unwrap()).unwrap();
        edit(&mut desc);
        desc.compile().unwrap()
    }

    /// Index of the first coordinate of floating body `name`'s frame in q.
    fn frame(model: &Model, name: &str) -> usize {
        model
            .floating
            .iter()
            .find(|f| f.name == name)
            .unwrap()
            .offset
    }

    /// Strain energy at the assembled state (J) and the state.
    fn assembled(model: &mut Model) -> (f64, Vec<f64>, crate::InitialConditions) {
        let (y, ic) = model.assemble_initial_state(0.0).unwrap();
        let n = model.n_coordinates();
        (model.energies(&y[..n], &y[n..2 * n]).elastic, y, ic)
    }

    /// The only undeformed closure of the loop at crank angle 0 puts the rod frame at the crank
    /// pin (0.15, 0) with angle 0 and, from the crank speed ω = 150 rad/s, frame velocity
    /// (0, ω l1) = (0, 22.5) m/s and angular velocity −ω l1/l2 = −75 rad/s (closed form of the
    /// slider–crank at dead centre); tolerance 1e-9 (Newton stops at ‖Φ‖∞ ≤ 1e-12).
    fn assert_closed_form(model: &Model, y: &[f64]) {
        let (o, n) = (frame(model, "rod"), model.n_coordinates());
        let expect = [0.15, 0.0, 0.0, 0.0, 22.5, -75.0];
        let got = [
            y[o],
            y[o + 1],
            y[o + 2],
            y[n + o],
            y[n + o + 1],
            y[n + o + 2],
        ];
        for (g, e) in got.iter().zip(expect) {
            assert!((g - e).abs() < 1e-9, "rod frame {got:?} vs {expect:?}");
        }
    }

    /// The given (consistent) file: nothing solved or corrected, and the strain energy is 0.
    #[test]
    fn consistent_file_starts_undeformed_without_notes() {
        let mut model = slider_crank(|_| {});
        let (u, y, ic) = assembled(&mut model);
        assert_eq!(u, 0.0);
        assert!(ic.notes().is_empty(), "{:?}", ic.notes());
        assert_closed_form(&model, &y);
    }

    /// Pose and velocity left out (Simeon's rod as the user wrote it): the frame is solved from
    /// the joints, the elastic coordinates stay exactly 0 (strain energy exactly 0, where the
    /// old assembly put −0.072 m into the axial coordinate), and the solved frame is reported.
    #[test]
    fn pose_left_out_is_solved_on_the_frame_not_the_elastic_coordinates() {
        let mut model = slider_crank(|d| {
            d.flexible_bodies[0].pose = None;
            d.flexible_bodies[0].velocity = None;
        });
        let (u, y, ic) = assembled(&mut model);
        assert_eq!(u, 0.0, "strain energy at t0");
        let (o, r) = (frame(&model, "rod"), model.floating[0].r);
        let n = model.n_coordinates();
        assert!(y[o + 3..o + 3 + r].iter().all(|&v| v == 0.0));
        assert!(y[n + o + 3..n + o + 3 + r].iter().all(|&v| v == 0.0));
        assert_closed_form(&model, &y);
        let solved: Vec<_> = ic
            .solved()
            .iter()
            .map(|(b, c, _)| format!("{b}.{c}"))
            .collect();
        assert!(solved.contains(&"rod.x".to_string()), "{solved:?}");
        let notes = ic.notes().join(" ");
        assert!(notes.contains("rod.x = 1.5"), "{notes}");
        assert!(notes.contains("rod.omega = -7.5"), "{notes}");
        // a coordinate left out is solved, not corrected: `exact` runs it
        assert!(ic.corrected().is_empty());
    }

    /// A pose angle off by 0.01 rad: corrected on the frame (back to the closed form 0),
    /// reported, the body undeformed; `exact` refuses it and names `rod.pose`.
    #[test]
    fn inconsistent_pose_is_corrected_on_the_frame_and_refused_by_exact() {
        let off = |d: &mut ModelDesc| d.flexible_bodies[0].pose = Some([0.15, 0.0, 0.01]);
        let mut model = slider_crank(off);
        let (u, y, ic) = assembled(&mut model);
        assert_eq!(u, 0.0, "strain energy at t0 (was 4.6 J)");
        assert_closed_form(&model, &y);
        let corrected = ic.corrected();
        assert!(
            corrected
                .iter()
                .any(|(b, c, g, _)| *b == "rod" && *c == "theta" && *g == 0.01),
            "{corrected:?}"
        );
        assert!(ic.notes().join(" ").contains("rod.theta 1.000000e-2"));
        let mut model = slider_crank(off);
        let mut opts = SimOptions::span(0.0, 1e-3, 1);
        opts.initial_conditions = InitialConditionsMode::Exact;
        match model.simulate(&opts) {
            Err(MbdError::InconsistentInitialConditions { field, .. }) => {
                assert_eq!(field, "rod.pose")
            }
            other => panic!("exact must refuse the pose: {:?}", other.map(|r| r.notes)),
        }
    }

    /// A wrong frame velocity (at rest) is corrected to the closed form, the elastic rates stay
    /// 0, and `exact` refuses it at `rod.velocity`.
    #[test]
    fn wrong_frame_velocity_is_corrected_and_refused_by_exact() {
        let rest = |d: &mut ModelDesc| d.flexible_bodies[0].velocity = Some([0.0; 3]);
        let mut model = slider_crank(rest);
        let (_, y, ic) = assembled(&mut model);
        assert_closed_form(&model, &y);
        let (o, r, n) = (
            frame(&model, "rod"),
            model.floating[0].r,
            model.n_coordinates(),
        );
        assert!(y[n + o + 3..n + o + 3 + r].iter().all(|&v| v == 0.0));
        assert!(ic
            .corrected()
            .iter()
            .any(|(b, c, _, _)| *b == "rod" && *c == "omega"));
        let mut model = slider_crank(rest);
        let mut opts = SimOptions::span(0.0, 1e-3, 1);
        opts.initial_conditions = InitialConditionsMode::Exact;
        assert!(matches!(
            model.simulate(&opts),
            Err(MbdError::InconsistentInitialConditions { field, .. }) if field == "rod.velocity"
        ));
    }

    /// The 1 m steel arm of the floating-body tests (clamped at node 0; Craig–Bampton with
    /// the tip node 4 as interface and one mode), pinned to the ground at node 0 (the origin)
    /// and at its tip to the ground point (`distance`, 0).
    fn pinned_twice(distance: f64) -> Model {
        let (mesh, _, _) = crate::floating::tests::arm(2e11);
        let red = Reduction::CraigBampton {
            interface_nodes: vec![4],
            modes: 1,
        };
        let mut b = ModelBuilder::new();
        b.floating_beam("arm", mesh, red, [0.0; 3], [0.0; 3])
            .revolute("p", ("ground", [0.0, 0.0]), ("arm", 0usize))
            .revolute("q", ("ground", [distance, 0.0]), ("arm", 4usize));
        b.build().unwrap()
    }

    /// The arm pinned at both ends 1.01 m apart: only stretching it closes the joints, which
    /// the assembly refuses, naming the arm; 1 m apart they are consistent and it starts
    /// undeformed and at rest.
    #[test]
    fn joints_that_need_deformation_are_refused_naming_the_body() {
        let mut model = pinned_twice(1.01);
        match model.assemble_initial_state(0.0) {
            Err(MbdError::FlexibleBodyDeformed {
                body,
                strain_energy,
            }) => {
                assert_eq!(body, "arm");
                // a bar stretched by δ: ½ (EA/L) δ² = ½ (2e11 · 1e-4 / 1)(0.01)² = 1e3 J (the
                // axial constraint mode is exact for linear elements); 1 % for the geometry
                assert!((strain_energy / 1e3 - 1.0).abs() < 0.01, "{strain_energy}");
            }
            other => panic!("expected FlexibleBodyDeformed, got {:?}", other.map(|_| ())),
        }
        // the joints hold the frame twice (Φ_q has full rank only through the tip's axial DOF)
        let mut model = pinned_twice(1.0);
        let (u, y, _) = assembled(&mut model);
        assert_eq!(u, 0.0);
        let n = model.n_coordinates();
        assert!(
            y[..3].iter().all(|v| v.abs() < 1e-12),
            "frame {:?}",
            &y[..3]
        );
        assert!(y[n..2 * n].iter().all(|v| v.abs() < 1e-12), "at rest");
    }
}
