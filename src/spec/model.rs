//! A generic model file read into its `clr_mbd::ModelDesc`, checked by compiling it once, with
//! its run settings and the file's text for placing errors.

use std::sync::{Arc, Mutex};

use clr_mbd::{Model, ModelDesc, SimOptions};

use super::locate::FieldPath;
use super::parse::parse_path;
use super::SpecError;

/// Item sections of a model file, in the order their names are searched.
const ITEM_SECTIONS: [&str; 9] = [
    "body",
    "beam",
    "flexible_body",
    "point",
    "joint",
    "driver",
    "force",
    "shape",
    "clearance",
];

/// A checked generic model: its description, run settings and what was changed on reading.
/// Plain data (`Send`); a sweep clones it and changes the description per point.
#[derive(Debug, Clone)]
pub struct ModelSpec {
    /// File the model came from (for messages).
    pub file: String,
    /// The file's text (for locating errors).
    src: String,
    /// Model name (`[model] name`, else the file stem).
    pub name: String,
    /// Description.
    pub description: String,
    /// Integrator settings (t0, t_end, output times, tolerances, solver, projection, events).
    pub options: SimOptions,
    /// Each clearance joint by name with its radial clearance c = R_bearing − R_journal (m;
    /// `None` for translational clearances and sliders).
    pub clearances: Vec<(String, Option<f64>)>,
    /// The description as run, every default filled in (for `summary.json`).
    pub resolved: serde_json::Value,
    /// What reading the file changed (upgrades of an older format, `--rtol` also setting
    /// `atol`), one sentence each; the command line prints them.
    pub notes: Vec<String>,
    /// The model description.
    desc: Box<ModelDesc>,
    /// The model compiled by the check, taken by the first [`ModelSpec::build`] (clones share
    /// it; later builds compile again).
    compiled: Compiled,
    /// Inputs given as functions of the state, applied by every build
    /// ([`ModelSpec::set_input_function`]).
    input_fns: InputFns,
}

/// Inputs given as functions (not `Debug`: closures).
#[derive(Clone, Default)]
struct InputFns(Vec<(String, clr_mbd::input::InputFn)>);

impl std::fmt::Debug for InputFns {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "InputFns({})", self.0.len())
    }
}

/// The compiled model kept from the check (not `Debug`, not `Clone`: shared by clones).
#[derive(Clone, Default)]
struct Compiled(Arc<Mutex<Option<Model>>>);

impl std::fmt::Debug for Compiled {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Compiled")
    }
}

/// A built model with its run settings.
pub struct Built {
    /// The clr-mbd model (Baumgarte coefficients and contact events as in `[solver]`).
    pub model: Model,
    /// Simulation options.
    pub options: SimOptions,
}

impl ModelSpec {
    /// A model from its description; `src` is the file's text (for placing errors), `notes`
    /// what reading it changed. The description is compiled once here to check it (the
    /// compiled model is kept for the first [`ModelSpec::build`]).
    ///
    /// # Errors
    /// [`SpecError`] at the field or item clr-mbd names, with its line when found.
    pub fn from_desc(
        file: &str,
        src: &str,
        desc: ModelDesc,
        notes: Vec<String>,
    ) -> Result<Self, SpecError> {
        let name = desc.model.name.clone().unwrap_or_else(|| {
            std::path::Path::new(file)
                .file_stem()
                .map_or("model".into(), |s| s.to_string_lossy().into_owned())
        });
        let mut spec = Self {
            file: file.to_string(),
            src: src.to_string(),
            name,
            description: desc.model.description.clone().unwrap_or_default(),
            options: SimOptions::default(),
            clearances: clearances(&desc),
            resolved: serde_json::Value::Null,
            notes,
            desc: Box::new(ModelDesc::default()),
            compiled: Compiled::default(),
            input_fns: InputFns::default(),
        };
        spec.options = desc
            .sim_options()
            .map_err(|e| SpecError::at(file, src, &spec.desc_path(&e.path), e.message.clone()))?;
        let model = desc.compile().map_err(|e| spec.model_error(&e))?;
        spec.compiled = Compiled(Arc::new(Mutex::new(Some(model))));
        spec.resolved = resolved(file, &desc)?;
        spec.desc = Box::new(desc);
        Ok(spec)
    }

