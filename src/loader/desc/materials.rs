//! Materials (the textures their slots take are in `textures.rs`).

use super::*;

#[derive(Clone, Debug)]
pub enum MaterialKind {
    Diffuse {
        reflectance: TextureDesc,
    },
    Phong {
        kd: Spectrum,
        ks: Spectrum,
        exponent: f64,
    },
    /// Smooth when `roughness` is None, else microfacets of `distribution` with roughness
    /// [α_u, α_v]: α_u along the surface's ∂p/∂u, α_v across it (equal when isotropic).
    Dielectric {
        ior: Ior,
        exterior_ior: f64,
        roughness: Option<[f64; 2]>,
        distribution: Distribution,
        /// The masking–shadowing function of a rough one (Mitsuba's scenes: separable).
        smith: Smith,
    },
    /// As a dielectric's: smooth, or roughness [α_u, α_v].
    Conductor {
        ior: ComplexIor,
        exterior_ior: f64,
        roughness: Option<[f64; 2]>,
        distribution: Distribution,
        smith: Smith,
    },
    /// No surface: light passes straight through (Mitsuba's `null`).
    Null,
    /// A thin linear polariser (Mitsuba's `polarizer`): transmission axis turned by `angle`,
    /// `transmittance` in [0, 1] on polarised light along it; not `polarizing`, a grey filter of
    /// ½·transmittance.
    Polariser {
        angle: Angle,
        transmittance: f64,
        polarizing: bool,
    },
    /// A thin linear retarder (Mitsuba's `retarder`): fast axis turned by `angle`, retardance
    /// (the phase delay of the slow axis) `retardance` at normal incidence.
    Retarder {
        angle: Angle,
        retardance: Angle,
    },
    /// A partly transparent surface (Mitsuba's `mask`): `opacity` (a number or a grey image)
    /// of the nested material, the rest straight through.
    Mask {
        opacity: TextureDesc,
        inner: Box<MaterialKind>,
    },
    /// A blend (Mitsuba's `blendbsdf`): (1 − weight)·f_a + weight·f_b, weight a number or a
    /// grey image in [0, 1].
    Blend {
        weight: TextureDesc,
        a: Box<MaterialKind>,
        b: Box<MaterialKind>,
    },
    /// Mitsuba's `normalmap`: `map` an image of raw triples, each a local normal encoded as
    /// (n + 1)/2, around the nested material; pbrt-v4's `normalmap` when `pbrt` (evaluated as
    /// pbrt-v4 does, as `BumpMap`'s `pbrt`).
    NormalMap {
        map: TextureDesc,
        inner: Box<MaterialKind>,
        pbrt: bool,
    },
    /// Mitsuba's `bumpmap`: a grey `height` image times `scale` displacing the shading normal
    /// of the nested material; pbrt-v4's `displacement` when `pbrt` (evaluated as pbrt-v4 does:
    /// see `crate::material::BumpMap::pbrt`).
    BumpMap {
        height: TextureDesc,
        scale: f64,
        inner: Box<MaterialKind>,
        pbrt: bool,
    },
    /// A conductor or dielectric (`inner`) with textured parameters: roughness [α_u, α_v] as
    /// grey textures (rough materials), and factors on the reflected and transmitted lobes
    /// (Mitsuba's `specular_reflectance`, `specular_transmittance`).
    Textured {
        alpha: Option<Box<[TextureDesc; 2]>>,
        /// The alpha textures hold pbrt-v4's roughness r, α = √r (its `remaproughness`).
        remap: bool,
        reflectance: TextureDesc,
        transmittance: TextureDesc,
        inner: Box<MaterialKind>,
    },
    /// A sheet of negligible thickness (Mitsuba's `thindielectric`), indices as a dielectric's.
    ThinDielectric {
        int_ior: f64,
        exterior_ior: f64,
    },
    /// A diffuse base under a dielectric coating (Mitsuba's `plastic`, and `roughplastic` when
    /// `roughness` is given; see `crate::material::Plastic`).
    Plastic {
        diffuse: TextureDesc,
        /// A factor on the coating's reflection (Mitsuba's `specular_reflectance`), 1 by default.
        specular: f64,
        int_ior: f64,
        exterior_ior: f64,
        nonlinear: bool,
        roughness: Option<f64>,
        distribution: Distribution,
    },
    /// Mitsuba's polarising plastic `pplastic` (see `crate::material::PPlastic`): a rough
    /// specular reflection of roughness [α_u, α_v] plus a diffuse term under two Fresnel
    /// transmissions.
    PPlastic {
        diffuse: TextureDesc,
        /// A factor on the specular lobe (Mitsuba's `specular_reflectance`), 1 by default.
        specular: f64,
        int_ior: f64,
        exterior_ior: f64,
        roughness: [f64; 2],
        distribution: Distribution,
    },
    /// Mitsuba's `measured_polarized`: a measured polarimetric BRDF table (Baek et al. 2020),
    /// importance-sampled by GGX of roughness `alpha_sample` (α) mixed with a cosine lobe; at
    /// the fixed `wavelength` (nm) for every wavelength if given.
    MeasuredPolarized {
        table: PbsdfTable,
        alpha_sample: f64,
        wavelength: Option<f64>,
    },
    /// pbrt-v4's and Mitsuba's `measured`: an RGL measured BRDF (Dupuy & Jakob 2018), shared
    /// by every material reading the same file.
    /// `jacobian`: whether `spectra` is multiplied by D/(4σ) (pbrt-v4 always; Mitsuba 3 as
    /// the file's flag says).
    Measured {
        table: std::sync::Arc<RglTable>,
        jacobian: bool,
    },
    /// A smooth dielectric or a conductor under thin-film layers (`coating = [...]`), the
    /// layers listed from the outside in.
    Coated {
        layers: Vec<CoatingLayerDesc>,
        inner: Box<MaterialKind>,
    },
    /// A free-standing coherent film in a medium of index `exterior_ior` (a soap bubble's wall).
    ThinFilm {
        layers: Vec<CoatingLayerDesc>,
        exterior_ior: f64,
    },
    /// Mitsuba's `principled` or `principledthin` (see `crate::material::Principled`).
    Principled(Box<PrincipledDesc>),
    /// Mitsuba's `hair` (see `crate::material::Hair`).
    Hair(Box<HairDesc>),
    /// pbrt-v4's `coateddiffuse` and `coatedconductor` (see `crate::material::Layered`).
    Layered(Box<LayeredDesc>),
    /// pbrt-v4's `diffusetransmission`: Lambertian reflection and transmission (see
    /// `crate::material::DiffuseTransmission`), dimensionless, each clamped to [0, 1].
    DiffuseTransmission {
        reflectance: TextureDesc,
        transmittance: TextureDesc,
    },
}

