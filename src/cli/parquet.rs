//! Time series and impacts as Parquet files (`--series parquet|both`): the columnar, compressed
//! format that pandas (`read_parquet`), polars, Arrow and MATLAB (`parquetread`) read directly.
//!
//! Layout of `results.parquet`: one DOUBLE column per results.csv column, named as in the CSV
//! header without the unit; the units are the file's key-value metadata `clr.units`, a JSON
//! object `{column: unit}`, so a reader keeps them (pyarrow: `pq.read_schema(p).metadata`). The
//! values are the engine's `f64`s, bit for bit (the CSV's shortest round-trip text reads back to
//! the same bits). Doubles are written PLAIN with Snappy compression, which every Parquet reader
//! decodes: on the slider–crank the file is about a third of the CSV (docs/cli.md).
//!
//! `impacts.parquet` has the columns of impacts.csv: `joint` (UTF-8), the times, velocities,
//! forces and penetrations as DOUBLE, and `separation_s`/`duration_s` OPTIONAL (null for an
//! impact still under way at the end of the run).

use std::fs::File;
use std::path::Path;
use std::sync::Arc;

use parquet::basic::{Compression, ConvertedType, Encoding, Repetition, Type as Physical};
use parquet::data_type::ByteArray;
use parquet::file::metadata::KeyValue;
use parquet::file::properties::WriterProperties;
use parquet::file::reader::{FileReader, SerializedFileReader};
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::Type;

use super::series::{Table, IMPACTS_HEADER};
use super::CliError;

/// The metadata key of the units.
pub(crate) const UNITS_KEY: &str = "clr.units";

/// Rows per row group: a reader can skip through a long run without reading it whole, and the
/// writer holds one group of a column at a time (64 Ki rows × 8 B = 512 KiB).
const ROW_GROUP: usize = 1 << 16;