    /// The model description.
    pub fn desc(&self) -> &ModelDesc {
        &self.desc
    }

    /// This model with the assignments applied to a clone of its description (`body.rod.mass`,
    /// `clearance.B.bearing_radius`; array items by name or index), checked and compiled once:
    /// a sweep point, without reading the file again.
    ///
    /// # Errors
    /// [`SpecError`] for a path that does not exist or a value the description refuses.
    pub fn with_overrides(&self, overrides: &[super::Assignment]) -> Result<Self, SpecError> {
        let mut root = toml::Table::try_from(&*self.desc).map_err(|e| {
            SpecError::plain(&self.file, "", format!("the model cannot be changed: {e}"))
        })?;
        for a in overrides {
            super::overrides::set_toml(&mut root, a)?;
        }
        let mut notes = self.notes.clone();
        notes.extend(super::parse::upgrade(&mut root));
        // refused values are reported as for `--set` on the command line (no file line)
        let desc = super::parse::desc("--set", "", root)?;
        // this model compiled without them, so what the compiler refuses comes from them
        let mut spec = Self::from_desc(&self.file, &self.src, desc, notes).map_err(|e| {
            let sets: Vec<String> = overrides
                .iter()
                .map(|a| format!("{}={}", a.path, a.value_text()))
                .collect();
            SpecError {
                file: format!("--set '{}'", sets.join("' --set '")),
                line: None,
                column: None,
                ..e
            }
        })?;
        spec.name.clone_from(&self.name);
        Ok(spec)
    }

    /// A field path of a clr-mbd message as a path in the file ([`item_path`]).
    fn desc_path(&self, path: &str) -> FieldPath {
        item_path(&self.src, path)
    }

    /// Set the end time (s).
    ///
    /// # Errors
    /// [`SpecError`] when `t_end` is not after the start time.
    pub fn set_t_end(&mut self, t_end: f64) -> Result<(), SpecError> {
        self.desc.output.t_end = Some(t_end);
        self.options = self
            .desc
            .sim_options()
            .map_err(|e| SpecError::plain("--t-end", "", format!("{t_end} s: {}", e.message)))?;
        self.resolved["output"]["t_end"] = serde_json::json!(t_end);
        Ok(())
    }

    /// Refuse plausibility warnings (`[solver] strict = true`).
    pub fn set_strict(&mut self) {
        self.desc.solver.strict = true;
        self.options.strict = true;
    }

    /// Write the integrator knobs that are set into the description's `[solver]` (they were
    /// asked for on the command line: no note) and check them with the method.
    ///
    /// # Errors
    /// [`SpecError`] for a knob the method does not use (`--max-order` with `dopri5`).
    pub fn set_knobs(&mut self, knobs: &clr_models::SolverKnobs) -> Result<(), SpecError> {
        knobs.apply(&mut self.desc.solver);
        self.options = self.desc.sim_options().map_err(|e| {
            let option = e.path.strip_prefix("solver.").unwrap_or(&e.path);
            SpecError::plain(
                &format!("--{}", option.replace('_', "-")),
                "",
                e.message.clone(),
            )
        })?;
        self.resolved["solver"] = serde_json::to_value(&self.desc.solver).unwrap_or_default();
        if self.desc.solver.atol.is_none() {
            let atol = clr_mbd::desc::ATOL_PER_RTOL * self.desc.solver.rtol;
            self.resolved["solver"]["atol"] = serde_json::json!(atol);
        }
        Ok(())
    }

    /// Set the relative tolerance; the absolute one follows the rule atol = 1e-3·rtol
    /// (`clr_mbd::desc::ATOL_PER_RTOL`) unless `--atol` gives it ([`ModelSpec::set_knobs`]). A
    /// different `atol` the file gave is replaced, with a note.
    ///
    /// # Errors
    /// [`SpecError`] when `rtol` is not positive.
    pub fn set_rtol(&mut self, rtol: f64) -> Result<(), SpecError> {
        let atol = clr_mbd::desc::ATOL_PER_RTOL * rtol;
        if let Some(file_atol) = self.desc.solver.atol.filter(|a| *a != atol) {
            self.notes.push(format!(
                "--rtol {rtol:e} also sets atol = 1e-3·rtol = {atol:e} (the file's [solver] atol \
                 = {file_atol:e} is not used); give `--atol` to choose it"
            ));
        }
        self.desc.solver.rtol = rtol;
        self.desc.solver.atol = None;
        self.options = self
            .desc
            .sim_options()
            .map_err(|e| SpecError::plain("--rtol", "", format!("{rtol}: {}", e.message)))?;
        self.resolved["solver"]["rtol"] = serde_json::json!(rtol);
        self.resolved["solver"]["atol"] = serde_json::json!(atol);
        Ok(())
    }

