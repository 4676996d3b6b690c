//! The tables of a run's time series, as read back by `clr plot` from results.csv
//! ([`super::output::read_csv`]) or results.parquet ([`super::parquet::read_table`]), and the
//! column names of the impacts table shared by impacts.csv and impacts.parquet.

/// Columns of a results file: names (units stripped), units and rows.
pub(crate) struct Table {
    /// Column names, as in the results.csv header without the unit.
    pub names: Vec<String>,
    /// Column units (empty when the file has none).
    pub units: Vec<String>,
    /// Rows of values.
    pub rows: Vec<Vec<f64>>,
}

impl Table {
    /// The values of column `k`.
    pub(crate) fn column(&self, k: usize) -> Vec<f64> {
        self.rows.iter().map(|r| r[k]).collect()
    }
}

/// Header of `impacts.csv` (units in the names; docs/cli.md).
pub(crate) const IMPACTS_HEADER: &str = "joint,onset_s,impact_velocity_m_per_s,peak_force_N,\
peak_force_time_s,max_penetration_m,max_penetration_time_s,separation_s,duration_s";
