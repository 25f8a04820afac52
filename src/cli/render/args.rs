//! `spectrace render`'s arguments (also written to a checkpoint's `args.toml`).

use std::path::PathBuf;

use clap::{Args, ValueEnum};

use crate::scene::IntegratorKind;

/// What a false-colour image shows.
#[derive(Clone, Copy, Debug, PartialEq, ValueEnum, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FalseColourKind {
    /// Luminance of the rendered image, cd/m².
    Luminance,
    /// Illuminance at the surfaces the pixels see, lx (an extra pass, as `rpict -i`).
    Illuminance,
}

/// The scale of a false-colour image.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, ValueEnum, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "lowercase")]
pub enum FalseColourScale {
    #[default]
    Log,
    Linear,
}

#[derive(Args, Debug, Default, Clone, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct RenderArgs {
    /// Scene file: spectrace TOML, Mitsuba 3 XML (.xml) or pbrt-v4 (.pbrt).
    #[arg(required_unless_present = "resume")]
    pub scene: Option<PathBuf>,
    /// Output EXR (float32: X, Y, Z in cd/m², linear sRGB R, G, B, band radiance L in
    /// W·m⁻²·sr⁻¹; spectral channels with --spectral-bins). Default: the scene's name with .exr,
    /// in the current folder.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// 8-bit sRGB PNG preview. Default: the EXR's name with .png.
    #[arg(long)]
    pub png: Option<PathBuf>,
    /// Samples per pixel (light tracing: light paths per pixel). Default: the scene's.
    #[arg(long)]
    pub spp: Option<u32>,
    /// Worker threads. Default: every core.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Seed of the sampler; the same seed gives the same image for any thread count.
    #[arg(long, default_value_t = 0)]
    pub seed: u32,
    /// Integrator: path (next-event estimation and MIS), light (particles from the lights:
    /// caustics), bdpt (bidirectional, combined by MIS), whitted (the notes' model) or direct
    /// (direct light at the first hit, Mitsuba's). Default: the scene's.
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(IntegratorKind::NAMES))]
    pub integrator: Option<String>,
    /// Spectral EXR bins over the film's wavelength range (Fichet et al. 2021 layout).
    #[arg(long)]
    pub spectral_bins: Option<u32>,
    /// PNG exposure EV₁₀₀ (saturation at 1.2·2^EV cd/m²). Default: automatic.
    #[arg(long, allow_negative_numbers = true)]
    pub exposure: Option<f32>,
    /// What a camera sample does at its first dispersive hit: `split` (trace it again with
    /// each of its wavelengths as the hero, so that every wavelength is estimated) or `hero`
    /// (keep the hero wavelength alone). Default: the scene's `dispersion` (`split`).
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(["split", "hero"]))]
    pub dispersion: Option<String>,
    /// The PNG's display transform: `standard` (out-of-gamut and over-exposed colours pale
    /// toward the grey of their luminance, keeping their hue; in-gamut colours unchanged) or
    /// `clip` (each channel clamped on its own). The EXR is never transformed.
    #[arg(long, default_value = "standard",
          value_parser = clap::builder::PossibleValuesParser::new(crate::output::View::NAMES))]
    pub view: String,
    /// Also write a false-colour PNG (viridis, with a legend in its unit) of `luminance` (cd/m²,
    /// the render's Y) or `illuminance` (lx at the surfaces seen: an extra pass at the render's
    /// spp, as Radiance's `rpict -i`).
    #[arg(long, value_name = "KIND", alias = "false-color")]
    pub false_colour: Option<FalseColourKind>,
    /// The false-colour PNG. Default: the EXR's name with .false.png.
    #[arg(long, value_name = "PNG", alias = "false-color-png")]
    pub false_colour_png: Option<PathBuf>,
    /// The false colours' scale.
    #[arg(long, value_enum, default_value_t, alias = "false-color-scale")]
    pub false_colour_scale: FalseColourScale,
    /// The top of the false colours' scale, in cd/m² or lx. Default: the largest value rounded
    /// up to 1, 2 or 5 × 10ⁿ.
    #[arg(long, value_name = "VALUE", alias = "false-color-max")]
    pub false_colour_max: Option<f64>,
    /// Decades below the top on the log scale [default: 3].
    #[arg(long, value_name = "N", alias = "false-color-decades")]
    pub false_colour_decades: Option<u32>,
    /// No progress bar and no summary.
    #[arg(short, long)]
    pub quiet: bool,
    /// Mitsuba XML parameter, NAME=VALUE (overrides a <default>); repeatable.
    #[arg(short = 'D', value_name = "NAME=VALUE")]
    pub define: Vec<String>,
    /// Write X, Y, Z, R, G, B on Mitsuba 3.9.1's scale: divided by 683.002 × 106.7502594
    /// = 72 910.6 (Mitsuba's film normalisation of unitless emitter spectra). L stays in
    /// W·m⁻²·sr⁻¹.
    #[arg(long)]
    pub mitsuba_units: bool,
    /// `bdpt` debugging: render only the connection strategy with S light and T camera
    /// vertices ("S,T"), with its MIS weight (the weighted images of all strategies sum to the
    /// full render).
    #[arg(long, value_name = "S,T")]
    pub bdpt_strategy: Option<String>,
    /// With --bdpt-strategy: without its MIS weight (an estimator of the paths it can sample
    /// by itself).
    #[arg(long, requires = "bdpt_strategy")]
    pub bdpt_unweighted: bool,
    /// Render only part I of N ("I/N", I from 0 to N − 1): a disjoint share of every pixel's
    /// samples. The EXR carries the part's exact sums; `spectrace merge` combines all N parts
    /// into the image one render would give, bit for bit.
    #[arg(long, value_name = "I/N")]
    pub part: Option<String>,
    /// Write checkpoints into folder DIR (created if needed), from which `--resume DIR`
    /// continues to the image an uninterrupted render gives, bit for bit.
    #[arg(long, value_name = "DIR")]
    pub checkpoint: Option<PathBuf>,
    /// Time between checkpoints ("60s", "5m", "500ms"; a bare number is seconds).
    #[arg(
        long,
        value_name = "TIME",
        default_value = "60s",
        requires = "checkpoint"
    )]
    pub checkpoint_every: String,
    /// Continue the render checkpointed in DIR, with the arguments it was started with
    /// (only --threads and --quiet may be given again).
    #[arg(long, value_name = "DIR", conflicts_with = "checkpoint")]
    #[serde(skip)]
    pub resume: Option<PathBuf>,
    /// Render time budget ("90s", "10m", "2h"): stop at the end of the pass after which the
    /// next would end past it. Without --spp, renders as many samples as fit.
    #[arg(long, value_name = "TIME")]
    pub time: Option<String>,
    /// Stop at the end of the first pass whose estimated relative RMS error of luminance is
    /// below this fraction (e.g. 0.01). Without --spp, renders as many samples as it takes.
    #[arg(long, value_name = "FRACTION")]
    pub target_error: Option<f64>,
}

impl RenderArgs {
    /// The scene's hash for a farm part or a checkpoint (which must match the scene they
    /// resume); empty when neither is asked for.
    pub(super) fn scene_hash(&self, scene: &std::path::Path) -> Result<String, super::CliError> {
        Ok(if self.part.is_some() || self.checkpoint.is_some() {
            super::super::farm::scene_hash(scene, &self.define)?
        } else {
            String::new()
        })
    }
}
