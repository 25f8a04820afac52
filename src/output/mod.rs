//! Writing a finished [`Image`]: float32 EXR with documented channels and header attributes,
//! spectral EXR (Fichet et al. 2021) when the film has bins, and an 8-bit sRGB PNG preview.
//! Every file is written atomically (temporary file, then rename) by `image_io`.
//!
//! EXR channels: `X`, `Y`, `Z` (CIE 1931, `Y` = luminance in cd/m²); `R`, `G`, `B` (linear
//! sRGB/Rec. 709 primaries, D65, same absolute scale); `L` (radiance integrated over the film's
//! wavelength range, W·m⁻²·sr⁻¹); spectral files add `S0.<λ>nm` channels (mean spectral radiance
//! of each bin, W·m⁻²·sr⁻¹·nm⁻¹). A polarised render adds its Stokes components ([`stokes_channels`]).
//!
//! PNG tone curve: linear RGB is divided by the saturating luminance of an ISO-100 camera,
//! L_max = 1.2 · 2^EV₁₀₀ cd/m² (the saturation-based sensitivity of ISO 12232), brought into
//! [0, 1] by the display transform ([`View`]: by default out-of-gamut and over-exposed colours
//! pale toward the grey of their luminance, keeping their hue) and encoded with the sRGB
//! transfer function. With automatic exposure,
//! EV₁₀₀ = log₂(L_avg · 100 / 12.5), the reflected-light meter calibration of ISO 2720 with
//! L_avg the geometric mean luminance of the pixels that are not black.

use std::path::Path;

mod stokes;

pub use stokes::stokes_channels;

pub use crate::colour::view::View;
use crate::film::Image;
use crate::image_io::{self, AttrValue, Channel, ImageError, WordChannel};
use crate::spectrum::WavelengthRange;

/// What the header records about a render.
pub struct RenderInfo<'a> {
    pub scene_file: &'a str,
    pub integrator: &'a str,
    /// Samples per pixel completed (light tracing: light paths per pixel).
    pub spp: u32,
    pub seed: u32,
    pub seconds: f64,
    pub partial: bool,
    pub nan_samples: u64,
    pub inf_samples: u64,
    pub range: WavelengthRange,
    /// Whether X, Y, Z, R, G, B were divided by K_m·∫ȳ (see [`to_mitsuba_scale`]).
    pub mitsuba_units: bool,
    /// Also write the second moments `m2.X`, `m2.Y`, `m2.Z` (Mitsuba's `moment` integrator).
    pub moment: bool,
    /// Why the render ended ([`crate::render::StopReason::name`]).
    pub stop: &'a str,
    /// The estimated relative error of Y (dimensionless), if known.
    pub rel_error: Option<f64>,
    /// The camera's sensor and the cosine of each pixel's chief ray with the optical axis:
    /// adds the sensor's channels (see [`sensor_channels`]).
    pub sensor: Option<(&'a crate::sensor::CameraSensor, &'a [f32])>,
    /// First-hit channels written after the image's (see [`crate::render::aov`]).
    pub aovs: &'a [crate::render::aov::AovChannel],
    /// The image is a window of the camera's full image (pbrt-v4's `cropwindow`): written as
    /// the EXR's data window within the full display window. None: the whole image.
    pub window: Option<image_io::DataWindow>,
}

