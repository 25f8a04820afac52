//! pbrt-v4's pixel sensor (`PixelSensor::Create`, `src/pbrt/film.cpp`): a film's `sensor`,
//! `iso` and `whitebalance`, with the camera's shutter interval as the exposure time
//! (`scene.cpp`: `shutterclose` − `shutteropen`), mapped onto spectrace's camera sensor with
//! pbrt-v4's calibration ([`crate::sensor::Calibration::PbrtV4`]). spectrace's X, Y, Z and
//! R, G, B stay the physical radiance; pbrt-v4's image is in the EXR's `sensor.wb.R/G/B`.

use super::params::{Params, R};
use crate::loader::Loc;
use crate::loader::desc::CameraSensorDesc;
use crate::sensor::{Adaptation, Calibration, pbrt};

/// The camera's exposure time, s: `shutterclose` (1) − `shutteropen` (0), which must be
/// positive (pbrt-v4 stops on a shutter that does not open).
pub(super) fn exposure_time(cam: &Params, loc: Loc) -> R<f64> {
    let t = cam.float("shutterclose", 1.0)? - cam.float("shutteropen", 0.0)?;
    if !(t > 0.0 && t.is_finite()) {
        return Err(cam.err(
            loc,
            format!("the shutter interval shutterclose − shutteropen is {t} s: the shutter does not open"),
        ));
    }
    Ok(t)
}

/// The film's sensor: None for pbrt-v4's pass-through (`cie1931`, `iso` 100, no
/// `whitebalance`, an exposure of 1 s), whose image is spectrace's own divided by K_m.
/// `whitebalance` is in K (0: none for `cie1931`, 6500 for a camera, as pbrt-v4).
pub(super) fn sensor(p: &Params, exposure_s: f64) -> R<Option<CameraSensorDesc>> {
    let name = p.string("sensor")?.unwrap_or_else(|| "cie1931".into());
    let iso = p.float("iso", 100.0)?;
    let mut wb = p.float("whitebalance", 0.0)?;
    if !(iso > 0.0 && iso.is_finite()) {
        return Err(p.err(p.loc_of("iso"), "\"iso\" must be positive"));
    }
    if !(wb >= 0.0 && wb.is_finite()) {
        return Err(p.err(
            p.loc_of("whitebalance"),
            "\"whitebalance\" is a colour temperature in K (0: none)",
        ));
    }
    let curves = if name == "cie1931" {
        None
    } else {
        let Some(c) = pbrt::camera_curves(&name) else {
            return Err(p.err(
                p.loc_of("sensor"),
                format!(
                    "unknown sensor \"{name}\": pbrt-v4's are cie1931, {}",
                    pbrt::camera_names().join(", ")
                ),
            ));
        };
        if wb == 0.0 {
            wb = 6500.0;
        }
        Some(c)
    };
    if curves.is_none() && wb == 0.0 && iso == 100.0 && exposure_s == 1.0 {
        return Ok(None);
    }
    let white_balance = if wb > 0.0 {
        let Some(d) = pbrt::daylight(wb) else {
            return Err(p.err(p.loc_of("whitebalance"), "no daylight at this temperature"));
        };
        (format!("pbrt-v4's daylight at {wb} K"), d)
    } else {
        // no white balance: pbrt-v4's matrix is sRGB's, which balancing from D65 to D65 keeps
        let d65 = crate::sensor::d65().map_err(|m| p.err(p.loc_of("sensor"), m))?;
        ("none".to_string(), d65)
    };
    Ok(Some(CameraSensorDesc {
        name: format!("pbrt-v4 {name}"),
        curves,
        iso,
        shutter: crate::units::Time::new::<crate::units::time::second>(exposure_s),
        f_number: 1.0,
        white_balance: Some((white_balance.0, white_balance.1, Adaptation::PbrtV4)),
        calibration: Calibration::PbrtV4,
    }))
}
