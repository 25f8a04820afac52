//! A rendered image as Python sees it: sizes, the stop reason and metadata, pixel planes as
//! little-endian f32 bytes (wrapped as NumPy arrays by `spectrace/__init__.py`), and a region's
//! mean luminance with its standard error.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyBytes;

/// A rendered image.
#[pyclass(frozen, module = "spectrace._native")]
pub(crate) struct Image {
    pub(crate) inner: spectrace::Image,
}

fn f32_bytes<'py>(py: Python<'py>, v: impl Iterator<Item = f32>) -> Bound<'py, PyBytes> {
    let b: Vec<u8> = v.flat_map(f32::to_le_bytes).collect();
    PyBytes::new(py, &b)
}

#[pymethods]
impl Image {
    /// Pixels across.
    #[getter]
    fn width(&self) -> usize {
        self.inner.width()
    }

    /// Pixels down.
    #[getter]
    fn height(&self) -> usize {
        self.inner.height()
    }

    /// Samples per pixel taken everywhere.
    #[getter]
    fn spp(&self) -> u32 {
        self.inner.samples_per_pixel()
    }

    /// Whether every sample asked for was taken (see stop_reason).
    #[getter]
    fn complete(&self) -> bool {
        self.inner.complete()
    }

    /// Why the render ended: "complete", "time limit", "target error" or "cancelled".
    #[getter]
    fn stop_reason(&self) -> &'static str {
        self.inner.stop_reason()
    }

    /// The EXR header's attributes, as text.
    #[getter]
    fn metadata(&self) -> Vec<(String, String)> {
        self.inner.metadata().to_vec()
    }

    /// X, Y, Z per pixel (cd/m²), rows from the top: little-endian f32 bytes.
    fn xyz_bytes<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        f32_bytes(py, self.inner.xyz_cd_m2().iter().flatten().copied())
    }

    /// Radiance over the wavelength range per pixel (W·m⁻²·sr⁻¹): f32 bytes.
    fn radiance_bytes<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        f32_bytes(py, self.inner.radiance_w_m2_sr().iter().copied())
    }

    /// The bins' centres (nm) and their planes (W·m⁻²·sr⁻¹·nm⁻¹, bin-major f32 bytes), or None.
    fn spectral_bytes<'py>(&self, py: Python<'py>) -> Option<(Vec<f32>, Bound<'py, PyBytes>)> {
        let (nm, planes) = self.inner.spectral_w_m2_sr_nm()?;
        Some((nm, f32_bytes(py, planes.iter().flatten().copied())))
    }

    /// A polarised render's X, Y, Z of S1, S2, S3 per pixel (cd/m², 9 per pixel, rows from the
    /// top): f32 bytes; None for an unpolarised render.
    fn stokes_bytes<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyBytes>> {
        let st = &self.inner.inner().stokes;
        if st.is_empty() {
            return None;
        }
        Some(f32_bytes(py, st.iter().flatten().flatten().copied()))
    }

    /// The mean luminance of the region and its standard error, cd/m².
    fn mean_luminance(
        &self,
        x0: usize,
        y0: usize,
        width: usize,
        height: usize,
    ) -> PyResult<(f64, f64)> {
        let (w, h) = (self.inner.width(), self.inner.height());
        if width == 0
            || height == 0
            || x0.saturating_add(width) > w
            || y0.saturating_add(height) > h
        {
            return Err(PyValueError::new_err(format!(
                "region x0={x0} y0={y0} width={width} height={height} is empty or leaves the {w} × {h} image"
            )));
        }
        let e = self.inner.mean_luminance(spectrace::Region {
            x0,
            y0,
            width,
            height,
        });
        use spectrace::units::luminance::candela_per_square_meter as cd;
        Ok((e.value.get::<cd>(), e.standard_error.get::<cd>()))
    }
}
