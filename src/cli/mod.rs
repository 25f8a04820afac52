//! Command-line interface (clap).

mod checkpoint;
mod farm;
mod lens;
mod material;
mod measure;
mod merge;
mod probe;
mod progress;
mod render;
mod spectrum;

use clap::{Parser, Subcommand};

/// spectrace: a spectral path tracer in physical units.
///
/// Wavelengths are in nm, radiance in W·m⁻²·sr⁻¹·nm⁻¹, luminance (Y) in cd/m². Without a
/// command, renders the built-in default scene (a projector's white beam through a slit and
/// an N-SF11 prism, its spectrum on the wall of a room) to
/// spectrace.exr and spectrace.png in the current folder.
#[derive(Parser, Debug)]
#[command(name = "spectrace", version, about, long_about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Print a named spectrum at wavelengths, summarise it, or list every name.
    ///
    /// With wavelengths, prints one line per wavelength: the value (illuminants: relative SPD;
    /// reflectances: factor from 0 to 1; glasses: index n), or "n k" for metals. Wavelengths take a
    /// unit ("587.56nm", "0.55 um"); a bare number is read as nm.
    Spectrum(spectrum::SpectrumArgs),
    /// Render a scene file to EXR and PNG.
    Render(Box<render::RenderArgs>),
    /// Merge the EXR files of render parts (`render --part I/N`) into one image, bit for bit
    /// the image one render of all their samples gives.
    Merge(merge::MergeArgs),
    /// Measure illuminance (lx) and irradiance (W/m²) at the scene's `[[sensors]]` by
    /// hemispherical integration, with a standard error per point, into a CSV file.
    Measure(measure::MeasureArgs),
    /// Print (and plot) the spectral radiance of a pixel or region of a spectral EXR.
    Probe(probe::ProbeArgs),
    /// Print a lens file's paraxial effective and back focal lengths (mm) per wavelength as CSV,
    /// with `--spot` its real-ray RMS spot radius (µm), with `--plot` its focal shift.
    Lens(lens::LensArgs),
    /// Print a material's directional-hemispherical reflectance and transmittance per
    /// wavelength as CSV (exact for smooth materials, with standard errors otherwise).
    Material(material::MaterialArgs),
}

/// An error for the user, printed after "error: ".
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    #[error(transparent)]
    UnknownSpectrum(#[from] crate::spectrum::named::UnknownSpectrum),
    #[error("wavelength {0}")]
    Wavelength(crate::units::parse::QuantityError),
    #[error("{0}")]
    Usage(String),
    #[error(transparent)]
    Scene(#[from] crate::loader::LoadError),
    #[error(transparent)]
    Image(#[from] crate::image_io::ImageError),
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Some(Command::Spectrum(args)) => spectrum::run(args),
        Some(Command::Render(args)) => render::run(*args),
        Some(Command::Merge(args)) => merge::merge(args),
        Some(Command::Measure(args)) => measure::run(args),
        Some(Command::Probe(args)) => probe::run(args),
        Some(Command::Lens(args)) => lens::run(args),
        Some(Command::Material(args)) => material::run(args),
        None => render::run_default(),
    }
}

/// The display transform called `name` (`--view`, checked by clap; an empty name, from a
/// checkpoint written before the option existed, is the default).
pub(crate) fn view(name: &str) -> crate::output::View {
    crate::output::View::from_name(name).unwrap_or_default()
}
