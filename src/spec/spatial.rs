//! A spatial model file (`[model] space = "spatial"`) read into its
//! `clr_mbd::spatial::SpatialDesc`, checked by compiling it once, with its run settings and
//! the file's text for placing errors (the spatial counterpart of [`super::ModelSpec`]).

use clr_mbd::spatial::{SpatialDesc, SpatialModel};
use clr_mbd::SimOptions;

use super::locate::FieldPath;
use super::model::item_path;
use super::SpecError;

/// A checked spatial model: description, run settings and what reading it changed.
#[derive(Debug, Clone)]
pub struct SpatialSpec {
    /// File the model came from.
    pub file: String,
    src: String,
    /// Model name (`[model] name`, else the file stem).
    pub name: String,
    /// Description line.
    pub description: String,
    /// Integrator settings.
    pub options: SimOptions,
    /// Each clearance joint by name with its radial clearance (m; `None` for a shape contact),
    /// and each contact group of a journal joint (`J.radial_a`, …) with `None`: what the generic
    /// metrics cover.
    pub clearances: Vec<(String, Option<f64>)>,
    /// The description as run (for `summary.json`).
    pub resolved: serde_json::Value,
    /// What reading the file changed, one sentence each.
    pub notes: Vec<String>,
    desc: Box<SpatialDesc>,
}

impl SpatialSpec {
    /// Read and check the description of the parsed file `root`.
    ///
    /// # Errors
    /// [`SpecError`] at the field, with its line when found.
    pub fn from_table(
        file: &str,
        src: &str,
        root: toml::Table,
        notes: Vec<String>,
    ) -> Result<Self, SpecError> {
        let desc = SpatialDesc::from_toml_table(root)
            .map_err(|e| super::parse::schema_error(file, src, &e))?;
        Self::from_desc(file, src, desc, notes)
    }

    fn from_desc(
        file: &str,
        src: &str,
        desc: SpatialDesc,
        notes: Vec<String>,
    ) -> Result<Self, SpecError> {
        if desc.bodies.is_empty() {
            return Err(SpecError::at(
                file,
                src,
                &FieldPath::root().key("body"),
                "the file defines nothing that moves: give at least one [[body]]",
            ));
        }
        let name = desc.model.name.clone().unwrap_or_else(|| {
            std::path::Path::new(file)
                .file_stem()
                .map_or("model".into(), |s| s.to_string_lossy().into_owned())
        });
        let mut spec = Self {
            file: file.into(),
            src: src.into(),
            name,
            description: desc.model.description.clone().unwrap_or_default(),
            options: SimOptions::default(),
            clearances: clearance_metrics_of(&desc),
            resolved: serde_json::Value::Null,
            notes,
            desc: Box::new(SpatialDesc::default()),
        };
        spec.options = desc
            .sim_options()
            .map_err(|e| SpecError::at(file, src, &super::parse::parse_path(&e.path), e.message))?;
        desc.compile().map_err(|e| spec.model_error(&e))?;
        let mut resolved = serde_json::to_value(&desc).map_err(|e| {
            SpecError::plain(file, "", format!("the model cannot be recorded: {e}"))
        })?;
        super::model::strip_nulls(&mut resolved);
        spec.resolved = resolved;
        spec.desc = Box::new(desc);
        Ok(spec)
    }

    /// The description.
    pub fn desc(&self) -> &SpatialDesc {
        &self.desc
    }

    /// The compiled model and its options.
    ///
    /// # Errors
    /// [`SpecError`] from clr-mbd's checks.
    pub fn build(&self) -> Result<(SpatialModel, SimOptions), SpecError> {
        let m = self.desc.compile().map_err(|e| self.model_error(&e))?;
        Ok((m, self.options.clone()))
    }

    /// A clr-mbd error placed at the item or field it names.
    pub fn model_error(&self, e: &clr_mbd::MbdError) -> SpecError {
        use clr_mbd::MbdError as E;
        let path = match e {
            E::UnknownBody { item, .. } => item.clone(),
            E::Invalid { path, .. } => path.clone(),
            E::InvalidInertia { body, .. } => format!("{body}.mass"),
            E::SameBody { item, .. }
            | E::InvalidParameter { item, .. }
            | E::Contact { item, .. } => item.clone(),
            E::DuplicateName { name, .. } => name.clone(),
            E::RedundantConstraints { involved: l, .. } | E::Assembly { worst: l, .. } => {
                l.split(" (").next().unwrap_or("").trim().to_string()
            }
            _ => String::new(),
        };
        let message = match e {
            E::Invalid { message, .. } => message.clone(),
            // the place is in the error's field already: drop clr-mbd's `item: ` prefix
            E::Contact { item, .. } | E::UnknownBody { item, .. } => {
                let text = e.to_string();
                text.strip_prefix(&format!("{item}: "))
                    .map_or(text.clone(), str::to_string)
            }
            other => other.to_string(),
        };
        SpecError::at(&self.file, &self.src, &item_path(&self.src, &path), message)
    }

