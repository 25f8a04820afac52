//! `spectrace probe IMAGE.exr X Y`: the spectral radiance of a pixel, or the mean over a square
//! region, read from a spectral EXR (spectrace's `--spectral-bins` or any file in Fichet et
//! al.'s layout), printed as CSV and optionally plotted.

use std::path::PathBuf;

use clap::Args;

use super::CliError;

#[derive(Args, Debug)]
pub struct ProbeArgs {
    /// A spectral EXR (`S0.<λ>nm` channels).
    pub image: PathBuf,
    /// Column of the pixel (0 = left).
    pub x: usize,
    /// Row of the pixel (0 = top).
    pub y: usize,
    /// The mean over the SIZE × SIZE pixels from (X, Y) right and down.
    #[arg(long, default_value_t = 1)]
    pub size: usize,
    /// Also plot the spectrum to an SVG file.
    #[arg(long, value_name = "SVG")]
    pub plot: Option<PathBuf>,
}

pub fn run(args: ProbeArgs) -> Result<(), CliError> {
    let img = crate::image_io::read_exr(&args.image)?;
    let chans = crate::image_io::spectral_channels(&img);
    if chans.is_empty() {
        return Err(CliError::Usage(format!(
            "{}: no spectral channels (S0.<λ>nm); render with --spectral-bins N",
            args.image.display()
        )));
    }
    let fits = |at: usize, len: usize| at.checked_add(args.size).is_some_and(|e| e <= len);
    if args.size == 0 || !fits(args.x, img.width) || !fits(args.y, img.height) {
        return Err(CliError::Usage(format!(
            "the region {}×{} at ({}, {}) does not fit in the {}×{} image",
            args.size, args.size, args.x, args.y, img.width, img.height
        )));
    }
    let mean = |data: &[f32]| {
        let mut s = 0.0f64;
        for y in args.y..args.y + args.size {
            for x in args.x..args.x + args.size {
                s += data[y * img.width + x] as f64;
            }
        }
        s / (args.size * args.size) as f64
    };
    let units = img
        .attributes
        .iter()
        .find(|(n, _)| n == "emissiveUnits")
        .and_then(|(_, v)| match v {
            crate::image_io::AttrValue::Text(t) => Some(t.clone()),
            _ => None,
        })
        .unwrap_or_default();
    let points: Vec<(f64, f64)> = chans
        .iter()
        .map(|&(wl, i)| (wl as f64, mean(&img.channels[i].1)))
        .collect();
    let mut csv = String::from("wavelength_nm,spectral_radiance_W_m2_sr_nm\n");
    for (wl, v) in &points {
        csv += &format!("{wl},{v:e}\n");
    }
    // a closed pipe (`| head`) ends the output quietly
    let _ = std::io::Write::write_all(&mut std::io::stdout().lock(), csv.as_bytes());
    // `--mitsuba-units` renders say so in their units text (and parts in mitsubaUnits)
    let mitsuba = img.attributes.iter().any(|(n, v)| match v {
        crate::image_io::AttrValue::Text(t) => n == "spectrace:units" && t.contains("Mitsuba"),
        crate::image_io::AttrValue::Int(1) => n == "spectrace:mitsubaUnits",
        _ => false,
    });
    if let Some(y) = img.channel("Y") {
        if mitsuba {
            eprintln!("Y = {:.6} (Mitsuba's scale, not cd/m²)", mean(y));
        } else {
            eprintln!("luminance Y = {:.6} cd/m²", mean(y));
        }
    }
    if !units.is_empty() {
        eprintln!("file's emissive units: {units} (per nm)");
    }
    if let Some(path) = &args.plot {
        let title = format!(
            "{} ({}, {}){}",
            args.image
                .file_name()
                .map(|f| f.to_string_lossy().into_owned())
                .unwrap_or_default(),
            args.x,
            args.y,
            if args.size > 1 {
                format!(", {0}×{0} mean", args.size)
            } else {
                String::new()
            }
        );
        let series = [crate::plot::Series {
            name: "radiance",
            points,
        }];
        let svg = crate::plot::svg(
            &series,
            &title,
            "wavelength (nm)",
            "spectral radiance (W·m⁻²·sr⁻¹·nm⁻¹)",
        );
        super::spectrum::write_text(path, &svg)?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}
