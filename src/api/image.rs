//! A rendered image with typed accessors, and the mean of a region with its standard error.

use crate::units::{Length, Luminance, Radiance, SpectralRadiance};
use crate::units::{length, luminance, radiance, spectral_radiance};

/// A rectangle of pixels: columns `x0 .. x0 + width`, rows `y0 .. y0 + height` (row 0 on top).
///
/// ```
/// let r = spectrace::Region { x0: 2, y0: 2, width: 4, height: 4 };
/// assert_eq!(r.width * r.height, 16);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Region {
    /// First column.
    pub x0: usize,
    /// First row.
    pub y0: usize,
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
}

impl Region {
    /// The whole image.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// let r = spectrace::api::Region::all(&image);
    /// ```
    pub fn all(image: &Image) -> Region {
        Region {
            x0: 0,
            y0: 0,
            width: image.width(),
            height: image.height(),
        }
    }
}

/// A value and its standard error, in the same unit.
///
/// ```
/// use spectrace::units::{Luminance, luminance::candela_per_square_meter as cd};
/// let e = spectrace::Estimate { value: Luminance::new::<cd>(100.0), standard_error: Luminance::new::<cd>(0.1) };
/// assert!(e.standard_error < e.value);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Estimate<Q> {
    /// The estimate.
    pub value: Q,
    /// Its standard error (from the per-pixel sample variance; NaN when it cannot be
    /// estimated: light tracing and `bdpt` splat into pixels without per-pixel moments).
    pub standard_error: Q,
}

/// A rendered image with typed accessors.
///
/// ```
/// # let scene = spectrace::Scene::from_toml("[camera]\neye = [0, 0, -1]\ntarget = [0, 0, 0]\nfov = \"40 deg\"\n[film]\nwidth = 4\nheight = 3\n[[lights]]\ntype = \"environment\"\nluminance = \"1 cd/m^2\"")?;
/// let image = spectrace::render(&scene, &spectrace::Options { spp: Some(4), ..Default::default() })?;
/// assert_eq!((image.width(), image.height()), (4, 3));
/// # Ok::<(), spectrace::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Image {
    pub(super) inner: crate::film::Image,
    /// Samples per pixel taken.
    pub(super) spp: u32,
    /// Whether every pixel's value is a mean of its own camera samples (so its second moment
    /// is known).
    pub(super) camera_samples: bool,
    /// Why the render ended ("complete", "time limit", "target error", "cancelled").
    stop: &'static str,
    /// The EXR header's attributes, as text.
    metadata: Vec<(String, String)>,
}

impl Image {
    /// The film's image of a render with `o` that ended with `stats`.
    pub(super) fn new(
        inner: crate::film::Image,
        o: &crate::render::RenderOptions,
        stats: &crate::render::RenderStats,
        scene: &crate::scene::Scene,
        source: &str,
    ) -> Image {
        use crate::loader::desc::IntegratorKind as K;
        let splats = matches!(o.integrator, K::Light | K::Bdpt);
        let info = crate::output::RenderInfo {
            scene_file: source,
            integrator: o.integrator.name(),
            spp: stats.spp_done,
            seed: o.seed,
            seconds: stats.elapsed.as_secs_f64(),
            partial: stats.partial,
            nan_samples: stats.nan_samples,
            inf_samples: stats.inf_samples,
            range: scene.wavelengths,
            mitsuba_units: false,
            moment: scene.integrator.moment && !splats,
            stop: stats.stop.name(),
            rel_error: stats.rel_error,
            sensor: None,
            aovs: &[],
            window: None,
        };
        let metadata = crate::output::header(&info)
            .into_iter()
            .map(|(k, v)| {
                let v = match v {
                    crate::image_io::AttrValue::Text(t) => t,
                    crate::image_io::AttrValue::Float(x) => x.to_string(),
                    crate::image_io::AttrValue::Double(x) => x.to_string(),
                    crate::image_io::AttrValue::Int(x) => x.to_string(),
                };
                (k.to_string(), v)
            })
            .collect();
        Image {
            inner,
            spp: stats.spp_done,
            camera_samples: !splats,
            stop: stats.stop.name(),
            metadata,
        }
    }

    /// Whether every sample asked for was taken: false when the render was cancelled or a time
    /// limit or target error ended it first ([`stop_reason`](Self::stop_reason) says which).
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// assert!(image.complete());
    /// ```
    pub fn complete(&self) -> bool {
        self.stop == crate::render::StopReason::Complete.name()
    }

