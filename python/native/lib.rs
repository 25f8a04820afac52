//! `spectrace._native`: the Python extension over `spectrace::api`. The Python package
//! (`python/spectrace/__init__.py`) wraps it with NumPy arrays and the scene builder; this
//! module only moves values across: scenes as TOML (the scene format's own checks and error
//! locations apply), images as little-endian `f32` bytes, quantities in the units the names
//! say.
//!
//! Rendering and measuring run on a Rust thread with the GIL released; the calling thread
//! wakes every 50 ms to run Python's signal handlers, so Ctrl-C (KeyboardInterrupt) stops the
//! work at its next check and is raised in Python ([`interruptible`]).

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

mod convert;
mod image;

use image::Image;
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use spectrace::units::{Length, length::nanometer};

pyo3::create_exception!(
    _native,
    SpectraceError,
    PyException,
    "A scene that does not load (file:line:col: field: message; also as the attributes file, line, column and field), an option out of range, or an unknown spectrum."
);

/// A SpectraceError with the message, and where the scene was wrong as attributes `file`,
/// `line`, `column` and `field` (None when the error is not in a scene).
fn err(e: spectrace::Error) -> PyErr {
    let py_err = SpectraceError::new_err(e.to_string());
    let at = match &e {
        spectrace::Error::Scene(l) => Some((
            l.file.display().to_string(),
            l.loc.line,
            l.loc.col,
            l.field.clone(),
        )),
        _ => None,
    };
    Python::attach(|py| {
        let v = py_err.value(py);
        let (file, line, column, field) = match at {
            Some((f, l, c, d)) => (Some(f), Some(l), Some(c), (!d.is_empty()).then_some(d)),
            None => (None, None, None, None),
        };
        // setting attributes on a fresh exception object cannot fail but for memory
        let _ = v.setattr("file", file);
        let _ = v.setattr("line", line);
        let _ = v.setattr("column", column);
        let _ = v.setattr("field", field);
    });
    py_err
}

/// A render-ready scene.
#[pyclass(frozen, module = "spectrace._native")]
struct Scene {
    inner: spectrace::Scene,
}

#[pymethods]
impl Scene {
    /// What the loader noted without refusing the scene.
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.inner.notes().to_vec()
    }

    fn __repr__(&self) -> String {
        format!("{:?}", self.inner)
    }
}

/// Loads a scene file (TOML, or Mitsuba 3 XML) with Mitsuba `$name` values.
#[pyfunction]
#[pyo3(signature = (path, defines = Vec::new()))]
fn load(py: Python<'_>, path: PathBuf, defines: Vec<(String, String)>) -> PyResult<Scene> {
    let s = py
        .detach(|| spectrace::Scene::load_with(&path, &defines))
        .map_err(err)?;
    Ok(Scene { inner: s })
}

/// A scene from TOML text; `name` is what errors call it and where relative files resolve.
#[pyfunction]
fn from_toml(py: Python<'_>, text: &str, name: PathBuf) -> PyResult<Scene> {
    let s = py
        .detach(|| spectrace::Scene::from_toml_as(text, &name))
        .map_err(err)?;
    Ok(Scene { inner: s })
}

/// The scene format's TOML text of a dict of its tables.
#[pyfunction]
fn dict_to_toml(d: &Bound<'_, PyDict>) -> PyResult<String> {
    match convert::to_toml(d.as_any(), "", 0)? {
        toml::Value::Table(t) => toml::to_string(&t)
            .map_err(|e| PyValueError::new_err(format!("cannot write the scene as TOML: {e}"))),
        _ => unreachable!("a dict converts to a table"),
    }
}

