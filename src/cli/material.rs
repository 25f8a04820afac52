//! `spectrace material SCENE MATERIAL`: a material's directional-hemispherical reflectance and
//! transmittance per wavelength, as CSV (and an SVG plot).

use clap::Args;

use super::CliError;
use crate::api::MaterialAlbedo;
use crate::units::{Angle, parse::parse};

#[derive(Args, Debug)]
pub struct MaterialArgs {
    /// A scene file (TOML or Mitsuba XML) that defines the material.
    pub scene: std::path::PathBuf,
    /// The material's name in the scene.
    pub material: String,
    /// Angle of incidence from the surface normal, with its unit ("30deg", "0.5 rad").
    #[arg(long, default_value = "0deg", allow_hyphen_values = true)]
    pub angle: String,
    /// Wavelengths: FROM:TO:STEP in nm (default 380:780:5), or a comma-separated list.
    #[arg(long, default_value = "380:780:5")]
    pub wavelengths: String,
    /// Samples per wavelength for materials with rough or diffuse lobes (specular materials
    /// are exact).
    #[arg(long, default_value_t = 65536)]
    pub samples: u32,
    /// Plot reflectance and transmittance against wavelength to an SVG file.
    #[arg(long, value_name = "SVG")]
    pub plot: Option<std::path::PathBuf>,
}

/// `FROM:TO:STEP` or `a,b,c` (nm).
pub fn wavelength_list(s: &str) -> Result<Vec<f32>, CliError> {
    let bad = || {
        CliError::Usage(format!(
            "--wavelengths \"{s}\": expected FROM:TO:STEP or a list, in nm"
        ))
    };
    let v: Vec<f32> = if let [a, b, c] = s.split(':').collect::<Vec<_>>()[..] {
        let (a, b, c): (f32, f32, f32) = (
            a.trim().parse().map_err(|_| bad())?,
            b.trim().parse().map_err(|_| bad())?,
            c.trim().parse().map_err(|_| bad())?,
        );
        if !(c > 0.0 && b >= a && (b - a) / c <= 100_000.0) {
            return Err(bad());
        }
        let n = ((b - a) / c + 1e-3).floor() as usize;
        (0..=n).map(|i| a + c * i as f32).collect()
    } else {
        s.split(',')
            .map(|x| x.trim().parse::<f32>().map_err(|_| bad()))
            .collect::<Result<_, _>>()?
    };
    if v.is_empty() || v.iter().any(|l| !(l.is_finite() && *l > 0.0)) {
        return Err(bad());
    }
    Ok(v)
}

pub fn run(args: MaterialArgs) -> Result<(), CliError> {
    let scene = crate::api::Scene::load(&args.scene).map_err(|e| CliError::Usage(e.to_string()))?;
    let a: Angle = parse(&args.angle).map_err(|e| CliError::Usage(format!("--angle: {e}")))?;
    let lambdas: Vec<crate::units::Length> = wavelength_list(&args.wavelengths)?
        .into_iter()
        .map(|l| crate::units::Length::new::<crate::units::length::nanometer>(l as f64))
        .collect();
    let rows = scene
        .material_albedo(&args.material, a, &lambdas, args.samples)
        .map_err(|e| CliError::Usage(format!("{}: {e}", args.scene.display())))?;
    print!("{}", table(&rows));
    if let Some(path) = &args.plot {
        let series = [
            crate::plot::Series {
                name: "reflectance",
                points: rows.iter().map(|r| (nm(r), r.reflectance)).collect(),
            },
            crate::plot::Series {
                name: "transmittance",
                points: rows.iter().map(|r| (nm(r), r.transmittance)).collect(),
            },
        ];
        let title = format!("{} at {}", args.material, args.angle);
        let svg = crate::plot::svg(
            &series,
            &title,
            "wavelength (nm)",
            "fraction of incident power",
        );
        super::spectrum::write_text(path, &svg)?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

fn nm(r: &MaterialAlbedo) -> f64 {
    r.wavelength.get::<crate::units::length::nanometer>()
}

/// CSV: `wavelength_nm,reflectance,transmittance,reflectance_se,transmittance_se`.
pub fn table(rows: &[MaterialAlbedo]) -> String {
    let mut out =
        String::from("wavelength_nm,reflectance,transmittance,reflectance_se,transmittance_se\n");
    for r in rows {
        out.push_str(&format!(
            "{},{:.6},{:.6},{:.6},{:.6}\n",
            nm(r),
            r.reflectance,
            r.transmittance,
            r.reflectance_se,
            r.transmittance_se
        ));
    }
    out
}
