//! Mitsuba 3 (and 2.x) XML scenes → [`SceneDesc`], so that one file renders in both renderers.
//!
//! Supported: `default` parameters with `$name` substitution (overridden by `-D name=value`),
//! `id`/`ref`, `include`; `perspective` and `thinlens` sensors with `to_world`
//! (`lookat`, `translate`, `rotate`, `scale`, `matrix`) and Mitsuba's field of view (`fov` on
//! `fov_axis`, else `focal_length`, default 50 mm on a 36 × 24 mm frame), `hdrfilm` (`width`,
//! `height`, `rfilter` box/gaussian), the `independent` sampler, the `path` integrator
//! (`max_depth` as path length); shapes `obj`, `ply`, `rectangle`, `cube`, `sphere`, `disk`
//! with `to_world` and `flip_normals`; BSDFs `diffuse`, `twosided`, `conductor` (default: the
//! perfect mirror eta = 0, k = 1), `roughconductor`, `dielectric`, `roughdielectric` (Beckmann,
//! Mitsuba's default, or GGX; anisotropic α is refused); emitters `area`, `point`,
//! `spot`, `constant`, `directional`; spectra as a float, `λ:v` lists, `filename`, `blackbody`,
//! `d65` and `rgb`. An emitter's absent spectrum, bare float and `rgb` are shaped by Mitsuba's
//! D65 (CIE D65 / 98.997), as Mitsuba reads them.
//!
//! Units: Mitsuba reads emitter spectra as plain numbers; they become spectral radiance (or
//! intensity, irradiance) in W·m⁻²·sr⁻¹·nm⁻¹ unchanged (`scale = 1`). spectrace's `Y` is then
//! K_m·∫ȳ = 683.002 × 106.856895 = 72 983.0 times Mitsuba's (`../shared/PHYSICS.md`).
//! Anything outside the subset is an error naming the element, its line and the nearest
//! supported plugin of the same kind.

mod bsdf;
mod cx;
mod emitters;
mod integrator;
mod media;
mod params;
mod plugins;
pub mod rgl;
mod scene;
mod sensor;
mod shapes;
mod spectra;
pub mod tensor;
mod textures;
mod transform;
mod vol;

pub use vol::{VolFile, parse as parse_vol};
mod xml;

use std::collections::HashMap;
use std::path::Path;

use super::SceneDesc;
use super::error::{LoadError, Loc, SourceMap};
pub use xml::Element;

/// Reads a Mitsuba XML scene; `defines` override its `default` parameters.
pub fn load(path: &Path, defines: &[(String, String)]) -> Result<SceneDesc, LoadError> {
    let text = crate::files::read_text(path, crate::files::MAX_TEXT_BYTES).map_err(|e| {
        LoadError::new(
            path,
            Loc { line: 0, col: 0 },
            "",
            format!("cannot read scene file: {e}"),
        )
    })?;
    load_str(&text, path, defines)
}

/// Parses one XML file into its root element, with errors located in that file.
pub(crate) fn parse_file(text: &str, path: &Path) -> Result<Element, LoadError> {
    xml::parse(text)
        .map_err(|e| LoadError::new(path, SourceMap::new(text).loc(e.pos), "", e.message))
}

/// Reads Mitsuba XML text; `path` names it in errors and anchors relative paths.
pub fn load_str(
    text: &str,
    path: &Path,
    defines: &[(String, String)],
) -> Result<SceneDesc, LoadError> {
    let root = parse_file(text, path)?;
    let defines: HashMap<String, String> = defines.iter().cloned().collect();
    scene::scene(root, text, path, &defines, None)
}

/// [`load_str`] with every `<include>` served from `includes` (file name as written → text)
/// instead of the disk: for tests and fuzzing. A name missing from the map is an error.
pub fn load_str_with_includes(
    text: &str,
    path: &Path,
    defines: &[(String, String)],
    includes: &HashMap<String, String>,
) -> Result<SceneDesc, LoadError> {
    let root = parse_file(text, path)?;
    let defines: HashMap<String, String> = defines.iter().cloned().collect();
    scene::scene(root, text, path, &defines, Some(includes))
}
