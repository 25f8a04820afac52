//! Python values into what the library reads: a builder's dicts and lists into TOML values,
//! wavelengths (numbers of nm or length strings) into lengths.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use spectrace::units::{Length, length::nanometer};

/// How deep a scene's dicts and lists may nest (a list that holds itself would not end).
const MAX_DEPTH: usize = 64;

/// One Python value as a TOML value; `at` names it in errors, `depth` counts the nesting.
pub(crate) fn to_toml(v: &Bound<'_, PyAny>, at: &str, depth: usize) -> PyResult<toml::Value> {
    use toml::Value;
    if depth > MAX_DEPTH {
        let short: String = at.chars().take(40).collect();
        return Err(PyValueError::new_err(format!(
            "{short}…: nested more than {MAX_DEPTH} deep (a list or dict that holds itself?)"
        )));
    }
    if v.is_instance_of::<PyBool>() {
        return Ok(Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return Ok(Value::Integer(v.extract().map_err(|_| {
            PyValueError::new_err(format!("{at}: integer out of range"))
        })?));
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(Value::Float(v.extract()?));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(Value::String(v.extract()?));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        let mut t = toml::Table::new();
        for (k, x) in d.iter() {
            let k: String = k
                .extract()
                .map_err(|_| PyValueError::new_err(format!("{at}: keys must be strings")))?;
            let sub = if at.is_empty() {
                k.clone()
            } else {
                format!("{at}.{k}")
            };
            t.insert(k, to_toml(&x, &sub, depth + 1)?);
        }
        return Ok(Value::Table(t));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let mut a = Vec::new();
        for (i, x) in v.try_iter()?.enumerate() {
            a.push(to_toml(&x?, &format!("{at}[{i}]"), depth + 1)?);
        }
        return Ok(Value::Array(a));
    }
    // NumPy scalars and arrays, os.PathLike
    let py = v.py();
    if v.hasattr("tolist")? {
        return to_toml(&v.call_method0("tolist")?, at, depth + 1);
    }
    if let Ok(p) = py.import("os")?.call_method1("fspath", (v,))
        && let Ok(text) = p.extract::<String>()
    {
        return Ok(Value::String(text));
    }
    Err(PyValueError::new_err(format!(
        "{at}: a {} cannot be written in a scene (numbers, strings, booleans, lists and dicts can)",
        v.get_type().name()?
    )))
}

/// A wavelength: a number of nm, or a string: a bare number of nm or a length with its unit
/// ("0.55 um"), read by the scene format's quantity parser.
pub(crate) fn wavelength(v: &Bound<'_, PyAny>) -> PyResult<Length> {
    if let Ok(s) = v.extract::<String>() {
        if let Ok(nm) = s.trim().parse::<f64>() {
            return Ok(Length::new::<nanometer>(nm));
        }
        return spectrace::units::parse::parse::<Length>(&s)
            .map_err(|e| PyValueError::new_err(format!("wavelength: {e}")));
    }
    let nm: f64 = v.extract().map_err(|_| {
        PyValueError::new_err(format!(
            "wavelength {}: expected a number of nm or a string such as \"0.55 um\"",
            v.repr().map(|r| r.to_string()).unwrap_or_default()
        ))
    })?;
    Ok(Length::new::<nanometer>(nm))
}
