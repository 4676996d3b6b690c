//! Compiling a description: names claimed in one namespace, the compiler's inputs, every
//! section's elements in order (joints, clearance joints of clearance 0 as ideal joints,
//! drivers, forces, clearances), then assembly.

use std::collections::HashMap;

use nalgebra::Vector2;

use super::ModelDesc;
use crate::element::{Clearance, Compiler, Inputs};
use crate::error::MbdError;
use crate::input::InputBank;
use crate::runtime::GROUND;
use crate::system::Model;

/// Validate `desc` and build the runtime model.
pub(crate) fn compile(desc: &ModelDesc) -> Result<Model, MbdError> {
    if desc.model.space == Some(super::parts::Space::Spatial) {
        return Err(MbdError::Invalid {
            path: "model.space".into(),
            message: "a spatial model is a clr_mbd::spatial::SpatialDesc (a model file with \
                      `space = \"spatial\"` is read as one), not a planar ModelDesc"
                .into(),
        });
    }
    claim_names(desc)?;
    let (bound, inputs) = bind_inputs(desc)?;
    let desc = &bound;
    let anchors = (desc.joints.iter().map(|e| (e.name(), e.anchors())))
        .chain(desc.drivers.iter().map(|e| (e.name(), e.anchors())))
        .chain(desc.forces.iter().map(|e| (e.name(), e.anchors())))
        .chain(
            desc.shapes
                .iter()
                .map(|s| (s.name.as_str(), s.at.iter().collect())),
        )
        .chain(desc.clearances.iter().map(|e| (e.name(), e.anchors())))
        .chain(desc.measures.iter().map(|e| (e.name(), e.anchors())))
        .collect();
    let mut c = Compiler::new(&Inputs {
        model: &desc.model,
        bodies: &desc.bodies,
        points: &desc.points,
        beams: &desc.beams,
        flexible_bodies: &desc.flexible_bodies,
        anchors,
    })?;
    for j in &desc.joints {
        j.compile(&mut c)?;
    }
    // a clearance joint of clearance 0 is its ideal joint: its rows follow the joints' (so a
    // file that writes it as the last `[[joint]]` has the same rows in the same order)
    for cl in &desc.clearances {
        match cl {
            Clearance::Revolute(r) if r.is_ideal() => r.compile_ideal(&mut c)?,
            Clearance::Translational(t) if t.is_ideal() => t.compile_ideal(&mut c)?,
            _ => {}
        }
    }
    for d in &desc.drivers {
        d.compile(&mut c)?;
    }
    for f in &desc.forces {
        f.compile(&mut c)?;
    }
    for s in &desc.shapes {
        s.compile(&mut c)?;
    }
    for cl in desc.clearances.iter().filter(|cl| !cl.is_ideal()) {
        cl.compile(&mut c)?;
    }
    for (k, m) in desc.measures.iter().enumerate() {
        crate::measure::named(m.name(), k)?;
        m.compile(&mut c)?;
    }
    let g = desc.model.gravity;
    if !(g[0].is_finite() && g[1].is_finite()) {
        return Err(MbdError::Invalid {
            path: "model.gravity".into(),
            message: format!(
                "gravitational acceleration [{}, {}] m/s²: both components must be finite",
                g[0], g[1]
            ),
        });
    }
    let mut model = c.finish(Vector2::new(g[0], g[1]))?;
    model.inputs = inputs;
    model.set_baumgarte(desc.solver.baumgarte_alpha, desc.solver.baumgarte_beta)?;
    model.set_contact_events(desc.solver.contact_events);
    model.input_warnings = super::checks::description_warnings(desc);
    model.set_output_nodes(&desc.output.nodes)?;
    let own = model.own_columns();
    crate::measure::runtime::resolve(&mut model.measures, &own)?;
    let mut columns = model.columns();
    super::twin::check_sources(desc, &columns)?;
    columns.extend(desc.deviations().iter().map(|d| d.column()));
    let twin = super::twin::twin_columns(desc, &columns);
    super::metric::check(&desc.metrics, &columns, &twin)?;
    Ok(model)
}