/// The sensor's channels of `img`: `sensor.H` (photometric exposure, lx·s; not for pbrt-v4's
/// calibration), raw `sensor.R`, `sensor.G`, `sensor.B` and, with white balance,
/// `sensor.wb.R/G/B` (see `crate::sensor`), with the header text that states their units.
/// Camera curves read the spectral bins (the caller renders with them).
pub fn sensor_channels(
    img: &Image,
    sensor: &crate::sensor::CameraSensor,
    cos_theta: &[f32],
) -> (Vec<(String, Vec<f32>)>, String) {
    let n = img.width * img.height;
    let weights = img.bins.as_ref().map(|b| {
        let centres: Vec<f32> = (0..b.count).map(|i| b.centre(i)).collect();
        sensor.bin_weights(&centres, b.width())
    });
    let mut h = vec![0.0f32; n];
    let mut raw = [vec![0.0f32; n], vec![0.0f32; n], vec![0.0f32; n]];
    let mut wb = sensor
        .white_balance
        .as_ref()
        .map(|_| [vec![0.0f32; n], vec![0.0f32; n], vec![0.0f32; n]]);
    for i in 0..n {
        let e = sensor.exposure_per_radiance(cos_theta[i] as f64);
        h[i] = (img.xyz[i][1] as f64 * e) as f32;
        let r: [f64; 3] = match (&sensor.curves, &weights) {
            (Some(_), Some(w)) => {
                let mut r = [0.0; 3];
                for (b, wk) in w.iter().enumerate() {
                    for k in 0..3 {
                        r[k] += img.spectral[b][i] as f64 * wk[k];
                    }
                }
                r
            }
            // the CIE sensor's response: the film's XYZ times the sensor's norm
            _ => img.xyz[i].map(|v| v as f64 * sensor.norm),
        };
        let scale = sensor.raw_scale(cos_theta[i] as f64);
        let r = r.map(|v| v * scale);
        for k in 0..3 {
            raw[k][i] = r[k] as f32;
        }
        if let (Some(out), Some((_, _, m))) = (&mut wb, &sensor.white_balance) {
            let b = *m * glam::DVec3::from(r);
            for k in 0..3 {
                out[k][i] = b[k] as f32;
            }
        }
    }
    let pbrt = sensor.calibration == crate::sensor::Calibration::PbrtV4;
    let mut ch = if pbrt {
        Vec::new()
    } else {
        vec![("sensor.H".to_string(), h)]
    };
    for (k, c) in ["R", "G", "B"].iter().enumerate() {
        ch.push((format!("sensor.{c}"), std::mem::take(&mut raw[k])));
    }
    if let Some(mut out) = wb {
        for (k, c) in ["R", "G", "B"].iter().enumerate() {
            ch.push((format!("sensor.wb.{c}"), std::mem::take(&mut out[k])));
        }
    }
    let balance = match &sensor.white_balance {
        None => String::new(),
        Some((name, crate::sensor::Adaptation::VonKries, _)) => {
            format!("; sensor.wb.R,G,B: raw balanced to {name} by von Kries in the sensor's space")
        }
        Some((name, crate::sensor::Adaptation::Bradford, _)) => format!(
            "; sensor.wb.R,G,B: linear sRGB (D65) of the raw values through the sensor's XYZ fit, Bradford-adapted from {name}"
        ),
        Some((name, crate::sensor::Adaptation::PbrtV4, _)) => format!(
            "; sensor.wb.R,G,B: pbrt-v4's rgb film values, linear sRGB through its sensor matrix (white balance: {name})"
        ),
    };
    if pbrt {
        let text = format!(
            "sensor {} as pbrt-v4's PixelSensor: ISO {}, exposure time {} s; sensor.R,G,B: raw values, (t ISO/100) x the integral over wavelength of the channel's sensitivity times the spectral radiance, W/(m^2 sr) (for cie1931: XYZ in cd/m^2 / 683){balance}",
            sensor.name, sensor.iso, sensor.shutter_s
        );
        return (ch, text);
    }
    let text = format!(
        "sensor {}: ISO {}, {} s, f/{}; sensor.H: photometric exposure of the sensor plane in lx.s, H = (pi/4) L t cos^4(theta) / N^2; sensor.R,G,B: raw values, 0.18 x ISO/10 x the channel's exposure response (lx.s, green matched to luminance under D65), so 10/ISO lx.s reads 0.18{balance}",
        sensor.name, sensor.iso, sensor.shutter_s, sensor.f_number
    );
    (ch, text)
}

/// What a checkpoint or a render part stores beside its image: the film's exact sums as
/// unsigned-integer channels and header attributes to continue or merge from.
pub struct State<'a> {
    pub words: &'a [(String, Vec<u32>)],
    pub attributes: Vec<(&'a str, AttrValue)>,
}

/// Mitsuba 3.9.1's XYZ film multiplies by `MI_CIE_Y_NORMALIZATION` = 1/106.7502594, not by
/// 1/∫ȳ = 1/106.856895 as `../shared/PHYSICS.md` assumes (measured: a flat spectrum of 1 reads
/// Y = 1.00101 in Mitsuba 3.9.1); the two differ by 0.1 %.
pub const MITSUBA_CIE_Y_NORMALIZATION_INV: f64 = 106.750_259_4;