    /// The clr-mbd model and its run settings.
    ///
    /// # Errors
    /// [`SpecError`] from clr-mbd's checks, placed at the field or item it names.
    pub fn build(&self) -> Result<Built, SpecError> {
        let kept = self.compiled.0.lock().ok().and_then(|mut m| m.take());
        let model = match kept {
            Some(m) => m,
            None => self.desc.compile().map_err(|e| self.model_error(&e))?,
        };
        let mut model = model;
        for (name, f) in &self.input_fns.0 {
            model
                .set_input_function(name, f.clone())
                .map_err(|e| SpecError::plain(&self.file, "input", e.to_string()))?;
        }
        Ok(Built {
            model,
            options: self.options.clone(),
        })
    }

    /// Make the load input `name` a function of time and the feedback measures at every build
    /// ([`clr_mbd::Model::set_input_function`]; checked when built).
    pub fn set_input_function(&mut self, name: &str, f: clr_mbd::input::InputFn) {
        self.input_fns.0.retain(|(n, _)| n != name);
        self.input_fns.0.push((name.to_string(), f));
    }

    /// A clr-mbd error as a [`SpecError`], placed at the field or item it names.
    pub fn model_error(&self, e: &clr_mbd::MbdError) -> SpecError {
        use clr_mbd::MbdError as E;
        let path = match e {
            // item.field paths (`pin.b.body`, `rod.mass`)
            E::UnknownBody { item, .. } | E::UnknownPoint { item, .. } => self.desc_path(item),
            E::Invalid { path, .. } => self.desc_path(path),
            E::InvalidInertia { body, what, .. } => {
                let field = if what.starts_with("mass") {
                    "mass"
                } else {
                    "inertia"
                };
                self.desc_path(&format!("{body}.{field}"))
            }
            E::SameBody { item, .. }
            | E::InvalidParameter { item, .. }
            | E::Contact { item, .. }
            | E::Beam { item, .. } => self.desc_path(item),
            E::DuplicateName { name, .. } => self.desc_path(name),
            E::InconsistentInitialConditions { field, .. }
            | E::UndeterminedCoordinates { field, .. } => self.desc_path(field),
            E::InitialPenetration { element, .. } => self.desc_path(element),
            E::FlexibleBodyDeformed { body, .. } => self.desc_path(&format!("{body}.pose")),
            // labels are `item (equation)`: place the error at the first item named
            E::RedundantConstraints {
                involved: label, ..
            }
            | E::Assembly { worst: label, .. } => {
                self.desc_path(label.split(" (").next().unwrap_or("").trim())
            }
            _ => FieldPath::root(),
        };
        let message = match e {
            E::Invalid { message, .. } => message.clone(),
            // the place is in the error's field already: drop clr-mbd's `item: ` prefix
            E::UnknownBody { item, .. } | E::UnknownPoint { item, .. } => {
                let text = e.to_string();
                text.strip_prefix(&format!("{item}: "))
                    .map_or(text.clone(), str::to_string)
            }
            other => other.to_string(),
        };
        SpecError::at(&self.file, &self.src, &path, message)
    }
}

/// A field path of a clr-mbd message (`joint[2].axis`, or `crank_drive.motion.rate` with an
/// item name first) as a path in the file of text `src`.
pub(crate) fn item_path(src: &str, path: &str) -> FieldPath {
    let (first, rest) = path.split_once('.').unwrap_or((path, ""));
    let section = ITEM_SECTIONS.contains(&first)
        || ["model", "solver", "output"].contains(&first)
        || first.contains('[');
    if !section {
        // an item name first: its place in its section
        if let Some(item) = path_of(src, first) {
            return join(&item, rest);
        }
    }
    parse_path(path)
}

