//! Physical outputs of flexible bodies: the displacement, rotation and world position of chosen
//! nodes (`[output.nodes]`, opt-in), the meaning and unit of every elastic coordinate, and the
//! coordinates of a recorded row with the world position of a floating body's node on them
//! (`Model::coordinates_from_row`, `Model::floating_node_position`).
//!
//! Node columns, per recorded node k of body or beam `b` (after the coordinates of the floating
//! bodies, in the order beams, then floating bodies, nodes ascending):
//!
//! - `b.node<k>.ux`, `b.node<k>.uy` (m) and `b.node<k>.rz` (rad): the elastic displacement and
//!   rotation of the node: u = Φ_N q_f and φ_θ·q_f in the body frame for a floating body
//!   ([`crate::floating`]), the nodal DOF (0 where supported) in the world frame for a
//!   ground-fixed beam;
//! - `b.node<k>.x`, `b.node<k>.y` (m): its world position, R + A(θ)(ū₀ + Φ_N q_f) for a
//!   floating body (Shabana 2020, eq. 5.4), the undeformed node plus (ux, uy) for a beam.

use std::collections::BTreeMap;

use crate::error::MbdError;
use crate::initial_data::{AllNodes, NodeSelection};
use crate::system::Model;

pub(crate) use crate::initial_data::{NodeOutput, NodeOwner};

/// The column suffixes of one recorded node, in order.
const NODE_COLUMNS: [&str; 5] = ["ux", "uy", "rz", "x", "y"];

/// The meaning and unit of one elastic coordinate of a flexible body.
#[derive(Debug, Clone, PartialEq)]
pub struct CoordinateMeaning {
    /// Its result column (`rod.q3`, `beam.n2.v`).
    pub column: String,
    /// What it is, in words (`node 4 uy (Craig–Bampton boundary DOF)`, `mode 2`).
    pub meaning: String,
    /// Its unit: `m` or `rad` for nodal DOF, `-` for a modal coordinate (the amplitude of a
    /// mass-normalized mode shape, φᵀMφ = 1).
    pub unit: &'static str,
}

/// What the elastic coordinates of one flexible body (floating) or beam (ground-fixed) are.
#[derive(Debug, Clone, PartialEq)]
pub struct FlexibleCoordinates {
    /// Body or beam name.
    pub body: String,
    /// `floating` (floating frame of reference) or `ground_beam` (nodal DOF in the world).
    pub kind: &'static str,
    /// `modal`, `craig_bampton` or `none` (full nodal DOF).
    pub reduction: &'static str,
    /// One entry per elastic coordinate, in column order.
    pub coordinates: Vec<CoordinateMeaning>,
    /// Frequencies (Hz) of the kept modes: of the supported beam (its reference conditions)
    /// for modal truncation, the fixed-interface modes for Craig–Bampton; empty for a
    /// ground-fixed beam.
    pub mode_frequencies_hz: Vec<f64>,
}

/// The name of full beam DOF d (3 per node).
fn dof_meaning(d: usize) -> (String, &'static str) {
    let (name, unit) = [("ux", "m"), ("uy", "m"), ("rz", "rad")][d % 3];
    (format!("node {} {name}", d / 3), unit)
}

impl Model {
    /// Record the nodes `nodes` names (`[output.nodes]`: body or beam name → node indices or
    /// `"all"`).
    ///
    /// # Errors
    /// [`MbdError::Invalid`] at `output.nodes.<name>` for a name that is neither a floating
    /// flexible body nor a ground-fixed beam, or a node not in its mesh.
    pub fn set_output_nodes(
        &mut self,
        nodes: &BTreeMap<String, NodeSelection>,
    ) -> Result<(), MbdError> {
        let mut out = Vec::new();
        for (name, sel) in nodes {
            let (owner, count) = self.node_owner(name)?;
            let list: Vec<usize> = match sel {
                NodeSelection::All(AllNodes::All) => (0..count).collect(),
                NodeSelection::Nodes(v) => v.clone(),
            };
            if let Some(bad) = list.iter().find(|&&k| k >= count) {
                return Err(MbdError::Invalid {
                    path: format!("output.nodes.{name}"),
                    message: format!(
                        "node {bad} is not in the mesh of `{name}` (nodes 0 to {})",
                        count - 1
                    ),
                });
            }
            out.extend(list.into_iter().map(|node| NodeOutput { owner, node }));
        }
        out.sort_unstable();
        out.dedup();
        self.node_outputs = out;
        Ok(())
    }