/// Divides X, Y, Z and R, G, B by K_m × 106.7502594 = 72 910.6, the factor between spectrace's
/// Y in cd/m² and Mitsuba 3.9.1's XYZ film for the same numeric emitter spectra
/// (`../shared/PHYSICS.md`, "Comparing with Mitsuba 3", gives 72 983.0 from ∫ȳ; Mitsuba's own
/// constant is 0.1 % smaller, see [`MITSUBA_CIE_Y_NORMALIZATION_INV`]). L is unchanged.
pub fn to_mitsuba_scale(img: &mut Image) {
    let k = (1.0 / (crate::colour::cie::K_M * MITSUBA_CIE_Y_NORMALIZATION_INV)) as f32;
    for p in img.xyz.iter_mut().chain(img.rgb.iter_mut()) {
        *p = p.map(|v| v * k);
    }
    for p in img.xyz_m2.iter_mut() {
        *p = p.map(|v| v * k * k);
    }
    for p in img.stokes.iter_mut() {
        *p = p.map(|c| c.map(|v| v * k));
    }
}

/// Writes the EXR (spectral when the image has bins).
pub fn write_exr(path: &Path, img: &Image, info: &RenderInfo<'_>) -> Result<(), ImageError> {
    write_exr_state(path, img, info, None)
}

/// The header attributes of a render's EXR (`spectrace:units`, `samplesPerPixel`, `seed`,
/// `wavelengthRange`, `integrator`, `scene`, `renderTimeSeconds`, `partial`, the dropped
/// samples, `stopReason`, `estimatedRelativeErrorY`); the sensor's are added with its channels.
pub fn header(info: &RenderInfo<'_>) -> Vec<(&'static str, AttrValue)> {
    let xyz_units = if info.mitsuba_units {
        "X,Y,Z: CIE 1931 2deg on Mitsuba 3.9.1's scale (cd/m^2 divided by 683.002 x 106.7502594)"
    } else {
        "X,Y,Z: CIE 1931 2deg, Y = luminance in cd/m^2"
    };
    let units = format!(
        "{xyz_units}; R,G,B: linear sRGB (Rec.709 primaries, D65) on the same scale; L: radiance over {}-{} nm in W.m^-2.sr^-1{}",
        info.range.min_nm,
        info.range.max_nm,
        if info.moment {
            "; m2.X,m2.Y,m2.Z: second moments, the mean of the squared sample values of X,Y,Z (their units squared)"
        } else {
            ""
        }
    );
    let mut attrs = vec![
        ("spectrace:units", AttrValue::Text(units)),
        ("spectrace:samplesPerPixel", AttrValue::Int(info.spp as i32)),
        ("spectrace:seed", AttrValue::Int(info.seed as i32)),
        (
            "spectrace:wavelengthRange",
            AttrValue::Text(format!(
                "{} nm to {} nm",
                info.range.min_nm, info.range.max_nm
            )),
        ),
        (
            "spectrace:integrator",
            AttrValue::Text(info.integrator.to_string()),
        ),
        (
            "spectrace:scene",
            AttrValue::Text(info.scene_file.to_string()),
        ),
        (
            "spectrace:renderTimeSeconds",
            AttrValue::Double(info.seconds),
        ),
        ("spectrace:partial", AttrValue::Int(info.partial as i32)),
        (
            "spectrace:droppedNaNSamples",
            AttrValue::Double(info.nan_samples as f64),
        ),
        (
            "spectrace:droppedInfSamples",
            AttrValue::Double(info.inf_samples as f64),
        ),
        (
            "spectrace:stopReason",
            AttrValue::Text(info.stop.to_string()),
        ),
    ];
    if let Some(e) = info.rel_error {
        attrs.push(("spectrace:estimatedRelativeErrorY", AttrValue::Double(e)));
    }
    attrs
}

