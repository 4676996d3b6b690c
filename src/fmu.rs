//! Co-simulation FMUs (FMI 3.0, or 2.0 on request) of planar model files: what `clr fmu` and `clr.fmu.export`
//! write, and the configuration the FMU's runtime (the `clr-fmu` crate) reads back.
//!
//! An FMU is a zip archive holding `modelDescription.xml`, the runtime library
//! `binaries/x86_64-linux/clr_fmu.so` (the clr library with the FMI 3.0 C functions) and, under
//! `resources/`, the model file and `clr_fmu.json` ([`FmuConfig`]). The model's `[[input]]`s are
//! the FMU's inputs, its output columns (by default the `[[measure]]` columns) its outputs, and
//! the model-file fields named with `--parameter` its parameters (fixed: set before the end of
//! initialization, applied as `--set` overrides).

use std::io::Write;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::spec::{self, Assignment, Loaded};

/// The FMI model identifier: the runtime library's file stem.
pub const MODEL_IDENTIFIER: &str = "clr_fmu";
/// The runtime library's file name as cargo builds it.
pub const LIBRARY_FILE: &str = "libclr_fmu.so";
/// The model file inside `resources/`.
pub const MODEL_RESOURCE: &str = "model.toml";
/// The configuration inside `resources/`.
pub const CONFIG_RESOURCE: &str = "clr_fmu.json";

/// Why an FMU cannot be written.
#[derive(Debug, thiserror::Error)]
pub enum FmuError {
    /// The model file is not a planar generic model, or does not load.
    #[error("{0}")]
    Model(String),
    /// An output or parameter named in the request does not exist.
    #[error("{0}")]
    Request(String),
    /// The runtime library was not found.
    #[error(
        "the FMU runtime library {LIBRARY_FILE} was not found ({0}); build it with \
         `cargo build --release -p clr-fmu` (it lands next to `clr` in target/release), or \
         point CLR_FMU_LIBRARY at it"
    )]
    Library(String),
    /// Writing the archive failed.
    #[error("cannot write the FMU {path}: {message}")]
    Io {
        /// The FMU's path.
        path: String,
        /// The system's message.
        message: String,
    },
}

/// The FMI version of an FMU: 3.0 (the default) or 2.0, for masters that read only 2.0. The
/// runtime library is the same (it has both sets of functions).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum FmiVersion {
    /// FMI 2.0 co-simulation.
    V2,
    /// FMI 3.0 co-simulation.
    #[default]
    V3,
}

/// What the FMU exposes besides the inputs.
#[derive(Debug, Clone, Default)]
pub struct FmuRequest {
    /// FMI version (default 3.0).
    pub fmi_version: FmiVersion,
    /// Output columns; `None`: the `[[measure]]` columns, or every column but `t` in a model
    /// without measures.
    pub outputs: Option<Vec<String>>,
    /// Model-file fields made parameters, as `--set` paths (`clearance.B.clearance`,
    /// `body.rod.mass`); each must be written in the file with a number.
    pub parameters: Vec<String>,
    /// Communication step size written as the default experiment's `stepSize`, s (default:
    /// the file's output interval).
    pub step_size: Option<f64>,
}

/// A parameter of the FMU: a model-file field and its value in the file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ParameterConfig {
    /// The `--set` path.
    pub path: String,
    /// The value written in the file.
    pub start: f64,
}

/// A variable of the FMU with its unit ("" when it has none).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VariableConfig {
    /// Name (an input's name, an output column).
    pub name: String,
    /// Unit, ASCII (`N*m`).
    pub unit: String,
    /// One line of description.
    #[serde(default)]
    pub description: String,
    /// Start value (inputs: the default function at the start time).
    #[serde(default)]
    pub start: f64,
}

/// What the runtime reads from `resources/clr_fmu.json`; value references are 0 for time, then
/// the inputs, the outputs and the parameters in this order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FmuConfig {
    /// Model name.
    pub model_name: String,
    /// The instantiation token (a hash of the model file and this configuration).
    pub token: String,
    /// Inputs, in `[[input]]` order.
    pub inputs: Vec<VariableConfig>,
    /// Outputs: columns of the run.
    pub outputs: Vec<VariableConfig>,
    /// Parameters.
    pub parameters: Vec<ParameterConfig>,
    /// Default experiment: start, stop, step (s) and relative tolerance.
    pub experiment: [f64; 4],
}

