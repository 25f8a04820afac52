//! `spectrace spectrum NAME [WAVELENGTH...]`.

use clap::Args;

use super::CliError;
use crate::colour::cie::{CIE_Y_INTEGRAL, K_M, integrate_xyz, reflectance_xyz, xyz_to_xy};
use crate::colour::spaces::{srgb_encode, xyz_to_srgb};
use crate::spectrum::ior::FRAUNHOFER_D_NM;
use crate::spectrum::named::{CurveKind, Named, lookup, names};
use crate::units::parse::parse;
use crate::units::{Length, plain};

#[derive(Args, Debug)]
pub struct SpectrumArgs {
    /// Spectrum name, e.g. cie-d65, glass:N-BK7, metal:Au, colorchecker:dark-skin,
    /// blackbody:6500K.
    /// Without a name: a summary of all spectral data.
    pub name: Option<String>,
    /// Wavelengths, e.g. 587.56nm or "0.55 um" (a bare number is nm).
    #[arg(allow_negative_numbers = true)]
    pub wavelengths: Vec<String>,
    /// List every named spectrum.
    #[arg(long)]
    pub list: bool,
    /// Plot the spectrum to an SVG file: the value (with its unit) against wavelength in nm.
    /// NAME may also be a spectrum CSV file (wavelength_nm,value).
    #[arg(long, value_name = "SVG")]
    pub plot: Option<std::path::PathBuf>,
}

fn wavelength_nm(s: &str) -> Result<f32, CliError> {
    if let Ok(v) = s.trim().parse::<f64>() {
        if !v.is_finite() || v <= 0.0 {
            return Err(CliError::Usage(format!(
                "wavelength \"{s}\" must be a positive number of nm"
            )));
        }
        return Ok(v as f32);
    }
    let l: Length = parse(s).map_err(CliError::Wavelength)?;
    let nm = plain::nm(l);
    if nm <= 0.0 {
        return Err(CliError::Usage(format!(
            "wavelength \"{s}\" must be positive"
        )));
    }
    Ok(nm)
}

pub fn run(args: SpectrumArgs) -> Result<(), CliError> {
    if args.list {
        for (name, kind) in names() {
            println!("{name:<28} {kind}");
        }
        return Ok(());
    }
    let Some(name) = args.name else {
        print_data_summary();
        return Ok(());
    };
    let named = match lookup(&name) {
        Ok(n) => n,
        // a spectrum file, for plotting
        Err(_) if args.plot.is_some() && std::path::Path::new(&name).is_file() => {
            let t = crate::spectrum::data::load_spectrum_file(std::path::Path::new(&name))
                .map_err(|e| CliError::Usage(e.to_string()))?;
            Named::Curve {
                spectrum: crate::spectrum::Spectrum::Piecewise(std::sync::Arc::new(t)),
                kind: CurveKind::Illuminant,
                source: String::new(),
            }
        }
        Err(e) => return Err(e.into()),
    };
    if let Some(path) = &args.plot {
        let is_file = lookup(&name).is_err();
        return plot(&name, &named, is_file, path);
    }
    if args.wavelengths.is_empty() {
        print_summary(&name, &named);
        return Ok(());
    }
    let lambdas = args
        .wavelengths
        .iter()
        .map(|w| wavelength_nm(w))
        .collect::<Result<Vec<_>, _>>()?;
    for l in lambdas {
        match &named {
            Named::Curve { spectrum, .. } => println!("{}", spectrum.eval(l)),
            Named::Dielectric(g) => println!("{}", g.ior.eval(l)),
            Named::Conductor(m) => {
                let (n, k) = m.ior.eval(l);
                println!("{n} {k}");
            }
        }
    }
    Ok(())
}

