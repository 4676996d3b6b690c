//! `clr_sim.fmu.export`: the FMU of a model file's text (`clr_sim::fmu`).

use pyo3::prelude::*;

/// Write the FMU of the model file text `src` (`file` names it in messages) to `out` with the
/// runtime library at `library`; returns the FMU's configuration as JSON text.
#[pyfunction]
#[pyo3(signature = (src, file, out, library, outputs=None, parameters=Vec::new(), step_size=None))]
pub(crate) fn fmu_export(
    src: &str,
    file: &str,
    out: &str,
    library: &str,
    outputs: Option<Vec<String>>,
    parameters: Vec<String>,
    step_size: Option<f64>,
) -> PyResult<String> {
    let req = clr_sim::fmu::FmuRequest {
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