/// A dielectric coating over a base, with a slab between them (pbrt-v4's layered materials).
#[derive(Clone, Debug)]
pub struct LayeredDesc {
    /// None: a Lambertian base of `reflectance`; Some: a conductor of this index (None inside:
    /// of the index pbrt-v4 makes of `reflectance`) and roughness α [α_u, α_v] (None: smooth).
    pub conductor: Option<(Option<ComplexIor>, Option<[f64; 2]>)>,
    /// The diffuse base's reflectance, or the conductor's r.
    pub reflectance: TextureDesc,
    /// The coating's index and roughness α (None: smooth).
    pub eta: Ior,
    pub roughness: Option<[f64; 2]>,
    /// The coating's roughness as grey textures [u, v] in place of `roughness`, and whether
    /// they hold pbrt-v4's r (α = √r) rather than α.
    pub roughness_texture: Option<(Box<[TextureDesc; 2]>, bool)>,
    /// The slab's optical thickness (σₜ = 1), albedo and Henyey–Greenstein g.
    pub thickness: f64,
    pub albedo: TextureDesc,
    pub g: f64,
    /// pbrt-v4's `maxdepth` and `nsamples`.
    pub max_depth: u32,
    pub n_samples: u32,
    /// Weigh the exit's second estimate as pbrt-v4 does (biased; see
    /// `crate::material::Layered::pbrt_exit_weight`): false from every reader.
    pub pbrt_exit_weight: bool,
}

/// The parameters of a hair fibre.
#[derive(Clone, Debug)]
pub struct HairDesc {
    pub absorption: HairAbsorption,
    /// Index of the fibre relative to the outside.
    pub eta: f64,
    /// Longitudinal and azimuthal roughness β_m, β_n, in (0, 1].
    pub roughness: [f64; 2],
    /// Tilt of the cuticle's scales.
    pub scale_tilt: Angle,
    /// Read as pbrt-v4's `hair` (`crate::material::Hair::with_pbrt`): its offset across the
    /// fibre from the surface's v, its local frame and its I₀.
    pub pbrt: bool,
}

