//! `spectrace lens FILE`: a lens file's first-order optics per wavelength, as a lens-design
//! program prints them, its real-ray spot size and its focal shift.

use clap::Args;

use super::CliError;
use crate::optics::LensSystem;

#[derive(Args, Debug)]
pub struct LensArgs {
    /// A lens file (pbrt-v4's format: radius, thickness, index or glass, aperture diameter per
    /// line, mm, object side first).
    pub file: std::path::PathBuf,
    /// Wavelengths, nm, comma-separated (default: the F, d and C lines).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "486.1327,587.5618,656.2725"
    )]
    pub wavelengths: Vec<f64>,
    /// Also trace a real axial bundle (an object at infinity) and print its RMS spot radius, µm,
    /// on the paraxial focal plane of each wavelength.
    #[arg(long)]
    pub spot: bool,
    /// Plot the focal shift (back focal length minus its value at 587.56 nm, mm) against
    /// wavelength, 400–700 nm, to an SVG file.
    #[arg(long, value_name = "SVG")]
    pub plot: Option<std::path::PathBuf>,
}

pub fn run(args: LensArgs) -> Result<(), CliError> {
    use crate::units::{Length, length::millimeter, length::nanometer};
    let wl: Vec<Length> = args
        .wavelengths
        .iter()
        .map(|&l| Length::new::<nanometer>(l))
        .collect();
    let rows =
        crate::api::lens(&args.file, &wl, args.spot).map_err(|e| CliError::Usage(e.to_string()))?;
    let mut out = String::from("wavelength_nm,efl_mm,bfl_mm");
    if args.spot {
        out.push_str(",spot_rms_um");
    }
    out.push('\n');
    for r in &rows {
        out.push_str(&format!(
            "{},{:.6},{:.6}",
            r.wavelength.get::<nanometer>(),
            r.efl.get::<millimeter>(),
            r.bfl.get::<millimeter>()
        ));
        if args.spot {
            match r.spot_rms {
                Some(s) => out.push_str(&format!(",{:.4}", s.get::<millimeter>() * 1e3)),
                None => out.push_str(",nan"),
            }
        }
        out.push('\n');
    }
    print!("{out}");
    if let Some(path) = &args.plot {
        let desc = crate::loader::lens::read(&args.file)?;
        plot(&crate::build::lens_system(&desc)?, path)?;
    }
    Ok(())
}

fn plot(sys: &LensSystem, path: &std::path::Path) -> Result<(), CliError> {
    let d = sys
        .paraxial(crate::spectrum::ior::FRAUNHOFER_D_NM as f64)
        .bfl;
    let points = (400..=700)
        .map(|l| (l as f64, sys.paraxial(l as f64).bfl - d))
        .collect();
    let series = [crate::plot::Series {
        name: "focal shift",
        points,
    }];
    let svg = crate::plot::svg(
        &series,
        "paraxial focal shift",
        "wavelength (nm)",
        "back focal length − BFL(587.56 nm) (mm)",
    );
    super::spectrum::write_text(path, &svg)?;
    eprintln!("wrote {}", path.display());
    Ok(())
}
