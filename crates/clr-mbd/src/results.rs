//! The recorded output of a run (below the integration driver, so that errors can carry the
//! partial results without depending on it).

use std::io::Write;
use std::path::Path;

use clr_ode::Stats;

/// The energy columns of every run, planar or spatial (J; see [`Results`]).
pub(crate) const ENERGY_COLUMNS: [&str; 7] = [
    "energy.kinetic",
    "energy.potential",
    "energy.elastic",
    "energy.total",
    "energy.dissipated",
    "energy.work_in",
    "energy.balance",
];

/// The first columns of every clearance joint `C`, planar or spatial: `C.<name>` (m, m/s, N, N,
/// 1/0; see [`Results`]).
pub(crate) const CONTACT_COLUMNS: [&str; 5] = [
    "penetration",
    "rate",
    "normal_force",
    "friction_force",
    "contact",
];

/// The units a user may give a column or a metric (`unit = "N"`), in clr's spelling: SI, `*`
/// for products, `^` for powers, `-` for dimensionless.
pub const UNITS: [&str; 26] = [
    "-", "s", "1/s", "Hz", "m", "m/s", "m/s^2", "m^2", "rad", "rad/s", "rad/s^2", "kg", "kg*m^2",
    "N", "N/m", "N*s/m", "N*s", "N*m", "N*m/rad", "N*m*s", "Pa", "J", "W", "kg*m/s", "kg*m^2/s",
    "m*N",
];

/// The spelling in [`UNITS`] of the unit `u`, or `None` for a unit clr does not know (a
/// misspelling, or a unit in mm or degrees, which clr does not use).
pub fn known_unit(u: &str) -> Option<&'static str> {
    UNITS.iter().find(|k| **k == u.trim()).copied()
}

/// Unit of a result column from its name (the columns of [`Results`], planar and spatial, the
/// `[[measure]]` suffixes of [`crate::measure`] and the derived columns of the built-in models):
/// `s`, `m`, `rad`, `N`, … or `-` (modal amplitudes, flags, unknown names).
pub fn unit_of(column: &str) -> &'static str {
    match column {
        "t" => return "s",
        "violation.position" => return "m or rad",
        "violation.velocity" => return "m/s or rad/s",
        "violation.quaternion" => return "-",
        _ if column.starts_with("energy.") => return "J",
        _ => {}
    }
    match column.rsplit('.').next().unwrap_or(column) {
        "x" | "y" | "z" | "u" | "v" | "ux" | "uy" | "ex" | "ey" | "ez" | "penetration"
        | "lugre_z" | "lugre_zx" | "lugre_zy" | "lugre_zz" | "film_thickness" | "axial_offset"
        | "error" | "distance" => "m",
        "theta" | "rz" | "tilt" | "angle" => "rad",
        "vx" | "vy" | "vz" | "rate" | "distance_rate" => "m/s",
        "omega" | "wx" | "wy" | "wz" => "rad/s",
        "ax" | "ay" | "az" => "m/s^2",
        "alpha" | "alphax" | "alphay" | "alphaz" => "rad/s^2",
        "Fx" | "Fy" | "Fz" | "F" | "normal_force" | "friction_force" | "film_force" | "ftx"
        | "fty" | "ftz" => "N",
        "M" | "Mx" | "My" | "Mz" => "N*m",
        "px" | "py" => "kg*m/s",
        "L" => "kg*m^2/s",
        "energy" => "J",
        _ => "-",
    }
}