impl FmuConfig {
    /// Value reference of input k.
    pub fn input_vr(&self, k: usize) -> u32 {
        1 + k as u32
    }
    /// Value reference of output k.
    pub fn output_vr(&self, k: usize) -> u32 {
        1 + (self.inputs.len() + k) as u32
    }
    /// Value reference of parameter k.
    pub fn parameter_vr(&self, k: usize) -> u32 {
        1 + (self.inputs.len() + self.outputs.len() + k) as u32
    }
}

/// The configuration and `modelDescription.xml` of the FMU of model file `src` (`file` names it
/// in messages).
///
/// # Errors
/// [`FmuError::Model`] for a built-in form, a spatial model or a model that does not load;
/// [`FmuError::Request`] for unknown outputs or parameters.
pub fn plan(file: &str, src: &str, req: &FmuRequest) -> Result<(FmuConfig, String), FmuError> {
    let spec = match spec::load_str(file, src, &[]).map_err(|e| FmuError::Model(e.to_string()))? {
        Loaded::Generic(s) => s,
        Loaded::Builtin { name, .. } => {
            return Err(FmuError::Model(format!(
                "{file} is the built-in form of `{name}`; export its complete model first \
                 (`clr export {name} -o model.toml`) or give the name `{name}` itself"
            )))
        }
        Loaded::Spatial(_) => {
            return Err(FmuError::Model(format!(
                "{file} is a spatial model; FMUs are written for planar models in this version"
            )))
        }
    };
    let built = spec.build().map_err(|e| FmuError::Model(e.to_string()))?;
    let (model, opts) = (built.model, built.options);
    let t0 = opts.t0;
    let inputs = model
        .inputs()
        .cells()
        .iter()
        .map(|c| VariableConfig {
            name: c.name().to_string(),
            unit: ascii_unit(c.unit()),
            description: c.description().to_string(),
            start: c.eval(t0)[0],
        })
        .collect();
    let outputs = outputs(&model, req)?;
    let root = toml::from_str::<toml::Table>(src).map_err(|e| FmuError::Model(e.to_string()))?;
    let parameters = req
        .parameters
        .iter()
        .map(|p| parameter(&root, p, file, src))
        .collect::<Result<Vec<_>, _>>()?;
    let step = req.step_size.unwrap_or_else(|| default_step(&opts));
    if !(step.is_finite() && step > 0.0) {
        return Err(FmuError::Request(format!(
            "the step size {step} s must be positive and finite"
        )));
    }
    let mut config = FmuConfig {
        model_name: spec.name.clone(),
        token: String::new(),
        inputs,
        outputs,
        parameters,
        experiment: [t0, opts.t_end, step, opts.rtol],
    };
    config.token = token(src, &config);
    let xml = match req.fmi_version {
        FmiVersion::V3 => model_description(&config, &spec.description),
        FmiVersion::V2 => model_description_v2(&config, &spec.description),
    };
    Ok((config, xml))
}

fn default_step(opts: &clr_mbd::SimOptions) -> f64 {
    match opts.times.as_slice() {
        [a, b, ..] => b - a,
        _ => (opts.t_end - opts.t0) / 500.0,
    }
}

fn outputs(model: &clr_mbd::Model, req: &FmuRequest) -> Result<Vec<VariableConfig>, FmuError> {
    let measures = model.measure_columns();
    let columns = model.columns();
    let unit = |c: &str| {
        measures
            .iter()
            .find(|(n, _)| n == c)
            .map_or_else(|| spec::run::unit_of(c), |(_, u)| u)
    };
    let names: Vec<String> = match &req.outputs {
        Some(list) => list.clone(),
        None if !measures.is_empty() => measures.iter().map(|(n, _)| n.clone()).collect(),
        None => columns.iter().skip(1).cloned().collect(),
    };
    names
        .into_iter()
        .map(|n| {
            if !columns.contains(&n) || n == "t" {
                return Err(FmuError::Request(format!(
                    "no output column `{n}`; {}",
                    spec::locate::suggestion(&n, columns.iter().map(String::as_str))
                )));
            }
            Ok(VariableConfig {
                unit: ascii_unit(unit(&n)),
                name: n,
                description: String::new(),
                start: 0.0,
            })
        })
        .collect()
}