/// [`write_exr`], with a film's state beside the image when `state` is given.
pub fn write_exr_state(
    path: &Path,
    img: &Image,
    info: &RenderInfo<'_>,
    state: Option<&State<'_>>,
) -> Result<(), ImageError> {
    let plane =
        |f: &dyn Fn(usize) -> f32| -> Vec<f32> { (0..img.width * img.height).map(f).collect() };
    let x = plane(&|i| img.xyz[i][0]);
    let y = plane(&|i| img.xyz[i][1]);
    let z = plane(&|i| img.xyz[i][2]);
    let r = plane(&|i| img.rgb[i][0]);
    let g = plane(&|i| img.rgb[i][1]);
    let b = plane(&|i| img.rgb[i][2]);
    let (mx, my, mz) = (
        plane(&|i| img.xyz_m2[i][0]),
        plane(&|i| img.xyz_m2[i][1]),
        plane(&|i| img.xyz_m2[i][2]),
    );
    let mut channels = vec![
        Channel {
            name: "X",
            data: &x,
        },
        Channel {
            name: "Y",
            data: &y,
        },
        Channel {
            name: "Z",
            data: &z,
        },
        Channel {
            name: "R",
            data: &r,
        },
        Channel {
            name: "G",
            data: &g,
        },
        Channel {
            name: "B",
            data: &b,
        },
        Channel {
            name: "L",
            data: &img.band,
        },
    ];
    if info.moment {
        for (name, data) in [("m2.X", &mx), ("m2.Y", &my), ("m2.Z", &mz)] {
            channels.push(Channel { name, data });
        }
    }
    let sensor = info.sensor.map(|(s, cos)| sensor_channels(img, s, cos));
    if let Some((sc, _)) = &sensor {
        for (name, data) in sc {
            channels.push(Channel { name, data });
        }
    }
    let (stokes, stokes_text) = stokes_channels(img);
    for (name, data) in &stokes {
        channels.push(Channel { name, data });
    }
    for (name, data) in info.aovs {
        channels.push(Channel { name, data });
    }
    let mut attrs = header(info);
    if !stokes.is_empty() {
        attrs.push(("spectrace:stokes", AttrValue::Text(stokes_text)));
    }
    if let Some((_, text)) = &sensor {
        attrs.push(("spectrace:sensor", AttrValue::Text(text.clone())));
    }
    let words: Vec<WordChannel> = state
        .map(|s| {
            s.words
                .iter()
                .map(|(name, data)| WordChannel { name, data })
                .collect()
        })
        .unwrap_or_default();
    if let Some(s) = state {
        attrs.extend(s.attributes.iter().cloned());
    }
    let extras = image_io::Extras {
        words: &words,
        window: info.window,
    };
    match &img.bins {
        Some(bins) => {
            let lambdas: Vec<f32> = (0..bins.count).map(|i| bins.centre(i)).collect();
            let planes: Vec<&[f32]> = img.spectral.iter().map(Vec::as_slice).collect();
            let spectral = image_io::Spectral {
                wavelengths_nm: &lambdas,
                bins: &planes,
            };
            image_io::write_spectral_exr_words(
                path, img.width, img.height, &spectral, &channels, &extras, &attrs,
            )
        }
        None => image_io::write_exr_words(path, img.width, img.height, &channels, &extras, &attrs),
    }
}

/// The automatic exposure EV₁₀₀ of an image (see the module doc). The geometric mean skips
/// black pixels (background, unlit), so that they do not overexpose the rest.
pub fn auto_ev100(img: &Image) -> f32 {
    let lit: Vec<f64> = img
        .xyz
        .iter()
        .map(|p| p[1] as f64)
        .filter(|y| *y > 0.0)
        .collect();
    if lit.is_empty() {
        return 0.0;
    }
    let log_avg = (lit.iter().map(|y| y.ln()).sum::<f64>() / lit.len() as f64).exp();
    (log_avg * 100.0 / 12.5).max(1e-12).log2() as f32
}

/// Writes the PNG preview with exposure `ev100` (None: automatic) through the display
/// transform `view`; returns the EV₁₀₀ used.
pub fn write_png(
    path: &Path,
    img: &Image,
    ev100: Option<f32>,
    view: View,
) -> Result<f32, ImageError> {
    let ev = ev100.unwrap_or_else(|| auto_ev100(img));
    let k = 1.0 / (1.2 * 2f32.powf(ev));
    let rgb: Vec<[f32; 3]> = img
        .rgb
        .iter()
        .map(|p| view.apply(p.map(|v| v * k)))
        .collect();
    image_io::write_png_linear(path, img.width, img.height, &rgb)?;
    Ok(ev)
}