    /// This model with assignments applied to a clone of its description (a sweep point).
    ///
    /// # Errors
    /// [`SpecError`] for a path that does not exist or a refused value.
    pub fn with_overrides(&self, overrides: &[super::Assignment]) -> Result<Self, SpecError> {
        let mut root = toml::Table::try_from(&*self.desc).map_err(|e| {
            SpecError::plain(&self.file, "", format!("the model cannot be changed: {e}"))
        })?;
        for a in overrides {
            super::overrides::set_toml(&mut root, a)?;
        }
        let sets: Vec<String> = overrides
            .iter()
            .map(|a| format!("{}={}", a.path, a.value_text()))
            .collect();
        let place = format!("--set '{}'", sets.join("' --set '"));
        let mut spec =
            Self::from_table(&self.file, &self.src, root, self.notes.clone()).map_err(|e| {
                SpecError {
                    file: place,
                    line: None,
                    column: None,
                    ..e
                }
            })?;
        spec.name.clone_from(&self.name);
        Ok(spec)
    }

    /// Set the end time (s).
    ///
    /// # Errors
    /// [`SpecError`] when `t_end` is not after the start time.
    pub fn set_t_end(&mut self, t_end: f64) -> Result<(), SpecError> {
        self.desc.output.t_end = Some(t_end);
        self.refresh("--t-end")?;
        self.resolved["output"]["t_end"] = serde_json::json!(t_end);
        Ok(())
    }

    /// Set the relative tolerance (atol = 1e-3·rtol unless given with `--atol`).
    ///
    /// # Errors
    /// [`SpecError`] when `rtol` is not positive.
    pub fn set_rtol(&mut self, rtol: f64) -> Result<(), SpecError> {
        self.desc.solver.rtol = rtol;
        self.desc.solver.atol = None;
        self.refresh("--rtol")?;
        self.resolved["solver"] = serde_json::to_value(&self.desc.solver).unwrap_or_default();
        Ok(())
    }

    /// Write the integrator knobs into `[solver]`.
    ///
    /// # Errors
    /// [`SpecError`] for a knob the method does not use.
    pub fn set_knobs(&mut self, knobs: &clr_models::SolverKnobs) -> Result<(), SpecError> {
        knobs.apply(&mut self.desc.solver);
        self.refresh("--solver options")?;
        self.resolved["solver"] = serde_json::to_value(&self.desc.solver).unwrap_or_default();
        Ok(())
    }

    /// Refuse plausibility warnings.
    pub fn set_strict(&mut self) {
        self.desc.solver.strict = true;
        self.options.strict = true;
    }

    fn refresh(&mut self, what: &str) -> Result<(), SpecError> {
        self.options = self
            .desc
            .sim_options()
            .map_err(|e| SpecError::plain(what, "", e.message))?;
        Ok(())
    }
}

/// The clearance joints the generic metrics cover: each joint with its radial clearance, and
/// for a journal joint each contact group (`J.radial_a`, `J.radial_b`, and for the revolute kind
/// `J.thrust_minus`, `J.thrust_plus`), whose columns and impacts carry the group's name.
fn clearance_metrics_of(desc: &SpatialDesc) -> Vec<(String, Option<f64>)> {
    use clr_mbd::spatial::{ClearanceKind, SpatialClearance};
    let mut v = Vec::new();
    for c in &desc.clearances {
        v.push((c.name().to_string(), c.clearance()));
        if let SpatialClearance::Journal(j) = c {
            let groups: &[&str] = match j.kind {
                ClearanceKind::Revolute => &["radial_a", "radial_b", "thrust_minus", "thrust_plus"],
                _ => &["radial_a", "radial_b"],
            };
            v.extend(groups.iter().map(|g| (format!("{}.{g}", j.name), None)));
        }
    }
    v
}