    /// Why the render ended: `"complete"`, `"time limit"`, `"target error"` or `"cancelled"`
    /// (the EXR header's `spectrace:stopReason`).
    ///
    /// ```
    /// let s = spectrace::Scene::from_toml("[camera]\neye = [0, 0, -1]\ntarget = [0, 0, 0]\nfov = \"40 deg\"\n[film]\nwidth = 4\nheight = 4\n[[lights]]\ntype = \"environment\"\nluminance = \"1 cd/m^2\"")?;
    /// let o = spectrace::Options { target_error: Some(0.5), ..Default::default() };
    /// let image = spectrace::render(&s, &o)?;
    /// assert_eq!(image.stop_reason(), "target error");
    /// assert!(!image.complete());
    /// # Ok::<(), spectrace::Error>(())
    /// ```
    pub fn stop_reason(&self) -> &'static str {
        self.stop
    }

    /// Samples per pixel taken everywhere.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// let n = image.samples_per_pixel();
    /// ```
    pub fn samples_per_pixel(&self) -> u32 {
        self.spp
    }

    /// The attributes `spectrace render` writes to the EXR header (`spectrace:units`,
    /// `spectrace:samplesPerPixel`, `spectrace:wavelengthRange`, …), as text.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// for (name, value) in image.metadata() { println!("{name}: {value}"); }
    /// ```
    pub fn metadata(&self) -> &[(String, String)] {
        &self.metadata
    }

    /// Every pixel's CIE 1931 X, Y, Z in cd/m² (Y is luminance), rows from the top, as
    /// plain numbers for bulk use (NumPy, plots).
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// let y_of_first_pixel = image.xyz_cd_m2()[0][1];
    /// ```
    pub fn xyz_cd_m2(&self) -> &[[f32; 3]] {
        &self.inner.xyz
    }

    /// Every pixel's radiance over the wavelength range, W·m⁻²·sr⁻¹, rows from the top.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// let l = image.radiance_w_m2_sr()[0];
    /// ```
    pub fn radiance_w_m2_sr(&self) -> &[f32] {
        &self.inner.band
    }

    /// The spectral bins' centres in nm and, per bin, every pixel's mean spectral radiance in
    /// W·m⁻²·sr⁻¹·nm⁻¹ (rows from the top); None without bins.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// if let Some((nm, planes)) = image.spectral_w_m2_sr_nm() { println!("{} bins", nm.len()); }
    /// ```
    pub fn spectral_w_m2_sr_nm(&self) -> Option<(Vec<f32>, &[Vec<f32>])> {
        let bins = self.inner.bins.as_ref()?;
        Some((
            (0..bins.count).map(|i| bins.centre(i)).collect(),
            &self.inner.spectral,
        ))
    }

    /// The renderer's own image (RGB, second moments).
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// let rgb = &image.inner().rgb;
    /// ```
    pub fn inner(&self) -> &crate::film::Image {
        &self.inner
    }
    /// Width, pixels.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// let n = image.width() * image.height();
    /// ```
    pub fn width(&self) -> usize {
        self.inner.width
    }

    /// Height, pixels.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// let h = image.height();
    /// ```
    pub fn height(&self) -> usize {
        self.inner.height
    }

    fn at(&self, x: usize, y: usize) -> usize {
        assert!(
            x < self.width() && y < self.height(),
            "pixel ({x}, {y}) outside the image"
        );
        y * self.width() + x
    }

    /// Luminance of pixel (x, y) (CIE 1931 Y). Panics outside the image.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// use spectrace::units::luminance::candela_per_square_meter;
    /// let cd = image.luminance(0, 0).get::<candela_per_square_meter>();
    /// ```
    pub fn luminance(&self, x: usize, y: usize) -> Luminance {
        Luminance::new::<luminance::candela_per_square_meter>(
            self.inner.xyz[self.at(x, y)][1] as f64,
        )
    }

    /// CIE 1931 X, Y, Z of pixel (x, y), on the luminance scale (Y in cd/m²).
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// let [x, y, z] = image.xyz(0, 0);
    /// ```
    pub fn xyz(&self, x: usize, y: usize) -> [Luminance; 3] {
        self.inner.xyz[self.at(x, y)]
            .map(|v| Luminance::new::<luminance::candela_per_square_meter>(v as f64))
    }

    /// The Stokes vector of pixel (x, y) of a polarised render as luminances: S0 (the pixel's
    /// luminance, CIE Y), S1, S2, S3 (their Y, on the same scale; the basis is the image's
    /// horizontal: S1 > 0 horizontal, S2 > 0 along the diagonal up and to the right, S3 > 0
    /// right-circular), and the degree of linear polarisation √(S1² + S2²)/S0
    /// (dimensionless, 0 where S0 is 0). None for an unpolarised render. Panics outside the
    /// image.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// if let Some((s, dolp)) = image.stokes(0, 0) { println!("S1 = {:?}, DoLP {dolp}", s[1]); }
    /// ```
    pub fn stokes(&self, x: usize, y: usize) -> Option<([Luminance; 4], f64)> {
        let i = self.at(x, y);
        let st = self.inner.stokes.get(i)?;
        let y0 = self.inner.xyz[i][1] as f64;
        let (s1, s2) = (st[0][1] as f64, st[1][1] as f64);
        let cd = |v: f64| Luminance::new::<luminance::candela_per_square_meter>(v);
        let dolp = if y0 > 0.0 { s1.hypot(s2) / y0 } else { 0.0 };
        Some(([cd(y0), cd(s1), cd(s2), cd(st[2][1] as f64)], dolp))
    }

    /// Radiance of pixel (x, y) over the scene's wavelength range.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// use spectrace::units::radiance::watt_per_square_meter_steradian;
    /// let l = image.radiance(0, 0).get::<watt_per_square_meter_steradian>();
    /// ```
    pub fn radiance(&self, x: usize, y: usize) -> Radiance {
        Radiance::new::<radiance::watt_per_square_meter_steradian>(
            self.inner.band[self.at(x, y)] as f64,
        )
    }

    /// Spectral radiance of pixel (x, y) in the spectral bin holding `wavelength` (its mean
    /// over the bin); None without bins ([`Options::spectral_bins`](super::Options::spectral_bins)) or outside the range.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// use spectrace::units::{Length, length::nanometer};
    /// let l = image.spectral_radiance(0, 0, Length::new::<nanometer>(550.0));
    /// ```
    pub fn spectral_radiance(
        &self,
        x: usize,
        y: usize,
        wavelength: Length,
    ) -> Option<SpectralRadiance> {
        let i = self.at(x, y);
        let bins = self.inner.bins.as_ref()?;
        let b = bins.index(wavelength.get::<length::nanometer>() as f32)?;
        Some(SpectralRadiance::new::<
            spectral_radiance::watt_per_square_meter_steradian_nanometer,
        >(self.inner.spectral[b][i] as f64))
    }

    /// The mean luminance over `region` and its standard error: each pixel's mean of `spp`
    /// samples has variance (m₂ − Ȳ²)/(spp − 1), m₂ its mean squared sample, and pixels are
    /// independent (each has its own scrambled sampler), so the region's mean has the variance
    /// Σ varᵢ / N². Panics if the region leaves the image or is empty.
    ///
    /// ```no_run
    /// # let image: spectrace::api::Image = unimplemented!();
    /// let est = image.mean_luminance(spectrace::api::Region { x0: 0, y0: 0, width: 4, height: 4 });
    /// ```
    pub fn mean_luminance(&self, r: Region) -> Estimate<Luminance> {
        let inside = |start: usize, len: usize, size: usize| {
            len > 0 && start.checked_add(len).is_some_and(|end| end <= size)
        };
        assert!(
            inside(r.x0, r.width, self.width()) && inside(r.y0, r.height, self.height()),
            "region {r:?} is empty or leaves the {} × {} image",
            self.width(),
            self.height()
        );
        let (mut sum, mut var) = (0.0f64, 0.0f64);
        for y in r.y0..r.y0 + r.height {
            for x in r.x0..r.x0 + r.width {
                let i = self.at(x, y);
                let m = self.inner.xyz[i][1] as f64;
                sum += m;
                let m2 = self.inner.xyz_m2[i][1] as f64;
                var += (m2 - m * m).max(0.0) / (self.spp as f64 - 1.0).max(1.0);
            }
        }
        let n = (r.width * r.height) as f64;
        let se = if self.camera_samples && self.spp > 1 {
            var.sqrt() / n
        } else {
            f64::NAN
        };
        let cd = |v: f64| Luminance::new::<luminance::candela_per_square_meter>(v);
        Estimate {
            value: cd(sum / n),
            standard_error: cd(se),
        }
    }
}