/// Runs `job` on a Rust thread with the GIL released while this thread waits for it, waking
/// every 50 ms to run Python's signal handlers: when one raises (Ctrl-C: KeyboardInterrupt),
/// `cancel` is set, the job is waited for (it stops at its next check) and the exception is
/// returned. Signal handlers run only on Python's main thread; from another thread the job
/// runs to its end.
fn interruptible<T: Send>(
    py: Python<'_>,
    cancel: &AtomicBool,
    job: impl FnOnce() -> T + Send,
) -> PyResult<T> {
    let mut interrupted: Option<PyErr> = None;
    let result = py.detach(|| {
        std::thread::scope(|s| {
            let (done, finished) = std::sync::mpsc::channel::<()>();
            let worker = s.spawn(move || {
                let r = job();
                let _ = done.send(());
                r
            });
            while let Err(std::sync::mpsc::RecvTimeoutError::Timeout) =
                finished.recv_timeout(Duration::from_millis(50))
            {
                if let Err(e) = Python::attach(|py| py.check_signals()) {
                    interrupted = Some(e);
                    cancel.store(true, Ordering::Relaxed);
                    break;
                }
            }
            worker.join()
        })
    });
    if let Some(e) = interrupted {
        return Err(e);
    }
    result.map_err(|_| {
        SpectraceError::new_err("spectrace panicked (a bug: please report it with the scene)")
    })
}

#[pyfunction]
#[pyo3(signature = (scene, spp = None, seed = 0, integrator = None, threads = None, spectral_bins = None, time_limit = None, target_error = None))]
#[allow(clippy::too_many_arguments)]
fn render(
    py: Python<'_>,
    scene: &Scene,
    spp: Option<u32>,
    seed: u32,
    integrator: Option<&str>,
    threads: Option<usize>,
    spectral_bins: Option<u32>,
    time_limit: Option<f64>,
    target_error: Option<f64>,
) -> PyResult<Image> {
    use spectrace::api::Integrator as I;
    let integrator = match integrator {
        None => None,
        Some(name) => Some(I::from_name(name).ok_or_else(|| {
            PyValueError::new_err(format!(
                "integrator {name:?}: expected one of {}",
                I::NAMES.join(", ")
            ))
        })?),
    };
    let time_limit = match time_limit {
        None => None,
        Some(t) => Some(Duration::try_from_secs_f64(t).map_err(|_| {
            PyValueError::new_err(format!(
                "time_limit {t}: expected a positive number of seconds"
            ))
        })?),
    };
    let options = spectrace::Options {
        spp,
        seed,
        integrator,
        threads,
        spectral_bins,
        time_limit,
        target_error,
    };
    let cancel = AtomicBool::new(false);
    let image = interruptible(py, &cancel, || {
        spectrace::render_with(&scene.inner, &options, &cancel, &|_, _| {})
    })?;
    Ok(Image {
        inner: image.map_err(err)?,
    })
}

/// Meter readings: (meter, i, j, x, y, z (m), lx, lx standard error, W/m², W/m² standard error).
type Reading = (String, u32, u32, f64, f64, f64, f64, f64, f64, f64);

/// Reads the scene's illuminance meters (GIL released; Ctrl-C stops and raises).
#[pyfunction]
#[pyo3(signature = (scene, samples = 4096, seed = 0, threads = None))]
fn measure(
    py: Python<'_>,
    scene: &Scene,
    samples: u32,
    seed: u32,
    threads: Option<usize>,
) -> PyResult<Vec<Reading>> {
    let o = spectrace::MeasureOptions {
        samples,
        seed,
        threads,
    };
    let cancel = AtomicBool::new(false);
    let rs = interruptible(py, &cancel, || {
        spectrace::measure_with(&scene.inner, &o, &cancel)
    })?
    .map_err(err)?;
    use spectrace::units::{
        illuminance::lux, irradiance::watt_per_square_meter as wm2, length::meter,
    };
    Ok(rs
        .into_iter()
        .map(|r| {
            let [x, y, z] = r.position.map(|c| c.get::<meter>());
            (
                r.meter,
                r.cell[0],
                r.cell[1],
                x,
                y,
                z,
                r.illuminance.value.get::<lux>(),
                r.illuminance.standard_error.get::<lux>(),
                r.irradiance.value.get::<wm2>(),
                r.irradiance.standard_error.get::<wm2>(),
            )
        })
        .collect())
}

