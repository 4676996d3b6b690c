//! `clr plot results.csv --x time --y a,b` (or results.parquet).

use std::path::{Path, PathBuf};

use clr_plot::Figure;
use clr_sim::spec::locate::suggestion;

use super::output::read_csv;
use super::CliError;

fn find(names: &[String], name: &str) -> Result<usize, CliError> {
    let key = if name == "time" { "t" } else { name };
    names.iter().position(|n| n == key).ok_or_else(|| {
        CliError::Input(format!(
            "no column `{name}` in the file; {}",
            suggestion(name, names.iter().map(String::as_str))
        ))
    })
}

pub(crate) fn plot_command(
    csv: &Path,
    x: &str,
    ys: &[String],
    out: Option<&Path>,
) -> Result<(), CliError> {
    let table = match csv.extension().and_then(|e| e.to_str()) {
        Some("parquet") => super::parquet::read_table(csv)?,
        _ => read_csv(csv)?,
    };
    let xi = find(&table.names, x)?;
    let xs = table.column(xi);
    let label = |k: usize| {
        if table.units[k].is_empty() {
            table.names[k].clone()
        } else {
            format!("{} ({})", table.names[k], table.units[k])
        }
    };
    let mut f = Figure::new(csv.display().to_string()).x_label(label(xi));
    let mut units = Vec::new();
    for y in ys {
        let yi = find(&table.names, y.trim())?;
        let v = table.column(yi);
        if !units.contains(&table.units[yi]) {
            units.push(table.units[yi].clone());
        }
        f = f.line(table.names[yi].clone(), xs.iter().copied().zip(v).collect());
    }
    f = f.y_label(units.join(", "));
    let out: PathBuf = match out {
        Some(p) => p.to_path_buf(),
        None => csv.with_file_name("plot.svg"),
    };
    let err = |e: clr_plot::PlotError| CliError::Input(e.to_string());
    match out.extension().and_then(|e| e.to_str()) {
        Some("svg") => f.save_svg(&out).map_err(err)?,
        Some("png") => f.save_png(&out).map_err(err)?,
        _ => {
            f.save(&out).map_err(err)?;
        }
    }
    eprintln!("clr: wrote {}", out.display());
    Ok(())
}