/// Writes an SVG plot of a named (or file) spectrum, atomically.
fn plot(name: &str, named: &Named, is_file: bool, path: &std::path::Path) -> Result<(), CliError> {
    use crate::plot::Series;
    let range = |lo: f32, hi: f32| {
        // about one point per nm, at most 4096
        let n = ((hi - lo).round() as usize).clamp(1, 4096);
        (0..=n).map(move |k| lo + (hi - lo) * k as f32 / n as f32)
    };
    let (series, y_label): (Vec<Series<'_>>, &str) = match named {
        Named::Curve { spectrum, kind, .. } => {
            let (lo, hi) = match spectrum {
                crate::spectrum::Spectrum::Piecewise(t) => t.domain(),
                _ => (360.0, 830.0),
            };
            let label = if is_file {
                "value (as in the file)"
            } else {
                kind.quantity()
            };
            let pts = range(lo, hi)
                .map(|l| (l as f64, spectrum.eval(l) as f64))
                .collect();
            (vec![Series { name, points: pts }], label)
        }
        Named::Dielectric(g) => {
            let (lo, hi) = g.range_nm;
            let pts = range(lo, hi)
                .map(|l| (l as f64, g.ior.eval(l) as f64))
                .collect();
            (
                vec![Series {
                    name: "n",
                    points: pts,
                }],
                "refractive index n",
            )
        }
        Named::Conductor(m) => {
            let n = range(360.0, 830.0)
                .map(|l| (l as f64, m.ior.eval(l).0 as f64))
                .collect();
            let k = range(360.0, 830.0)
                .map(|l| (l as f64, m.ior.eval(l).1 as f64))
                .collect();
            (
                vec![
                    Series {
                        name: "n",
                        points: n,
                    },
                    Series {
                        name: "k",
                        points: k,
                    },
                ],
                "complex index n + ik",
            )
        }
    };
    let svg = crate::plot::svg(&series, name, "wavelength (nm)", y_label);
    write_text(path, &svg)?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

/// Writes text to `path` atomically.
pub(super) fn write_text(path: &std::path::Path, text: &str) -> Result<(), CliError> {
    crate::image_io::write_atomically(path, |f| {
        use std::io::Write;
        f.write_all(text.as_bytes())
            .map_err(|e| crate::image_io::ImageError::Io {
                path: path.to_path_buf(),
                action: "write".into(),
                source: e,
            })
    })?;
    Ok(())
}

fn print_summary(name: &str, named: &Named) {
    match named {
        Named::Curve {
            spectrum,
            kind,
            source,
        } => {
            let what = match kind {
                CurveKind::Illuminant => "illuminant, relative spectral power distribution",
                CurveKind::Reflectance => "reflectance factor",
                CurveKind::ColourMatching => "CIE 1931 2° colour-matching function",
                CurveKind::Blackbody => "black body, normalised to 1 at its peak",
            };
            println!("{name}: {what}");
            if let crate::spectrum::Spectrum::Piecewise(t) = spectrum {
                let (lo, hi) = t.domain();
                println!(
                    "  tabulated {lo}–{hi} nm, {} samples, max {}",
                    t.wavelengths().len(),
                    t.max_value()
                );
            }
            let s = |l: f32| spectrum.eval(l) as f64;
            match kind {
                CurveKind::Illuminant | CurveKind::Blackbody => {
                    let xy = xyz_to_xy(integrate_xyz(s));
                    println!(
                        "  chromaticity x = {:.4}, y = {:.4} (CIE 1931 2°)",
                        xy[0], xy[1]
                    );
                }
                CurveKind::Reflectance => {
                    let d65 = match lookup("cie-d65") {
                        Ok(Named::Curve { spectrum, .. }) => spectrum,
                        _ => return,
                    };
                    let xyz = reflectance_xyz(s, |l| d65.eval(l) as f64);
                    let rgb = xyz_to_srgb(xyz).map(|v| srgb_encode(v.clamp(0.0, 1.0)) * 255.0);
                    println!(
                        "  under D65: Y = {:.4}, sRGB = ({:.0}, {:.0}, {:.0})",
                        xyz[1], rgb[0], rgb[1], rgb[2]
                    );
                }
                CurveKind::ColourMatching => {}
            }
            if !source.is_empty() {
                println!("  {source}");
            }
        }
        Named::Dielectric(g) => {
            println!("{name}: dielectric, Sellmeier dispersion");
            println!(
                "  n_d({FRAUNHOFER_D_NM} nm) = {:.5} (catalogue {:.5}), Abbe V_d = {:.2}{}",
                g.ior.eval(FRAUNHOFER_D_NM),
                g.nd,
                g.ior.abbe_number(),
                g.vd.map(|v| format!(" (catalogue {v:.2})"))
                    .unwrap_or_default()
            );
            println!("  formula valid {}–{} nm", g.range_nm.0, g.range_nm.1);
            println!("  {}", g.source);
        }
        Named::Conductor(m) => {
            let (lo, hi) = m.ior.n.domain();
            let (n, k) = m.ior.eval(550.0);
            println!("{name}: conductor, complex index n + ik");
            println!("  tabulated {lo}–{hi} nm; at 550 nm n = {n:.4}, k = {k:.4}");
            println!("  {}", m.source);
        }
    }
}

/// The main job's output until the renderer exists: what spectral data spectrace carries.
pub fn print_data_summary() {
    let y = integrate_xyz(|_| 1.0)[1];
    println!(
        "spectrace {} — spectral data summary",
        env!("CARGO_PKG_VERSION")
    );
    println!("CIE 1931 2°: ∫ȳ dλ = {y:.6} nm (reference {CIE_Y_INTEGRAL}), K_m = {K_M} lm/W");
    println!(
        "1 W·m⁻²·sr⁻¹·nm⁻¹ flat over 360–830 nm = {:.1} cd/m²",
        K_M * y
    );
    let all = names();
    for family in ["cie-", "glass:", "metal:", "colorchecker:"] {
        let n: Vec<&str> = all
            .iter()
            .filter(|(k, _)| k.starts_with(family))
            .map(|(k, _)| k.as_str())
            .collect();
        println!("{:<14} {:>2} spectra: {}", family, n.len(), n.join(" "));
    }
    if let Ok(Named::Dielectric(g)) = lookup("glass:N-BK7") {
        println!(
            "N-BK7: n_d = {:.5}, V_d = {:.2}",
            g.ior.eval(FRAUNHOFER_D_NM),
            g.ior.abbe_number()
        );
    }
    println!("Try: spectrace spectrum --list, spectrace spectrum glass:N-BK7 587.56nm");
}
