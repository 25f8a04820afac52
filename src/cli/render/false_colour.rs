//! False-colour images of a render (luminance, or illuminance from an extra pass) and the
//! per-pixel cos θ a camera sensor's exposure needs.

use std::path::Path;

use super::*;

/// The false-colour and unit options checked against each other and the scene.
pub(super) fn check_false_colour_args(
    args: &RenderArgs,
    scene: &crate::scene::Scene,
) -> Result<(), CliError> {
    if args.mitsuba_units && (args.false_colour.is_some() || scene.camera_sensor.is_some()) {
        return Err(CliError::Usage(
            "--mitsuba-units rescales X, Y, Z away from cd/m², which false colour and a camera sensor read; leave it out".into(),
        ));
    }
    if args.false_colour_png.is_some() && args.false_colour.is_none() {
        return Err(CliError::Usage(
            "--false-colour-png needs --false-colour luminance or illuminance".into(),
        ));
    }
    if let Some(m) = args.false_colour_max
        && !(m > 0.0 && m.is_finite())
    {
        return Err(CliError::Usage(format!(
            "--false-colour-max must be a positive number, found {m}"
        )));
    }
    if args
        .false_colour_decades
        .is_some_and(|d| !(1..=12).contains(&d))
    {
        return Err(CliError::Usage(
            "--false-colour-decades must be from 1 to 12".into(),
        ));
    }
    Ok(())
}

/// Per pixel, cos θ between its central ray and the image centre's (for a camera sensor's
/// cos⁴θ fall-off), row by row.
pub(super) fn pixel_cos_theta(scene: &crate::scene::Scene) -> Vec<f32> {
    let (w, h) = (scene.film.width, scene.film.height);
    let centre = scene
        .camera
        .generate_ray(
            glam::Vec2::new(w as f32 / 2.0, h as f32 / 2.0),
            glam::Vec2::splat(0.5),
        )
        .d;
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            let d = scene
                .camera
                .generate_ray(
                    glam::Vec2::new(x as f32 + 0.5, y as f32 + 0.5),
                    glam::Vec2::splat(0.5),
                )
                .d;
            d.dot(centre).clamp(0.0, 1.0)
        })
        .collect()
}

/// Writes the false-colour PNG of `kind` (see [`RenderArgs::false_colour`]).
pub(super) fn false_colour(
    args: &RenderArgs,
    scene: &crate::scene::Scene,
    opts: &RenderOptions,
    spp: u32,
    image: &crate::film::Image,
    kind: FalseColourKind,
    path: &Path,
) -> Result<(), CliError> {
    let (values, unit): (Vec<f32>, &str) = match kind {
        FalseColourKind::Luminance => (image.xyz.iter().map(|p| p[1]).collect(), "cd/m²"),
        FalseColourKind::Illuminance => {
            let m = crate::render::measure::MeasureOptions {
                samples: spp,
                threads: opts.threads,
                seed: opts.seed,
                max_depth: opts.max_depth,
                spectral_bins: 0,
            };
            let bar = Progress::new(scene.film.height as u64, args.quiet);
            let v = crate::render::measure::illuminance_image(scene, opts.spp, &m, &CANCEL, &|d| {
                bar.set(d)
            })
            .map_err(|e| CliError::Usage(e.to_string()))?;
            bar.finish();
            if CANCEL.load(Ordering::Relaxed) {
                return Ok(());
            }
            (v, "lx")
        }
    };
    let log = args.false_colour_scale == FalseColourScale::Log;
    let decades = args.false_colour_decades.unwrap_or(3);
    let scale = match args.false_colour_max {
        Some(hi) if log => crate::falsecolour::Scale::Log {
            lo: hi / 10f64.powi(decades as i32),
            hi,
        },
        Some(hi) => crate::falsecolour::Scale::Linear { lo: 0.0, hi },
        None => crate::falsecolour::Scale::auto(&values, log, decades)
            .unwrap_or(crate::falsecolour::Scale::Linear { lo: 0.0, hi: 1.0 }),
    };
    let (w, h) = (scene.film.width as usize, scene.film.height as usize);
    let (img, fw, fh) = crate::falsecolour::image(&values, w, h, scale, unit);
    crate::image_io::write_png_srgb8(path, fw, fh, &img)?;
    if !args.quiet {
        eprintln!("wrote {} ({unit}, {scale:?})", shown(path));
    }
    Ok(())
}