fn parameter(
    root: &toml::Table,
    path: &str,
    file: &str,
    src: &str,
) -> Result<ParameterConfig, FmuError> {
    let v = spec::overrides::get_toml(root, path).map_err(FmuError::Request)?;
    let start = match v {
        toml::Value::Float(f) => f,
        toml::Value::Integer(i) => i as f64,
        other => {
            return Err(FmuError::Request(format!(
                "`{path}` is `{other}` in the file; a parameter must be a number"
            )))
        }
    };
    // the value must also be accepted as an override (the runtime applies it so)
    let a = Assignment {
        path: path.to_string(),
        value: toml::Value::Float(start),
    };
    spec::load_str(file, src, &[a]).map_err(|e| FmuError::Request(e.to_string()))?;
    Ok(ParameterConfig {
        path: path.to_string(),
        start,
    })
}

/// A unit in ASCII as FMI tools expect (`N·m` → `N*m`); "" for none.
fn ascii_unit(u: &str) -> String {
    match u {
        "-" | "m or rad" | "m/s or rad/s" => String::new(),
        u => u.replace('·', "*").replace('²', "^2"),
    }
}

/// FNV-1a of the model file and the configuration, as the FMI instantiation token.
fn token(src: &str, c: &FmuConfig) -> String {
    let json = serde_json::to_string(c).unwrap_or_default();
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in src.bytes().chain(json.bytes()) {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    format!("{{clr-{h:016x}}}")
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The `UnitDefinitions` (every unit of a variable, and s) and `LogCategories` elements, the
/// same in FMI 2.0 and 3.0.
fn units_and_log_categories(c: &FmuConfig) -> String {
    let mut units: Vec<&str> = (c.inputs.iter().chain(&c.outputs))
        .map(|v| v.unit.as_str())
        .filter(|u| !u.is_empty())
        .chain(["s"])
        .collect();
    units.sort_unstable();
    units.dedup();
    let mut x = String::from("  <UnitDefinitions>\n");
    for u in units {
        x.push_str(&format!("    <Unit name=\"{}\"/>\n", xml_escape(u)));
    }
    x.push_str(
        "  </UnitDefinitions>\n  <LogCategories>\n    <Category name=\"logStatusError\"/>\n    \
         <Category name=\"logStatusWarning\"/>\n    <Category name=\"logInfo\"/>\n  \
         </LogCategories>\n",
    );
    x
}

/// `modelDescription.xml` (FMI 3.0, co-simulation) of `c`.
pub fn model_description(c: &FmuConfig, description: &str) -> String {
    let mut x = String::new();
    x.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    x.push_str(&format!(
        "<fmiModelDescription fmiVersion=\"3.0\" modelName=\"{}\" description=\"{}\" \
         instantiationToken=\"{}\" generationTool=\"clr {}\" variableNamingConvention=\"flat\">\n",
        xml_escape(&c.model_name),
        xml_escape(description),
        c.token,
        env!("CARGO_PKG_VERSION"),
    ));
    x.push_str(&format!(
        "  <CoSimulation modelIdentifier=\"{MODEL_IDENTIFIER}\" \
         canHandleVariableCommunicationStepSize=\"true\" canGetAndSetFMUState=\"true\" \
         canSerializeFMUState=\"true\" hasEventMode=\"false\" \
         providesIntermediateUpdate=\"false\" canReturnEarlyAfterIntermediateUpdate=\"false\"/>\n"
    ));
    x.push_str(&units_and_log_categories(c));
    let [t0, t1, h, tol] = c.experiment;
    x.push_str(&format!(
        "  <DefaultExperiment startTime=\"{t0:e}\" stopTime=\"{t1:e}\" stepSize=\"{h:e}\" \
         tolerance=\"{tol:e}\"/>\n"
    ));
    x.push_str("  <ModelVariables>\n");
    x.push_str(
        "    <Float64 name=\"time\" valueReference=\"0\" causality=\"independent\" \
         variability=\"continuous\" description=\"simulation time\" unit=\"s\"/>\n",
    );
    let unit_attr = |u: &str| {
        if u.is_empty() {
            String::new()
        } else {
            format!(" unit=\"{}\"", xml_escape(u))
        }
    };
    for (k, v) in c.inputs.iter().enumerate() {
        x.push_str(&format!(
            "    <Float64 name=\"{}\" valueReference=\"{}\" causality=\"input\" \
             variability=\"continuous\" description=\"{}\"{} start=\"{:e}\"/>\n",
            xml_escape(&v.name),
            c.input_vr(k),
            xml_escape(&v.description),
            unit_attr(&v.unit),
            v.start
        ));
    }
    for (k, v) in c.outputs.iter().enumerate() {
        x.push_str(&format!(
            "    <Float64 name=\"{}\" valueReference=\"{}\" causality=\"output\" \
             variability=\"continuous\" initial=\"calculated\"{}/>\n",
            xml_escape(&v.name),
            c.output_vr(k),
            unit_attr(&v.unit)
        ));
    }
    for (k, p) in c.parameters.iter().enumerate() {
        x.push_str(&format!(
            "    <Float64 name=\"{}\" valueReference=\"{}\" causality=\"parameter\" \
             variability=\"fixed\" start=\"{:e}\" description=\"model-file field {}\"/>\n",
            xml_escape(&p.path),
            c.parameter_vr(k),
            p.start,
            xml_escape(&p.path)
        ));
    }
    x.push_str("  </ModelVariables>\n  <ModelStructure>\n");
    for k in 0..c.outputs.len() {
        x.push_str(&format!(
            "    <Output valueReference=\"{}\"/>\n",
            c.output_vr(k)
        ));
    }
    for k in 0..c.outputs.len() {
        x.push_str(&format!(
            "    <InitialUnknown valueReference=\"{}\"/>\n",
            c.output_vr(k)
        ));
    }
    x.push_str("  </ModelStructure>\n</fmiModelDescription>\n");
    x
}

/// `modelDescription.xml` (FMI 2.0, co-simulation) of `c`: the same variables and value
/// references as [`model_description`], as `ScalarVariable`s.
pub fn model_description_v2(c: &FmuConfig, description: &str) -> String {
    let mut x = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    x.push_str(&format!(
        "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"{}\" description=\"{}\" \
         guid=\"{}\" generationTool=\"clr {}\" variableNamingConvention=\"flat\" \
         numberOfEventIndicators=\"0\">\n",
        xml_escape(&c.model_name),
        xml_escape(description),
        c.token,
        env!("CARGO_PKG_VERSION"),
    ));
    x.push_str(&format!(
        "  <CoSimulation modelIdentifier=\"{MODEL_IDENTIFIER}\" \
         canHandleVariableCommunicationStepSize=\"true\" canGetAndSetFMUstate=\"true\" \
         canSerializeFMUstate=\"true\"/>\n"
    ));
    x.push_str(&units_and_log_categories(c));
    let [t0, t1, h, tol] = c.experiment;
    x.push_str(&format!(
        "  <DefaultExperiment startTime=\"{t0:e}\" stopTime=\"{t1:e}\" stepSize=\"{h:e}\" \
         tolerance=\"{tol:e}\"/>\n  <ModelVariables>\n"
    ));
    let var = |x: &mut String, name: &str, vr: u32, attrs: &str, real: String| {
        x.push_str(&format!(
            "    <ScalarVariable name=\"{}\" valueReference=\"{vr}\" {attrs}>\n      \
             <Real{real}/>\n    </ScalarVariable>\n",
            xml_escape(name)
        ));
    };
    let unit = |u: &str| {
        if u.is_empty() {
            String::new()
        } else {
            format!(" unit=\"{}\"", xml_escape(u))
        }
    };
    var(
        &mut x,
        "time",
        0,
        "causality=\"independent\" variability=\"continuous\"",
        " unit=\"s\"".into(),
    );
    for (k, v) in c.inputs.iter().enumerate() {
        let attrs = format!(
            "causality=\"input\" variability=\"continuous\" description=\"{}\"",
            xml_escape(&v.description)
        );
        var(
            &mut x,
            &v.name,
            c.input_vr(k),
            &attrs,
            format!("{} start=\"{:e}\"", unit(&v.unit), v.start),
        );
    }
    for (k, v) in c.outputs.iter().enumerate() {
        let attrs = "causality=\"output\" variability=\"continuous\" initial=\"calculated\"";
        var(&mut x, &v.name, c.output_vr(k), attrs, unit(&v.unit));
    }
    for (k, p) in c.parameters.iter().enumerate() {
        let attrs = format!(
            "causality=\"parameter\" variability=\"fixed\" initial=\"exact\" \
             description=\"model-file field {}\"",
            xml_escape(&p.path)
        );
        var(
            &mut x,
            &p.path,
            c.parameter_vr(k),
            &attrs,
            format!(" start=\"{:e}\"", p.start),
        );
    }
    // 1-based indices in ModelVariables: time, the inputs, then the outputs
    let first_output = 2 + c.inputs.len();
    x.push_str("  </ModelVariables>\n  <ModelStructure>\n    <Outputs>\n");
    for k in 0..c.outputs.len() {
        x.push_str(&format!(
            "      <Unknown index=\"{}\"/>\n",
            first_output + k
        ));
    }
    x.push_str("    </Outputs>\n    <InitialUnknowns>\n");
    for k in 0..c.outputs.len() {
        x.push_str(&format!(
            "      <Unknown index=\"{}\"/>\n",
            first_output + k
        ));
    }
    x.push_str("    </InitialUnknowns>\n  </ModelStructure>\n</fmiModelDescription>\n");
    x
}

/// The runtime library: `CLR_FMU_LIBRARY`, else `libclr_fmu.so` next to the running program.
///
/// # Errors
/// [`FmuError::Library`] saying where it looked.
pub fn find_library() -> Result<PathBuf, FmuError> {
    if let Some(p) = std::env::var_os("CLR_FMU_LIBRARY") {
        let p = PathBuf::from(p);
        return if p.is_file() {
            Ok(p)
        } else {
            Err(FmuError::Library(format!(
                "CLR_FMU_LIBRARY={} is not a file",
                p.display()
            )))
        };
    }
    let exe = std::env::current_exe().map_err(|e| FmuError::Library(e.to_string()))?;
    let dir = exe.parent().map(Path::to_path_buf).unwrap_or_default();
    // next to the program, or one level up (a test binary runs from target/<profile>/deps)
    for d in [dir.clone(), dir.join("..")] {
        let p = d.join(LIBRARY_FILE);
        if p.is_file() {
            return Ok(p);
        }
    }
    Err(FmuError::Library(format!("looked in {}", dir.display())))
}

/// Write the FMU of model file `src` to `out` with the runtime library at `library`.
///
/// # Errors
/// As [`plan`], and [`FmuError::Io`].
pub fn write(
    out: &Path,
    (file, src): (&str, &str),
    req: &FmuRequest,
    library: &Path,
) -> Result<FmuConfig, FmuError> {
    let (config, xml) = plan(file, src, req)?;
    let platform = match req.fmi_version {
        FmiVersion::V3 => "x86_64-linux",
        FmiVersion::V2 => "linux64",
    };
    let io = |e: std::io::Error| FmuError::Io {
        path: out.display().to_string(),
        message: e.to_string(),
    };
    let lib = std::fs::read(library).map_err(|e| FmuError::Library(e.to_string()))?;
    let json = serde_json::to_string_pretty(&config).unwrap_or_default();
    let entries: [(String, &[u8]); 4] = [
        ("modelDescription.xml".into(), xml.as_bytes()),
        (
            format!("binaries/{platform}/{MODEL_IDENTIFIER}.so"),
            lib.as_slice(),
        ),
        (format!("resources/{MODEL_RESOURCE}"), src.as_bytes()),
        (format!("resources/{CONFIG_RESOURCE}"), json.as_bytes()),
    ];
    // written under a temporary name and renamed: the FMU is complete or absent
    let tmp = out.with_extension("fmu.part");
    let mut f = std::fs::File::create(&tmp).map_err(io)?;
    zip::write(&mut f, &entries).map_err(io)?;
    f.flush().map_err(io)?;
    drop(f);
    std::fs::rename(&tmp, out).map_err(io)?;
    Ok(config)
}

/// A minimal zip writer (deflate, no directories entries needed by FMI tools).
mod zip {
    use std::io::{self, Write};

    use flate2::write::DeflateEncoder;
    use flate2::Compression;

    /// Write `entries` (name, bytes) as a zip archive.
    pub(super) fn write(out: &mut impl Write, entries: &[(String, &[u8])]) -> io::Result<()> {
        let mut central = Vec::new();
        let mut offset: u32 = 0;
        for (name, data) in entries {
            let mut enc = DeflateEncoder::new(Vec::new(), Compression::default());
            enc.write_all(data)?;
            let packed = enc.finish()?;
            let crc = crc32fast::hash(data);
            let size =
                |n: usize| u32::try_from(n).map_err(|_| io::Error::other("an entry exceeds 4 GiB"));
            let (csize, usize_) = (size(packed.len())?, size(data.len())?);
            let name_len = u16::try_from(name.len()).map_err(io::Error::other)?;
            let mut local = Vec::with_capacity(30 + name.len());
            local.extend_from_slice(&0x0403_4b50u32.to_le_bytes());
            header_common(&mut local, crc, csize, usize_, name_len);
            local.extend_from_slice(name.as_bytes());
            out.write_all(&local)?;
            out.write_all(&packed)?;
            central.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
            central.extend_from_slice(&20u16.to_le_bytes()); // version made by
            header_common(&mut central, crc, csize, usize_, name_len);
            central.extend_from_slice(&[0; 6]); // comment length, disk, internal attributes
            central.extend_from_slice(&0u32.to_le_bytes()); // external attrs
            central.extend_from_slice(&offset.to_le_bytes());
            central.extend_from_slice(name.as_bytes());
            offset = offset
                .checked_add(size(local.len() + packed.len())?)
                .ok_or_else(|| io::Error::other("the archive exceeds 4 GiB"))?;
        }
        out.write_all(&central)?;
        let n = u16::try_from(entries.len()).map_err(io::Error::other)?;
        let mut end = Vec::new();
        end.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
        end.extend_from_slice(&[0; 4]); // disk numbers
        end.extend_from_slice(&n.to_le_bytes());
        end.extend_from_slice(&n.to_le_bytes());
        end.extend_from_slice(&(central.len() as u32).to_le_bytes());
        end.extend_from_slice(&offset.to_le_bytes());
        end.extend_from_slice(&0u16.to_le_bytes());
        out.write_all(&end)
    }

    /// The fields shared by local and central headers from "version needed" to "extra length".
    fn header_common(b: &mut Vec<u8>, crc: u32, csize: u32, size: u32, name_len: u16) {
        b.extend_from_slice(&20u16.to_le_bytes()); // version needed
        b.extend_from_slice(&0u16.to_le_bytes()); // flags
        b.extend_from_slice(&8u16.to_le_bytes()); // deflate
        b.extend_from_slice(&0u16.to_le_bytes()); // time
        b.extend_from_slice(&0x21u16.to_le_bytes()); // date 1980-01-01
        b.extend_from_slice(&crc.to_le_bytes());
        b.extend_from_slice(&csize.to_le_bytes());
        b.extend_from_slice(&size.to_le_bytes());
        b.extend_from_slice(&name_len.to_le_bytes());
        b.extend_from_slice(&0u16.to_le_bytes()); // extra length
    }
}
