//! Mitsuba's `mesh_attribute` texture: a PLY mesh's per-vertex or per-face values at a hit,
//! bound to one mesh when the scene is built (`src/textures/mesh_attribute.cpp`,
//! `Mesh::interpolate_attribute` in `src/render/mesh.cpp`, Mitsuba 3.9.1).
//!
//! A vertex attribute is blended with the hit's barycentric weights; a face attribute is its
//! triangle's value. In spectral variants an attribute of three fields whose name contains
//! `color` is an RGB reflectance: each corner's RGB becomes Jakob–Hanika coefficients (the
//! same table as flat RGB reflectances) and the corners' *spectra* are blended ("the expansion
//! is nonlinear and therefore precedes the blend"); another three-field attribute gives the
//! luminance of its blended value, a one-field attribute its blended value, at every
//! wavelength. Everything is multiplied by `scale`.

use crate::geometry::shape::{Mesh, MeshAttribute};
use crate::spectrum::rgb2spec::{SigmoidPolynomial, srgb_table};
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// Rec. 709 luminance weights (Mitsuba's `luminance`).
const LUMINANCE: [f32; 3] = [0.212671, 0.715160, 0.072169];

/// An attribute of one mesh, per kept triangle and corner (as [`Mesh::indices`] stores them).
#[derive(Clone, Debug, PartialEq)]
pub struct AttributeTexture {
    /// The raw value at each corner: the attribute's fields, a one-field value in all three.
    raw: Vec<[[f32; 3]; 3]>,
    /// The corners' spectra of a colour attribute; empty otherwise.
    colour: Vec<[SigmoidPolynomial; 3]>,
    /// Whether the attribute has three fields (luminance when not a colour).
    three: bool,
    scale: f32,
    /// [`AttributeTexture::mean`] before `scale`, found once.
    mean: f32,
}

impl AttributeTexture {
    /// `attr` of `mesh` (read from the same file) times `scale`; an error if its count does
    /// not match the mesh's vertices or faces.
    pub fn new(attr: &MeshAttribute, mesh: &Mesh, scale: f32) -> Result<Self, String> {
        let d = attr.dim;
        let at = |k: usize| -> Result<[f32; 3], String> {
            let v = attr.values.get(k * d..(k + 1) * d).ok_or_else(|| {
                format!(
                    "attribute \"{}\" has too few values for the mesh",
                    attr.name
                )
            })?;
            Ok(if d == 3 {
                [v[0], v[1], v[2]]
            } else {
                [v[0]; 3]
            })
        };
        let mut raw = Vec::with_capacity(mesh.triangle_count());
        for (i, tri) in mesh.indices().iter().enumerate() {
            raw.push(if attr.per_face {
                [at(mesh.source_triangle(i) as usize)?; 3]
            } else {
                [
                    at(tri[0] as usize)?,
                    at(tri[1] as usize)?,
                    at(tri[2] as usize)?,
                ]
            });
        }
        let colour = if d == 3 && attr.name.contains("color") {
            let table = srgb_table();
            raw.iter().map(|c| c.map(|rgb| table.lookup(rgb))).collect()
        } else {
            Vec::new()
        };
        let mut t = Self {
            raw,
            colour,
            three: d == 3,
            scale: 1.0,
            mean: 0.0,
        };
        let third = [1.0 / 3.0; 3];
        let n = t.raw.len().max(1) as f32;
        t.mean = (0..t.raw.len() as u32)
            .map(|p| t.value(p, third))
            .sum::<f32>()
            / n;
        t.scale = scale;
        Ok(t)
    }

    /// The same attribute times `k` more.
    pub fn scaled(&self, k: f32) -> Self {
        Self {
            scale: self.scale * k,
            ..self.clone()
        }
    }

    /// Whether the attribute is an RGB reflectance (else the same at every wavelength).
    pub fn is_colour(&self) -> bool {
        !self.colour.is_empty()
    }

    /// The value at triangle `prim` with barycentric weights `b` for the wavelengths `w`.
    #[inline]
    pub fn sample<const N: usize>(
        &self,
        prim: u32,
        b: [f32; 3],
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        let Some(c) = self.colour.get(prim as usize) else {
            return SampledSpectrum::splat(self.value(prim, b));
        };
        let mut out = [0.0; N];
        for (k, o) in out.iter_mut().enumerate() {
            let l = w.lambda[k];
            *o = self.scale * (b[0] * c[0].eval(l) + b[1] * c[1].eval(l) + b[2] * c[2].eval(l));
        }
        SampledSpectrum(out)
    }

    /// One number at triangle `prim` with barycentric weights `b` (Mitsuba's `eval_1`): the
    /// blended value, or the luminance of a blended triple.
    #[inline]
    pub fn value(&self, prim: u32, b: [f32; 3]) -> f32 {
        let Some(c) = self.raw.get(prim as usize) else {
            return 0.0;
        };
        let v: [f32; 3] = std::array::from_fn(|j| b[0] * c[0][j] + b[1] * c[1][j] + b[2] * c[2][j]);
        self.scale
            * if self.three {
                LUMINANCE[0] * v[0] + LUMINANCE[1] * v[1] + LUMINANCE[2] * v[2]
            } else {
                v[0]
            }
    }

    /// The mean over triangles and corners of [`AttributeTexture::value`] (unweighted by
    /// area), for sampling weights.
    pub fn mean(&self) -> f32 {
        self.mean * self.scale
    }
}