    /// The owner of `name` and its number of nodes.
    fn node_owner(&self, name: &str) -> Result<(NodeOwner, usize), MbdError> {
        if let Some(k) = self.beams.iter().position(|b| b.name == name) {
            return Ok((NodeOwner::Beam(k), self.beams[k].nodes.len()));
        }
        if let Some(k) = self.floating.iter().position(|f| f.name == name) {
            return Ok((NodeOwner::Floating(k), self.floating[k].nodes.len()));
        }
        let known: Vec<&str> = (self.beams.iter().map(|b| b.name.as_str()))
            .chain(self.floating.iter().map(|f| f.name.as_str()))
            .collect();
        Err(MbdError::Invalid {
            path: format!("output.nodes.{name}"),
            message: format!(
                "`{name}` is not a flexible body or beam; nodes can be recorded for: {}",
                if known.is_empty() {
                    "none (the model has no flexible body or beam)".to_string()
                } else {
                    known.join(", ")
                }
            ),
        })
    }

    fn node_owner_name(&self, owner: NodeOwner) -> &str {
        match owner {
            NodeOwner::Beam(k) => &self.beams[k].name,
            NodeOwner::Floating(k) => &self.floating[k].name,
        }
    }

    /// The node output columns (see the module docs).
    pub(crate) fn node_output_columns(&self) -> Vec<String> {
        let mut c = Vec::with_capacity(5 * self.node_outputs.len());
        for o in &self.node_outputs {
            let b = self.node_owner_name(o.owner);
            c.extend(
                NODE_COLUMNS
                    .iter()
                    .map(|s| format!("{b}.node{}.{s}", o.node)),
            );
        }
        c
    }

    /// Append the node outputs at coordinates q (m, rad) to `out`.
    pub(crate) fn record_node_outputs(&self, q: &[f64], out: &mut Vec<f64>) {
        for o in &self.node_outputs {
            let n = o.node;
            match o.owner {
                NodeOwner::Floating(k) => {
                    let f = &self.floating[k];
                    let (u, rz) = f.node_local(n, &q[f.offset + 3..f.offset + 3 + f.r]);
                    let p = f.node_position(n, q);
                    let [x0, y0] = f.nodes[n];
                    out.extend_from_slice(&[u.x - x0, u.y - y0, rz, p.x, p.y]);
                }
                NodeOwner::Beam(k) => {
                    let b = &self.beams[k];
                    let dof = |c: usize| b.free_index[3 * n + c].map_or(0.0, |i| q[b.offset + i]);
                    let (ux, uy) = (dof(0), dof(1));
                    let [x0, y0] = b.nodes[n];
                    out.extend_from_slice(&[ux, uy, dof(2), x0 + ux, y0 + uy]);
                }
            }
        }
    }

    /// The meaning, unit and mode frequencies of the elastic coordinates of every ground-fixed
    /// beam and floating flexible body, in column order (what summary.json lists).
    pub fn flexible_coordinates(&self) -> Vec<FlexibleCoordinates> {
        let beams = self.beams.iter().map(|b| FlexibleCoordinates {
            body: b.name.clone(),
            kind: "ground_beam",
            reduction: "none",
            coordinates: b
                .free
                .iter()
                .zip(b.dof_names())
                .map(|(&d, column)| {
                    let (meaning, unit) = dof_meaning(d);
                    CoordinateMeaning {
                        column,
                        meaning,
                        unit,
                    }
                })
                .collect(),
            mode_frequencies_hz: Vec::new(),
        });
        let floating = self.floating.iter().map(|f| {
            let nb = f.boundary_dofs.len();
            let coordinates = (0..f.r)
                .map(|k| {
                    let column = format!("{}.q{k}", f.name);
                    if let Some(&d) = f.boundary_dofs.get(k) {
                        let (m, unit) = dof_meaning(d);
                        let meaning = format!("{m} (Craig–Bampton boundary DOF, body frame)");
                        return CoordinateMeaning {
                            column,
                            meaning,
                            unit,
                        };
                    }
                    let j = k - nb;
                    let kind = if nb > 0 {
                        "fixed-interface mode"
                    } else {
                        "mode"
                    };
                    let hz = f.mode_hz.get(j).copied().unwrap_or(f64::NAN);
                    CoordinateMeaning {
                        column,
                        meaning: format!(
                            "{kind} {j} ({hz:.6e} Hz), amplitude of the mass-normalized shape"
                        ),
                        unit: "-",
                    }
                })
                .collect();
            FlexibleCoordinates {
                body: f.name.clone(),
                kind: "floating",
                reduction: if nb > 0 { "craig_bampton" } else { "modal" },
                coordinates,
                mode_frequencies_hz: f.mode_hz.clone(),
            }
        });
        beams.chain(floating).collect()
    }
}

