//! What the scene asks the integrator for: which estimator, and how it chooses lights. The
//! loaders name these; the render side owns them.

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IntegratorKind {
    Path,
    Light,
    /// Bidirectional path tracing (`integrator::bdpt`).
    Bdpt,
    Whitted,
    /// Mitsuba's `direct`: emission seen directly plus direct lighting at the first hit from
    /// this many light and BSDF samples, combined by MIS.
    Direct {
        emitter_samples: u32,
        bsdf_samples: u32,
    },
}

impl IntegratorKind {
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