/// One column to write.
enum Column<'a> {
    /// Required doubles.
    Double(&'a str, Vec<f64>),
    /// Optional doubles (None is null).
    OptionalDouble(&'a str, Vec<Option<f64>>),
    /// Required UTF-8 strings.
    Text(&'a str, Vec<String>),
}

impl Column<'_> {
    fn name(&self) -> &str {
        match self {
            Column::Double(n, _) | Column::OptionalDouble(n, _) | Column::Text(n, _) => n,
        }
    }

    fn len(&self) -> usize {
        match self {
            Column::Double(_, v) => v.len(),
            Column::OptionalDouble(_, v) => v.len(),
            Column::Text(_, v) => v.len(),
        }
    }

    fn schema(&self) -> parquet::errors::Result<Type> {
        let (physical, repetition, converted) = match self {
            Column::Double(..) => (Physical::DOUBLE, Repetition::REQUIRED, ConvertedType::NONE),
            Column::OptionalDouble(..) => {
                (Physical::DOUBLE, Repetition::OPTIONAL, ConvertedType::NONE)
            }
            Column::Text(..) => (
                Physical::BYTE_ARRAY,
                Repetition::REQUIRED,
                ConvertedType::UTF8,
            ),
        };
        Type::primitive_type_builder(self.name(), physical)
            .with_repetition(repetition)
            .with_converted_type(converted)
            .build()
    }

    /// Write rows `rows` of this column into the row group's column writer.
    fn write(
        &self,
        w: &mut parquet::column::writer::ColumnWriter<'_>,
        rows: std::ops::Range<usize>,
    ) -> parquet::errors::Result<()> {
        use parquet::column::writer::ColumnWriter as W;
        match (self, w) {
            (Column::Double(_, v), W::DoubleColumnWriter(w)) => {
                w.write_batch(&v[rows], None, None)?;
            }
            (Column::OptionalDouble(_, v), W::DoubleColumnWriter(w)) => {
                let part = &v[rows];
                let values: Vec<f64> = part.iter().flatten().copied().collect();
                let defs: Vec<i16> = part.iter().map(|x| i16::from(x.is_some())).collect();
                w.write_batch(&values, Some(&defs), None)?;
            }
            (Column::Text(_, v), W::ByteArrayColumnWriter(w)) => {
                let values: Vec<ByteArray> = v[rows]
                    .iter()
                    .map(|s| ByteArray::from(s.as_str()))
                    .collect();
                w.write_batch(&values, None, None)?;
            }
            _ => {
                return Err(parquet::errors::ParquetError::General(format!(
                    "column `{}`: writer of another type",
                    self.name()
                )))
            }
        }
        Ok(())
    }
}

fn err(path: &Path, e: impl std::fmt::Display) -> CliError {
    CliError::Input(format!("cannot write {}: {e}", path.display()))
}

/// Write `columns` (all of one length) with the key-value `metadata` to `path`.
fn write_columns(
    path: &Path,
    columns: &[Column<'_>],
    metadata: Vec<KeyValue>,
) -> Result<(), CliError> {
    let fields = columns
        .iter()
        .map(|c| c.schema().map(Arc::new))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| err(path, e))?;
    let schema = Type::group_type_builder("clr")
        .with_fields(fields)
        .build()
        .map_err(|e| err(path, e))?;
    // Dictionary encoding is useless for doubles that are nearly all distinct. PLAIN rather than
    // BYTE_STREAM_SPLIT (10 % smaller on the slider–crank): every Parquet reader decodes PLAIN
    // and Snappy, while byte-stream split is missing from older Arrow builds such as those inside
    // MATLAB's parquetread.
    let props = WriterProperties::builder()
        .set_compression(Compression::SNAPPY)
        .set_dictionary_enabled(false)
        .set_encoding(Encoding::PLAIN)
        .set_column_dictionary_enabled("joint".into(), true)
        .set_key_value_metadata(Some(metadata))
        .set_created_by(format!("clr {}", clr_models::provenance::CLR_VERSION))
        .build();
    let file = File::create(path).map_err(|e| err(path, e))?;
    let mut writer = SerializedFileWriter::new(file, Arc::new(schema), Arc::new(props))
        .map_err(|e| err(path, e))?;
    let n = columns.first().map_or(0, Column::len);
    let mut start = 0;
    // An empty table still gets one (empty) row group, so that readers see its schema.
    loop {
        let rows = start..(start + ROW_GROUP).min(n);
        let mut group = writer.next_row_group().map_err(|e| err(path, e))?;
        for c in columns {
            let mut w = group
                .next_column()
                .map_err(|e| err(path, e))?
                .ok_or_else(|| err(path, "fewer columns in the schema than given"))?;
            c.write(w.untyped(), rows.clone())
                .map_err(|e| err(path, e))?;
            w.close().map_err(|e| err(path, e))?;
        }
        group.close().map_err(|e| err(path, e))?;
        start = rows.end;
        if start >= n {
            break;
        }
    }
    writer.close().map_err(|e| err(path, e))?;
    Ok(())
}

/// Write the run's time series as `results.parquet` (the columns of results.csv).
pub(crate) fn write_results(
    path: &Path,
    res: &clr_mbd::Results,
    units: &[String],
) -> Result<(), CliError> {
    let width = res.columns.len();
    let columns: Vec<Column<'_>> = (res.columns.iter().enumerate())
        .map(|(k, name)| {
            let values = (0..res.len()).map(|r| res.data[r * width + k]).collect();
            Column::Double(name.as_str(), values)
        })
        .collect();
    let units: serde_json::Map<String, serde_json::Value> = (res.columns.iter())
        .zip(units)
        .map(|(c, u)| (c.clone(), serde_json::Value::String(u.clone())))
        .collect();
    let units = serde_json::Value::Object(units).to_string();
    write_columns(path, &columns, vec![KeyValue::new(UNITS_KEY.into(), units)])
}

/// Write the located impacts as `impacts.parquet` (the columns of impacts.csv).
pub(crate) fn write_impacts(path: &Path, impacts: &[clr_mbd::Impact]) -> Result<(), CliError> {
    let names: Vec<&str> = IMPACTS_HEADER.split(',').collect();
    let d = |k: usize, f: fn(&clr_mbd::Impact) -> f64| {
        Column::Double(names[k], impacts.iter().map(f).collect())
    };
    let columns = vec![
        Column::Text(names[0], impacts.iter().map(|i| i.joint.clone()).collect()),
        d(1, |i| i.onset),
        d(2, |i| i.impact_velocity),
        d(3, |i| i.peak_force),
        d(4, |i| i.peak_force_time),
        d(5, |i| i.max_penetration),
        d(6, |i| i.max_penetration_time),
        Column::OptionalDouble(names[7], impacts.iter().map(|i| i.separation).collect()),
        Column::OptionalDouble(names[8], impacts.iter().map(|i| i.duration).collect()),
    ];
    write_columns(path, &columns, Vec::new())
}

fn read_err(path: &Path, e: impl std::fmt::Display) -> CliError {
    CliError::Input(format!("cannot read {}: {e}", path.display()))
}

/// Read a `results.parquet` (or any Parquet file of required DOUBLE columns) into a table; the
/// units come from the `clr.units` metadata, empty when absent.
pub(crate) fn read_table(path: &Path) -> Result<Table, CliError> {
    let file = File::open(path).map_err(|e| read_err(path, e))?;
    let reader = SerializedFileReader::new(file).map_err(|e| read_err(path, e))?;
    let meta = reader.metadata();
    let schema = meta.file_metadata().schema_descr();
    let mut names = Vec::new();
    for c in schema.columns() {
        if c.physical_type() != Physical::DOUBLE || c.max_def_level() != 0 {
            return Err(read_err(
                path,
                format!("column `{}` is not a required DOUBLE", c.name()),
            ));
        }
        names.push(c.name().to_string());
    }
    let units_map: serde_json::Map<String, serde_json::Value> = (meta.file_metadata())
        .key_value_metadata()
        .and_then(|kv| kv.iter().find(|k| k.key == UNITS_KEY))
        .and_then(|k| k.value.as_deref())
        .and_then(|v| serde_json::from_str(v).ok())
        .unwrap_or_default();
    let units = (names.iter())
        .map(|n| {
            units_map
                .get(n)
                .and_then(|u| u.as_str())
                .unwrap_or("")
                .to_string()
        })
        .collect();
    let rows_total = usize::try_from(meta.file_metadata().num_rows()).unwrap_or(0);
    let mut columns: Vec<Vec<f64>> = vec![Vec::with_capacity(rows_total); names.len()];
    for g in 0..meta.num_row_groups() {
        let group = reader.get_row_group(g).map_err(|e| read_err(path, e))?;
        let rows = usize::try_from(meta.row_group(g).num_rows()).unwrap_or(0);
        for (k, col) in columns.iter_mut().enumerate() {
            let mut r = group.get_column_reader(k).map_err(|e| read_err(path, e))?;
            let parquet::column::reader::ColumnReader::DoubleColumnReader(r) = &mut r else {
                return Err(read_err(path, "column reader of another type"));
            };
            let mut buf = Vec::with_capacity(rows);
            let (records, _, _) =
                (r.read_records(rows, None, None, &mut buf)).map_err(|e| read_err(path, e))?;
            if records != rows {
                return Err(read_err(path, format!("row group {g} is short")));
            }
            col.extend_from_slice(&buf);
        }
    }
    let n = columns.first().map_or(0, Vec::len);
    let rows = (0..n)
        .map(|r| columns.iter().map(|c| c[r]).collect())
        .collect();
    Ok(Table { names, units, rows })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Written and read back through the parquet crate's reader (an independent decoder of the
    /// encoding): every value bit for bit, the special ones (NaN, ±0, ±∞, subnormal) included,
    /// over more than one row group; the units from the metadata.
    #[test]
    fn results_read_back_bit_for_bit_over_row_groups() {
        let rows = ROW_GROUP + 17;
        let special = [
            f64::NAN,
            -0.0,
            0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            5e-324,
        ];
        let value = |r: usize, k: usize| match (r % 1000, k) {
            (i, 1) if i < special.len() => special[i],
            _ => (r as f64 * 1e-5).sin() * 10f64.powi(k as i32 - 3),
        };
        let res = clr_mbd::Results {
            columns: vec!["t".into(), "a.x".into(), "b.q0".into()],
            data: (0..rows)
                .flat_map(|r| (0..3).map(move |k| value(r, k)))
                .collect(),
            ..Default::default()
        };
        let units = vec!["s".to_string(), "m".into(), "".into()];
        let dir = std::env::temp_dir().join(format!("clr-parquet-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("results.parquet");
        write_results(&path, &res, &units).unwrap();
        let t = read_table(&path).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(t.names, res.columns);
        assert_eq!(t.units, units);
        assert_eq!(t.rows.len(), rows);
        for (r, row) in t.rows.iter().enumerate() {
            for (k, v) in row.iter().enumerate() {
                assert_eq!(v.to_bits(), value(r, k).to_bits(), "row {r} column {k}");
            }
        }
    }

    /// An impacts table is not a results table: reading it is refused with the column named.
    #[test]
    fn a_table_with_text_is_refused_by_name() {
        let dir = std::env::temp_dir().join(format!("clr-parquet-imp-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("impacts.parquet");
        write_impacts(&path, &[]).unwrap();
        let e = format!("{:?}", read_table(&path).err());
        std::fs::remove_dir_all(&dir).unwrap();
        assert!(e.contains("`joint` is not a required DOUBLE"), "{e}");
    }
}