impl Model {
    /// World position (m) of node `node` of floating flexible body `body` at coordinates `q`
    /// (e.g. a row of [`crate::Results`] coordinates or the first n entries of a state):
    /// r = R + A(θ)(ū₀ + Φ q_f) (Shabana 2020, eq. 5.4).
    ///
    /// # Errors
    /// [`MbdError::UnknownBody`] for an unknown body name, [`MbdError::InvalidParameter`] for a
    /// node that is not in the beam model or a `q` shorter than [`crate::Model::n_coordinates`].
    pub fn floating_node_position(
        &self,
        body: &str,
        node: usize,
        q: &[f64],
    ) -> Result<[f64; 2], MbdError> {
        let Some(fb) = self.floating.iter().find(|f| f.name == body) else {
            return Err(MbdError::UnknownBody {
                item: "floating_node_position".into(),
                body: body.into(),
                known: self
                    .floating
                    .iter()
                    .map(|f| f.name.clone())
                    .collect::<Vec<_>>()
                    .join(", "),
            });
        };
        if node >= fb.nodes.len() || q.len() < self.n {
            return Err(MbdError::InvalidParameter {
                item: body.into(),
                what: "node index or coordinate vector length",
                value: node as f64,
                requirement: "a node of the beam model and q with n_coordinates() entries",
            });
        }
        let p = fb.node_position(node, q);
        Ok([p.x, p.y])
    }
}