/// A named spectrum at wavelengths: (kind, wavelengths in nm, values, k), k only for
/// conductors.
#[pyfunction]
#[allow(clippy::type_complexity)]
fn spectrum(
    name: &str,
    wavelengths: Vec<Bound<'_, PyAny>>,
) -> PyResult<(String, Vec<f64>, Vec<f64>, Option<Vec<f64>>)> {
    let l = wavelengths
        .iter()
        .map(convert::wavelength)
        .collect::<PyResult<Vec<Length>>>()?;
    let nm = l.iter().map(|x| x.get::<nanometer>()).collect();
    use spectrace::SpectrumValues as V;
    Ok(match spectrace::spectrum(name, &l).map_err(err)? {
        V::Curve { kind, values } => (kind.to_string(), nm, values, None),
        V::Dielectric(n) => ("refractive index n".to_string(), nm, n, None),
        V::Conductor(nk) => (
            "complex refractive index n + ik".to_string(),
            nm,
            nk.iter().map(|p| p.0).collect(),
            Some(nk.iter().map(|p| p.1).collect()),
        ),
    })
}

/// A lens file's paraxial focal lengths per wavelength: rows of (wavelength nm, EFL mm,
/// BFL mm, spot RMS radius mm or None).
#[pyfunction]
#[pyo3(signature = (path, wavelengths, spot = false))]
#[allow(clippy::type_complexity)]
fn lens(
    path: PathBuf,
    wavelengths: Vec<Bound<'_, PyAny>>,
    spot: bool,
) -> PyResult<Vec<(f64, f64, f64, Option<f64>)>> {
    use spectrace::units::length::millimeter;
    let l = wavelengths
        .iter()
        .map(convert::wavelength)
        .collect::<PyResult<Vec<Length>>>()?;
    Ok(spectrace::api::lens(&path, &l, spot)
        .map_err(err)?
        .iter()
        .map(|r| {
            (
                r.wavelength.get::<nanometer>(),
                r.efl.get::<millimeter>(),
                r.bfl.get::<millimeter>(),
                r.spot_rms.map(|s| s.get::<millimeter>()),
            )
        })
        .collect())
}

/// A material's reflectance and transmittance per wavelength for light at `angle_deg` from
/// the normal: rows of (wavelength nm, R, T, R's standard error, T's, exact).
#[pyfunction]
#[pyo3(signature = (scene, name, angle_deg, wavelengths, samples = 65536))]
#[allow(clippy::type_complexity)]
fn material_albedo(
    scene: &Scene,
    name: &str,
    angle_deg: f64,
    wavelengths: Vec<Bound<'_, PyAny>>,
    samples: u32,
) -> PyResult<Vec<(f64, f64, f64, f64, f64, bool)>> {
    let l = wavelengths
        .iter()
        .map(convert::wavelength)
        .collect::<PyResult<Vec<Length>>>()?;
    let a = spectrace::units::Angle::new::<spectrace::units::angle::degree>(angle_deg);
    Ok(scene
        .inner
        .material_albedo(name, a, &l, samples)
        .map_err(err)?
        .iter()
        .map(|r| {
            (
                r.wavelength.get::<nanometer>(),
                r.reflectance,
                r.transmittance,
                r.reflectance_se,
                r.transmittance_se,
                r.exact,
            )
        })
        .collect())
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SpectraceError", m.py().get_type::<SpectraceError>())?;
    m.add_class::<Scene>()?;
    m.add_class::<Image>()?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(from_toml, m)?)?;
    m.add_function(wrap_pyfunction!(dict_to_toml, m)?)?;
    m.add_function(wrap_pyfunction!(render, m)?)?;
    m.add_function(wrap_pyfunction!(measure, m)?)?;
    m.add_function(wrap_pyfunction!(spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(lens, m)?)?;
    m.add_function(wrap_pyfunction!(material_albedo, m)?)?;
    Ok(())
}
