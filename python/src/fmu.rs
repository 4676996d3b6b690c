//! `clr_sim.fmu.export`: the FMU of a model file's text (`clr_sim::fmu`).

use pyo3::prelude::*;

/// Write the FMU of the model file text `src` (`file` names it in messages) to `out` with the
/// runtime library at `library`; returns the FMU's configuration as JSON text.
#[pyfunction]
#[pyo3(signature = (src, file, out, library, outputs=None, parameters=Vec::new(), step_size=None, fmi_version=3))]
#[allow(clippy::too_many_arguments)] // one Python keyword argument each
pub(crate) fn fmu_export(
    src: &str,
    file: &str,
    out: &str,
    library: &str,
    outputs: Option<Vec<String>>,
    parameters: Vec<String>,
    step_size: Option<f64>,
    fmi_version: u8,
) -> PyResult<String> {
    let fmi_version = match fmi_version {
        2 => clr_sim::fmu::FmiVersion::V2,
        3 => clr_sim::fmu::FmiVersion::V3,
        v => {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "fmi_version={v}: give 3 (FMI 3.0, the default) or 2 (FMI 2.0)"
            )))
        }
    };
    let req = clr_sim::fmu::FmuRequest {
        fmi_version,
        outputs,
        parameters,
        step_size,
    };
    let config = clr_sim::fmu::write(
        std::path::Path::new(out),
        (file, src),
        &req,
        std::path::Path::new(library),
    )
    .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
    serde_json::to_string(&config)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))
}