/// Recorded output: one row per output point, named columns; arrays via [`Results::column`].
///
/// Columns, in order: `t`; per body `B.x B.y B.theta B.vx B.vy B.omega B.ax B.ay B.alpha`; per
/// flexible beam its free nodal displacements `beam.n<node>.<u|v|theta>` (m, rad); per
/// joint or driver `J.Fx J.Fy J.M` (reaction on its second body, or on its first when the second
/// is the ground, about that body's centre of mass); per clearance joint `C.penetration
/// C.rate C.normal_force C.friction_force C.contact C.ex C.ey` (eccentricity in the bearing
/// body's frame), followed by `C.lugre_z` for a joint with LuGre friction (its bristle deflection
/// in m; for a translational joint the F_N-weighted mean over its loaded corners, so that
/// σ₀·lugre_z·ΣF_N is the elastic bristle part of the friction force; the plain mean of its
/// corners when none is loaded); `energy.kinetic energy.potential energy.elastic energy.total
/// energy.dissipated energy.work_in energy.balance` (J: `dissipated` is the energy dissipated
/// since t0 by dampers, contact damping and friction; `work_in` the work done on the system since
/// t0 by drivers (their reaction forces) and applied forces, torques, actuator forces, nodal
/// loads, bushings and custom loads; `balance` = total + dissipated − work_in, constant up to
/// the integration error and the work of constraint reactions through violations);
/// `violation.position violation.velocity` (‖Φ‖∞, ‖Φ̇‖∞). Per floating flexible body its
/// coordinates `F.x F.y F.theta F.q<k>` follow the beams' (units and meaning of each `q<k>`:
/// [`Model::flexible_coordinates`](crate::Model::flexible_coordinates)), then the recorded
/// nodes `<body>.node<k>.<ux|uy|rz|x|y>` (opt-in, [`crate::node_output`]).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Results {
    /// Column names.
    pub columns: Vec<String>,
    /// Row-major values, `columns.len()` per row.
    pub data: Vec<f64>,
    /// Solver statistics (accumulated over restarts).
    pub stats: Stats,
    /// Number of contact onsets located as events.
    pub onsets: usize,
    /// Number of projections applied.
    pub projections: usize,
    /// Largest ‖Φ‖∞ seen after accepted steps (before any projection), m or rad.
    pub max_position_violation: f64,
    /// Final state (q, q̇, dissipated energy E_d in J, input work W_in in J, LuGre bristle
    /// states in m; see [`Model::n_bristle_states`](crate::Model::n_bristle_states)).
    pub y_final: Vec<f64>,
    /// Automatic choices the run made for the user, in words (for example the Newton matrix
    /// falling back to finite differences for a model with LuGre bristle states).
    pub notes: Vec<String>,
    /// Impacts of the clearance joints located on the dense output, in onset order
    /// ([`Impact`](crate::Impact); onset, impact velocity m/s, peak normal force N and largest
    /// penetration m with their times, separation and duration s). A failed run carries the
    /// impacts up to its last accepted step, the one under way with `separation: None`.
    pub impacts: Vec<crate::Impact>,
    /// What the assembly of consistent initial conditions solved and changed (set by
    /// [`Model::simulate`](crate::Model::simulate); `None` from
    /// [`Model::simulate_from`](crate::Model::simulate_from), which starts from the state it is
    /// given).
    pub initial_conditions: Option<crate::InitialConditions>,
    /// Findings of the plausibility checks before and after the run ([`crate::plausible`];
    /// set by [`Model::simulate`](crate::Model::simulate)).
    pub warnings: Vec<crate::initial_data::Warning>,
    /// Units of the columns whose name does not fix them (the deviation columns `<name>.error`,
    /// in the unit of what they compare); every other column's unit is [`unit_of`] its name.
    pub units: Vec<(String, &'static str)>,
}

impl Results {
    /// The unit of column `name`: its entry in [`Results::units`], else [`unit_of`] its name.
    pub fn unit(&self, name: &str) -> &'static str {
        (self.units.iter())
            .find(|(c, _)| c == name)
            .map_or_else(|| unit_of(name), |(_, u)| *u)
    }

    /// Append columns (name, one value per row) after the last one.
    ///
    /// # Panics
    /// When a column does not have one value per row (a caller's bug, not an input).
    pub fn append_columns(&mut self, new: Vec<(String, Vec<f64>)>) {
        if new.is_empty() {
            return;
        }
        let n = self.len();
        assert!(new.iter().all(|(_, v)| v.len() == n), "one value per row");
        let w = self.columns.len();
        let mut data = Vec::with_capacity(n * (w + new.len()));
        for r in 0..n {
            data.extend_from_slice(&self.data[r * w..(r + 1) * w]);
            data.extend(new.iter().map(|(_, v)| v[r]));
        }
        self.columns.extend(new.into_iter().map(|(c, _)| c));
        self.data = data;
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        if self.columns.is_empty() {
            0
        } else {
            self.data.len() / self.columns.len()
        }
    }
    /// True without rows.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Index of a column by name.
    pub fn index(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }
    /// A column as an array (`None` for unknown names).
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let k = self.index(name)?;
        let w = self.columns.len();
        Some(self.data.chunks_exact(w).map(|r| r[k]).collect())
    }
    /// Row `r`.
    pub fn row(&self, r: usize) -> &[f64] {
        let w = self.columns.len();
        &self.data[r * w..(r + 1) * w]
    }
    /// Write all rows as CSV with a header line.
    ///
    /// # Errors
    /// The I/O error of creating or writing the file.
    pub fn write_csv(&self, path: &Path) -> std::io::Result<()> {
        let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
        writeln!(f, "{}", self.columns.join(","))?;
        for r in 0..self.len() {
            let row: Vec<String> = self.row(r).iter().map(|v| format!("{v:e}")).collect();
            writeln!(f, "{}", row.join(","))?;
        }
        f.flush()?;
        Ok(())
    }
}
