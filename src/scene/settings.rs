//! What the scene asks the integrator for: which estimator, and how it chooses lights. The
//! loaders name these; the render side owns them.

/// Which estimator renders (the one list the scene formats, the CLI, the library API and
/// Python name integrators from).
///
/// ```
/// let o = spectrace::Options { integrator: Some(spectrace::Integrator::Bdpt), ..Default::default() };
/// assert_eq!(spectrace::Integrator::from_name("bdpt"), o.integrator);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IntegratorKind {
    /// Path tracing with next-event estimation and MIS (`integrator::path`).
    Path,
    /// Light tracing: particles from the lights connected to the camera (`integrator::light`).
    Light,
    /// Bidirectional path tracing (`integrator::bdpt`).
    Bdpt,
    /// The lecture notes' Whitted model: delta lobes and direct light only.
    Whitted,
    /// Mitsuba's `direct`: emission seen directly plus direct lighting at the first hit from
    /// this many light and BSDF samples, combined by MIS.
    Direct {
        emitter_samples: u32,
        bsdf_samples: u32,
    },
}

impl IntegratorKind {
    /// The names [`IntegratorKind::from_name`] knows, for the CLI's `--integrator`, the API's
    /// and Python's `integrator` and their messages.
    pub const NAMES: [&'static str; 5] = ["path", "light", "bdpt", "whitted", "direct"];

    /// The integrator called `name` (one of [`IntegratorKind::NAMES`]); `direct` with one light
    /// and one BSDF sample per camera hit (Mitsuba's defaults). None for other names.
    pub fn from_name(name: &str) -> Option<Self> {
        Some(match name {
            "path" => IntegratorKind::Path,
            "light" => IntegratorKind::Light,
            "bdpt" => IntegratorKind::Bdpt,
            "whitted" => IntegratorKind::Whitted,
            "direct" => IntegratorKind::Direct {
                emitter_samples: 1,
                bsdf_samples: 1,
            },
            _ => return None,
        })
    }

    /// The name the scene format, the CLI and EXR headers use.
    pub fn name(self) -> &'static str {
        match self {
            IntegratorKind::Path => "path",
            IntegratorKind::Light => "light",
            IntegratorKind::Bdpt => "bdpt",
            IntegratorKind::Whitted => "whitted",
            IntegratorKind::Direct { .. } => "direct",
        }
    }
}

/// Probabilities with which next-event estimation (and the light tracer) chooses a light. Either
/// is unbiased; they differ in noise.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightSelection {
    /// By each light's likely contribution at the shading point, through a tree over the
    /// lights' bounds ([`crate::light::LightTree`]; pbrt-v4's `BVHLightSampler`): spectrace's
    /// default, for next-event estimation in `path` and `direct`. Lights at infinity and beams
    /// are chosen beside the tree, each as likely as the tree (pbrt-v4's rule); the particle
    /// tracers (`light`, and `bdpt`, whose strategies share their light choice) choose the
    /// same groups alike and the tree's lights by power.
    Tree,
    /// In proportion to emitted power (pbrt-v4's `PowerLightSampler`), best when lights
    /// differ greatly in power and little in distance.
    Power,
    /// Every emitting light alike, or in proportion to its `sampling_weight`: Mitsuba 3's rule
    /// (weights 1 by default), better when a weak light is hard to sample well, such as a sky
    /// beside a lamp.
    Uniform,
}

#[cfg(test)]
mod tests {
    use super::IntegratorKind;

    /// Every name the CLI, the API and Python accept reads back as itself, and nothing else
    /// reads as an integrator.
    #[test]
    fn names_round_trip() {
        for n in IntegratorKind::NAMES {
            let k = IntegratorKind::from_name(n).unwrap_or_else(|| panic!("{n}"));
            assert_eq!(k.name(), n);
        }
        assert_eq!(IntegratorKind::from_name("volpath"), None);
    }
}

/// A first-hit quantity written beside the image (Mitsuba's `aov` integrator), averaged over a
/// pixel's camera samples with the film's filter. Lengths in m, zero where the ray escapes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AovKind {
    /// Distance from the camera along the ray, m (`.T`).
    Depth,
    /// Hit point, world space, m (`.X .Y .Z`).
    Position,
    /// Surface coordinates (`.U .V`).
    Uv,
    /// Unit geometric normal, outward (`.X .Y .Z`).
    GeoNormal,
    /// Unit shading normal before normal or bump maps (`.X .Y .Z`).
    ShNormal,
    /// ∂p/∂u and ∂p/∂v, m per unit (`.X .Y .Z`).
    DpDu,
    DpDv,
    /// The primitive's index within its shape, and the shape's index (`.I`).
    PrimIndex,
    ShapeIndex,
}

impl AovKind {
    /// The kind Mitsuba's `aovs` names `name`; None for names spectrace does not write
    /// (`albedo`, `duv_dx`, `duv_dy`) or does not know.
    pub fn from_mitsuba(name: &str) -> Option<Self> {
        Some(match name {
            "depth" => AovKind::Depth,
            "position" => AovKind::Position,
            "uv" => AovKind::Uv,
            "geo_normal" => AovKind::GeoNormal,
            "sh_normal" => AovKind::ShNormal,
            "dp_du" => AovKind::DpDu,
            "dp_dv" => AovKind::DpDv,
            "prim_index" => AovKind::PrimIndex,
            "shape_index" => AovKind::ShapeIndex,
            _ => return None,
        })
    }
}

/// One AOV: its channel name prefix (`nn` gives `nn.X`, `nn.Y`, `nn.Z`) and kind.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Aov {
    pub name: String,
    pub kind: AovKind,
}
