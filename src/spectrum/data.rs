//! Spectra from data tables: the CSV format and the embedded files are [`crate::data`]'s (a
//! leaf that `colour` reads too); this module turns a table's columns into curves.

use std::path::Path;

pub(crate) use crate::data::embedded_table;
pub use crate::data::{DataError, Table, embedded, parse_csv};

/// Reads a user spectrum file: CSV with a wavelength column in nm (`wavelength_nm`, or the first
/// column) and one value column. Errors name the file and line.
pub fn load_spectrum_file(path: &Path) -> Result<super::curve::PiecewiseLinear, DataError> {
    let file = path.display().to_string();
    let text =
        crate::files::read_text(path, crate::files::MAX_TEXT_BYTES).map_err(|e| DataError {
            file: file.clone(),
            line: 0,
            message: format!("cannot read: {e}"),
        })?;
    parse_spectrum_text(&text, &file)
}

/// Parses the text of a user spectrum file as [`load_spectrum_file`] does; `file` names it in
/// errors.
pub fn parse_spectrum_text(
    text: &str,
    file: &str,
) -> Result<super::curve::PiecewiseLinear, DataError> {
    let file = file.to_string();
    let table = parse_csv(text, &file)?;
    if table.columns.len() != 2 {
        return Err(DataError {
            file,
            line: table.row_lines[0],
            message: format!(
                "expected 2 columns (wavelength_nm,value), found {}",
                table.columns.len()
            ),
        });
    }
    table_to_curve(&table, 0, 1, &file)
}

/// Column `value_col` against column `lambda_col` (nm) as a piecewise-linear curve.
pub fn table_to_curve(
    table: &Table,
    lambda_col: usize,
    value_col: usize,
    file: &str,
) -> Result<super::curve::PiecewiseLinear, DataError> {
    let lambda: Vec<f32> = table.column(lambda_col).iter().map(|&v| v as f32).collect();
    // a wavelength of 0 nm or less is no wavelength (inline samples refuse it too)
    if let Some(i) = lambda.iter().position(|&l| !(l > 0.0)) {
        return Err(DataError {
            file: file.to_string(),
            line: table.row_lines[i],
            message: format!("wavelength {} nm is not positive", lambda[i]),
        });
    }
    let value: Vec<f32> = table.column(value_col).iter().map(|&v| v as f32).collect();
    super::curve::PiecewiseLinear::new(lambda, value).map_err(|e| {
        let line = match e {
            super::curve::TableError::NotIncreasing { index, .. }
            | super::curve::TableError::NonFinite { index, .. } => table.row_lines[index],
            _ => table.row_lines[0],
        };
        DataError {
            file: file.to_string(),
            line,
            message: e.to_string(),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn curve_errors_name_the_line() {
        let t = parse_csv("l,v\n500,1\n400,2\n", "s.csv").unwrap();
        assert_eq!(table_to_curve(&t, 0, 1, "s.csv").unwrap_err().line, 3);
        let t = parse_csv("l,v\n0,1\n400,2\n", "s.csv").unwrap();
        assert_eq!(table_to_curve(&t, 0, 1, "s.csv").unwrap_err().line, 2);
    }
}