/// How a fibre absorbs, per fibre radius (dimensionless).
#[derive(Clone, Debug)]
pub enum HairAbsorption {
    /// Concentrations of eumelanin and pheomelanin (d'Eon et al. 2011's per-radius units).
    Pigments { eumelanin: f64, pheomelanin: f64 },
    /// σₐ itself, times `scale`.
    Sigma {
        sigma_a: crate::spectrum::Spectrum,
        scale: f64,
    },
}

/// The parameters of a principled material, each a texture (scalar ones grey); a lobe's
/// parameter that is `None` was not given (or given as 0), and the lobe is absent.
#[derive(Clone, Debug)]
pub struct PrincipledDesc {
    /// A reflectance.
    pub base_color: TextureDesc,
    pub roughness: TextureDesc,
    pub anisotropic: Option<TextureDesc>,
    pub spec_trans: Option<TextureDesc>,
    pub metallic: Option<TextureDesc>,
    pub clearcoat: Option<TextureDesc>,
    pub clearcoat_gloss: TextureDesc,
    pub sheen: Option<TextureDesc>,
    pub sheen_tint: Option<TextureDesc>,
    pub flatness: Option<TextureDesc>,
    pub spec_tint: Option<TextureDesc>,
    /// The sheet's diffuse transmission, in [0, 2].
    pub diff_trans: Option<TextureDesc>,
    /// Index of the inside (the sheet) relative to the outside.
    pub eta: f64,
    /// Sampling rates (see `crate::material::Principled::rates`).
    pub rates: [f64; 4],
    pub thin: bool,
}

/// One thin-film layer: its material and thickness.
#[derive(Clone, Debug, PartialEq)]
pub struct CoatingLayerDesc {
    pub medium: crate::optics::thin_film::LayerIndex,
    pub thickness: Length,
}

/// A pBSDF table as Mitsuba's `.pbsdf` files hold it: Mueller matrices of the BRDF (sr⁻¹, no
/// cosine) on a grid of Rusinkiewicz angles φ_d, θ_d, θ_h (radians, each strictly increasing)
/// and wavelengths (nm), `m` in C order φ_d × θ_d × θ_h × λ × 4 × 4 (row, then column), in the
/// basis s = ω_light × ω_view on both beams.
#[derive(Clone, Debug, PartialEq)]
pub struct PbsdfTable {
    pub phi_d: Vec<f32>,
    pub theta_d: Vec<f32>,
    pub theta_h: Vec<f32>,
    pub wavelengths: Vec<f32>,
    pub m: std::sync::Arc<Vec<f32>>,
}

/// An RGL measured BRDF as its `.bsdf` file holds it (`loader::mitsuba::rgl`): the grids of
/// θ_i and φ_i (radians) and wavelengths (nm), and tables in C order, each `[columns, rows]`
/// in its `_size`: `ndf` and `sigma` (on u of the half vector and of ω_o), `vndf` (φ_i × θ_i
/// slices), `luminance` (φ_i × θ_i slices of `sample_size`) and `spectra` (φ_i × θ_i × λ
/// slices of `sample_size`, dimensionless reflectance factors).
#[derive(Clone, Debug, PartialEq)]
pub struct RglTable {
    /// The file's `jacobian` flag: whether `spectra` holds R of f = R·D/(4σ cos θ_i) (set) or
    /// f·cos θ_i itself.
    pub jacobian: bool,
    pub theta_i: Vec<f32>,
    pub phi_i: Vec<f32>,
    pub wavelengths: Vec<f32>,
    pub ndf: Vec<f32>,
    pub ndf_size: [usize; 2],
    pub sigma: Vec<f32>,
    pub sigma_size: [usize; 2],
    pub vndf: Vec<f32>,
    pub vndf_size: [usize; 2],
    pub luminance: Vec<f32>,
    pub sample_size: [usize; 2],
    pub spectra: Vec<f32>,
}

#[derive(Clone, Debug)]
pub struct MaterialDesc {
    pub name: String,
    pub kind: MaterialKind,
    pub loc: Loc,
}