impl Model {
    /// The coordinates q (length [`crate::Model::n_coordinates`]) of output row `row` of
    /// [`crate::Results`] from this model: rigid-body poses, floating-body coordinates, beam
    /// DOF; the node-frame coordinates of node ties are set from their tie (p = R + A ū,
    /// ψ = θ + φ_θ·q_f), which the constraints enforce. Use it with
    /// [`crate::Model::floating_node_position`] on recorded results.
    ///
    /// # Errors
    /// [`MbdError::InvalidParameter`] when `row` does not have one entry per output column.
    pub fn coordinates_from_row(&self, row: &[f64]) -> Result<Vec<f64>, MbdError> {
        let width = self.columns().len();
        if row.len() != width {
            return Err(MbdError::InvalidParameter {
                item: "coordinates_from_row".into(),
                what: "row length",
                value: row.len() as f64,
                requirement: "a row of Results from this model (one entry per output column)",
            });
        }
        let mut q = vec![0.0; self.n];
        let mut c = 1;
        for k in 0..self.bodies.len() {
            q[3 * k..3 * k + 3].copy_from_slice(&row[c..c + 3]);
            c += 9;
        }
        for b in &self.beams {
            let nf = b.n_free();
            q[b.offset..b.offset + nf].copy_from_slice(&row[c..c + nf]);
            c += nf;
        }
        for f in &self.floating {
            let nc = f.n_coords();
            q[f.offset..f.offset + nc].copy_from_slice(&row[c..c + nc]);
            c += nc;
        }
        let zeros = vec![0.0; self.n];
        for f in &self.floating {
            for &(node, col) in &f.ties {
                let (p, _) = f.node_frame(node, &q, &zeros);
                q[col..col + 3].copy_from_slice(&p);
            }
        }
        Ok(q)
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use crate::initial_data::{AllNodes, NodeSelection};
    use crate::{MbdError, ModelBuilder, ModelDesc, SimOptions};

    /// A 1 m steel arm of 4 elements clamped at node 0 (2 cantilever modes), pinned to the
    /// ground at its frame origin, which starts at (0.1, 0.2) with angle 0.5 rad.
    fn pendulum() -> crate::Model {
        let (mesh, red, _) = crate::floating::tests::arm(2e11);
        let mut b = ModelBuilder::new();
        b.gravity(0.0, -9.81)
            .floating_beam("arm", mesh, red, [0.1, 0.2, 0.5], [0.0; 3])
            .revolute("pin", ("ground", [0.1, 0.2]), ("arm", 0usize));
        b.build().unwrap()
    }

    /// Node 4 (the tip) at t0 is at R + A(θ) ū₀ = (0.1 + cos 0.5, 0.2 + sin 0.5) m with no
    /// elastic displacement (closed form of the undeformed start); along the swing the world
    /// columns equal R + A(θ)(ū₀ + (ux, uy)) from the recorded body-frame columns (the two
    /// frames agree) to 1e-12 m; the tip deflects (the check is not empty).
    #[test]
    fn floating_node_outputs_match_the_frame_pose() {
        let mut model = pendulum();
        let nodes = BTreeMap::from([("arm".to_string(), NodeSelection::Nodes(vec![4]))]);
        model.set_output_nodes(&nodes).unwrap();
        let res = model.simulate(&SimOptions::span(0.0, 0.2, 4)).unwrap();
        let col = |c: &str| res.column(c).unwrap();
        let (x, y) = (col("arm.node4.x"), col("arm.node4.y"));
        let (ux, uy, rz) = (
            col("arm.node4.ux"),
            col("arm.node4.uy"),
            col("arm.node4.rz"),
        );
        let (rx, ry, th) = (col("arm.x"), col("arm.y"), col("arm.theta"));
        assert_eq!([ux[0], uy[0], rz[0]], [0.0; 3]);
        assert!((x[0] - (0.1 + 0.5f64.cos())).abs() < 1e-15, "{}", x[0]);
        assert!((y[0] - (0.2 + 0.5f64.sin())).abs() < 1e-15, "{}", y[0]);
        for k in 0..res.len() {
            let (c, s) = (th[k].cos(), th[k].sin());
            let (lx, ly) = (1.0 + ux[k], uy[k]);
            assert!((x[k] - (rx[k] + c * lx - s * ly)).abs() < 1e-12);
            assert!((y[k] - (ry[k] + s * lx + c * ly)).abs() < 1e-12);
        }
        assert!(uy[4].abs() > 1e-9, "the falling arm bends: {}", uy[4]);
    }

    /// The rod of tests/data/flexible_slider_crank.toml: its first three coordinates are the
    /// tip's DOF (m, m, rad), then two fixed-interface modes whose frequencies are those of
    /// the clamped–clamped beam, f = λ²/(2π L²) √(EI/ρA) with λ = 4.73004, 7.85320 (R. D.
    /// Blevins, *Formulas for Natural Frequency and Mode Shape*, 1979, table 8-1): 8 cubic
    /// elements give them to 0.1 % (measured 0.01 % and 0.06 %).
    #[test]
    fn craig_bampton_coordinates_have_units_and_clamped_clamped_frequencies() {
        let text = include_str!("../../../tests/data/flexible_slider_crank.toml");
        let desc = ModelDesc::from_toml_table(toml::from_str(text).unwrap()).unwrap();
        let model = desc.compile().unwrap();
        let f = &model.flexible_coordinates()[0];
        assert_eq!((f.body.as_str(), f.reduction), ("rod", "craig_bampton"));
        let units: Vec<_> = f.coordinates.iter().map(|c| c.unit).collect();
        assert_eq!(units, ["m", "m", "rad", "-", "-"]);
        assert_eq!(f.coordinates[1].column, "rod.q1");
        assert!(f.coordinates[1].meaning.starts_with("node 8 uy"));
        let (e, rho, a, l) = (2.0e11, 7870.0, 0.008f64 * 0.008, 0.3f64);
        let i = 0.008f64.powi(4) / 12.0;
        for (lambda, hz) in [4.73004f64, 7.85320].iter().zip(&f.mode_frequencies_hz) {
            let exact =
                lambda.powi(2) / (2.0 * std::f64::consts::PI * l * l) * (e * i / (rho * a)).sqrt();
            assert!((hz / exact - 1.0).abs() < 1e-3, "{hz} Hz vs {exact} Hz");
        }
        let columns = model.columns();
        for c in ["rod.node8.ux", "rod.node8.rz", "rod.node4.y"] {
            assert!(columns.iter().any(|x| x == c), "{c}");
        }
    }

    /// Unknown names and nodes are refused at their field; `"all"` records every node.
    #[test]
    fn node_selection_is_checked() {
        let mut model = pendulum();
        let bad = BTreeMap::from([("arm".to_string(), NodeSelection::Nodes(vec![5]))]);
        assert!(matches!(
            model.set_output_nodes(&bad),
            Err(MbdError::Invalid { path, .. }) if path == "output.nodes.arm"
        ));
        let bad = BTreeMap::from([("pin".to_string(), NodeSelection::All(AllNodes::All))]);
        assert!(model.set_output_nodes(&bad).is_err());
        let all = BTreeMap::from([("arm".to_string(), NodeSelection::All(AllNodes::All))]);
        model.set_output_nodes(&all).unwrap();
        assert_eq!(model.node_output_columns().len(), 5 * 5);
    }
}