/// The description with every `{ type = "input" }` bound to the cell of its `[[input]]`, and
/// the cells (a fresh set per compile: no two compiled models share an input).
fn bind_inputs(desc: &ModelDesc) -> Result<(ModelDesc, InputBank), MbdError> {
    let mut bound = desc.clone();
    let mut bank = InputBank::default();
    let decl = &desc.inputs;
    for (k, d) in bound.drivers.iter_mut().enumerate() {
        crate::input::bind(&format!("driver[{k}]"), d.time_fns(), decl, &mut bank)?;
    }
    for (k, f) in bound.forces.iter_mut().enumerate() {
        crate::input::bind(&format!("force[{k}]"), f.time_fns(), decl, &mut bank)?;
    }
    crate::input::finish(decl, &mut bank)?;
    Ok((bound, bank))
}

/// A blank name cannot be referred to and would leave errors about its item without a place
/// (`cargo xtask fuzz` found both a `[[point]]` and a joint named " "): refused at its field.
fn refuse_blank_names(desc: &ModelDesc) -> Result<(), MbdError> {
    let sections: [(&str, Vec<&str>); 9] = [
        (
            "body",
            desc.bodies.iter().map(|b| b.name.as_str()).collect(),
        ),
        (
            "flexible_body",
            desc.flexible_bodies
                .iter()
                .map(|f| f.name.as_str())
                .collect(),
        ),
        ("beam", desc.beams.iter().map(|b| b.name.as_str()).collect()),
        (
            "point",
            desc.points.iter().map(|p| p.name.as_str()).collect(),
        ),
        ("joint", desc.joints.iter().map(|e| e.name()).collect()),
        ("driver", desc.drivers.iter().map(|e| e.name()).collect()),
        ("force", desc.forces.iter().map(|e| e.name()).collect()),
        (
            "shape",
            desc.shapes.iter().map(|s| s.name.as_str()).collect(),
        ),
        (
            "clearance",
            desc.clearances.iter().map(|e| e.name()).collect(),
        ),
    ];
    for (section, names) in sections {
        if let Some(k) = names.iter().position(|n| n.trim().is_empty()) {
            return Err(MbdError::Invalid {
                path: format!("{section}[{k}].name"),
                message: format!(
                    "the name `{}` is blank: give a name other elements and messages can refer to",
                    names[k]
                ),
            });
        }
    }
    Ok(())
}

/// One namespace for every named thing; `ground` is reserved.
fn claim_names(desc: &ModelDesc) -> Result<(), MbdError> {
    refuse_blank_names(desc)?;
    let mut names: HashMap<&str, &'static str> = HashMap::new();
    names.insert(GROUND, "ground");
    let all = desc
        .bodies
        .iter()
        .map(|b| (b.name.as_str(), "body"))
        .chain(
            desc.flexible_bodies
                .iter()
                .map(|f| (f.name.as_str(), "floating flexible body")),
        )
        .chain(
            desc.beams
                .iter()
                .map(|b| (b.name.as_str(), "flexible beam")),
        )
        .chain(desc.points.iter().map(|p| (p.name.as_str(), "point")))
        .chain(desc.joints.iter().map(|e| (e.name(), e.kind())))
        .chain(desc.drivers.iter().map(|e| (e.name(), e.kind())))
        .chain(desc.forces.iter().map(|e| (e.name(), e.kind())))
        .chain(desc.shapes.iter().map(|s| (s.name.as_str(), "shape")))
        .chain(desc.clearances.iter().map(|e| (e.name(), e.kind())));
    for (name, kind) in all {
        if let Some(first) = names.get(name) {
            return Err(MbdError::DuplicateName {
                name: name.to_string(),
                first,
                second: kind,
            });
        }
        names.insert(name, kind);
    }
    Ok(())
}