/// `joint[2]` for the item named `name` in the file of text `src` (the last one when a name
/// repeats: that is the duplicate).
fn path_of(src: &str, name: &str) -> Option<FieldPath> {
    let root: toml::Table = toml::from_str(src).ok()?;
    let mut found = None;
    for sec in ITEM_SECTIONS {
        if let Some(toml::Value::Array(a)) = root.get(sec) {
            for (k, item) in a.iter().enumerate() {
                if item.get("name").and_then(|n| n.as_str()) == Some(name) {
                    found = Some(FieldPath::root().key(sec).index(k));
                }
            }
        }
    }
    found
}

/// `base` extended by a relative dotted path (`normal.restitution`).
fn join(base: &FieldPath, rel: &str) -> FieldPath {
    let mut p = base.clone();
    p.0.extend(parse_path(rel).0);
    p
}

/// Each clearance joint by name with its radial clearance (m; `None` without one).
fn clearances(desc: &ModelDesc) -> Vec<(String, Option<f64>)> {
    desc.clearances
        .iter()
        .map(|c| {
            let radial = match c {
                clr_mbd::element::Clearance::Revolute(r) => {
                    Some(r.bearing_radius - r.journal_radius)
                }
                _ => None,
            };
            (c.name().to_string(), radial)
        })
        .collect()
}

/// The description as JSON without empty optional fields (for `summary.json`), with a
/// `derived` table of the values the run computed from it rather than read (see [`derived`]).
fn resolved(file: &str, desc: &ModelDesc) -> Result<serde_json::Value, SpecError> {
    let mut v = serde_json::to_value(desc)
        .map_err(|e| SpecError::plain(file, "", format!("the model cannot be recorded: {e}")))?;
    strip_nulls(&mut v);
    v["derived"] = derived(desc);
    Ok(v)
}

/// Values the run uses that the file does not give, each with how it was derived: the
/// absolute tolerance by the rule atol = 1e-3·rtol, and per contact element the elastic law's
/// stiffness K and exponent n (computed from materials and radii for the journal-bearing
/// laws), its hysteresis factor χ and effective restitution.
fn derived(desc: &ModelDesc) -> serde_json::Value {
    use clr_mbd::element::Clearance;
    let mut d = serde_json::Map::new();
    if desc.solver.atol.is_none() {
        d.insert(
            "solver.atol".into(),
            serde_json::json!({
                "value": clr_mbd::desc::ATOL_PER_RTOL * desc.solver.rtol,
                "unit": "units of q and q̇",
                "from": "1e-3·rtol (not given)",
            }),
        );
    }
    // a clearance of 0 runs as the ideal joint: its normal law acts on nothing
    for c in desc.clearances.iter().filter(|c| !c.is_ideal()) {
        let (normal, radii) = match c {
            Clearance::Revolute(r) => (&r.normal, Some((r.bearing_radius, r.journal_radius))),
            Clearance::Translational(t) => (&t.normal, None),
            Clearance::SliderOnBeam(s) => (&s.normal, None),
            Clearance::Contact(s) => (&s.normal, None),
        };
        let name = c.name();
        let Ok(law) = normal.build(&format!("{name}.normal"), radii) else {
            continue;
        };
        let mut entry = serde_json::json!({
            "elastic_law": law.elastic().name(),
            "hysteresis_factor": law.chi(),
            "effective_restitution": law.effective_restitution(),
            "from": "the normal law's parameters, materials and the joint's radii",
        });
        if let Some((k, n)) = law.elastic().power_parameters() {
            entry["stiffness"] = serde_json::json!(k);
            entry["exponent"] = serde_json::json!(n);
            entry["stiffness_unit"] = serde_json::json!(format!("N/m^{n}"));
        }
        d.insert(format!("{name}.normal"), entry);
    }
    serde_json::Value::Object(d)
}

pub(crate) fn strip_nulls(v: &mut serde_json::Value) {
    match v {
        serde_json::Value::Object(o) => {
            o.retain(|_, x| !x.is_null());
            o.values_mut().for_each(strip_nulls);
        }
        serde_json::Value::Array(a) => a.iter_mut().for_each(strip_nulls),
        _ => {}
    }
}
