//! A pinhole that projects an image, the reciprocal of a perspective camera: Mitsuba 3's
//! `projector` (src/emitters/projector.cpp) and pbrt-v4's `projection` light
//! (`ProjectionLight`, src/pbrt/lights.cpp), which differ in how the image sets the intensity
//! ([`ProjectorLaw`]).

use super::bounds::LightBounds;
use glam::{Mat3, Vec2, Vec3};

use super::{EmissionPdf, EmissionSample, LightSample};
use crate::spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};
use crate::texture::Texture;

/// How a projector's image sets its intensity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProjectorLaw {
    /// Mitsuba 3: I = π · spectrum · image / cos³θ, so that a uniform image lights the plane
    /// z = 1 with uniform irradiance π · spectrum · image.
    PlaneIrradiance,
    /// pbrt-v4 (`ProjectionLight::I`): I = spectrum · image, so that a uniform image is a
    /// uniform intensity over the frustum.
    Intensity,
}

impl ProjectorLaw {
    /// The intensity per unit spectrum · image at cos θ from the axis, sr⁻¹·(unit of I).
    #[inline]
    fn factor(self, cos: f32) -> f32 {
        match self {
            ProjectorLaw::PlaneIrradiance => std::f32::consts::PI / (cos * cos * cos),
            ProjectorLaw::Intensity => 1.0,
        }
    }
}

/// A projector at `position` looking along its local +z (`frame`'s third column), its image
/// spanning 2·`tan_x` by 2·`tan_y` on the plane z = 1. A point at local (x, y, z), z > 0,
/// takes the image at uv = (½(1 − x/(z·tan_x)), ½(1 − y/(z·tan_y))) (Mitsuba's perspective
/// mapping: u grows toward local −x, v toward −y), and receives the intensity
///
/// I(ω) = π · spectrum(λ) · image(uv, λ) / cos³θ   (W·sr⁻¹·nm⁻¹),
///
/// θ from the axis, so that the plane z = 1 is lit with irradiance π · spectrum · image
/// ([`ProjectorLaw::PlaneIrradiance`]; pbrt-v4's law is I = spectrum · image). For a
/// Mitsuba scene the spectrum is the constant `scale` (measured: Mitsuba 3.9.1 projects a grey
/// image with X = Y = Z, not D65-shaped), the image a texture.
#[derive(Clone, Debug)]
pub struct ProjectorLight {
    pub position: Vec3,
    /// Columns: the projector's local x, y, z (the axis) in world space, orthonormal.
    pub frame: Mat3,
    pub tan_x: f32,
    pub tan_y: f32,
    pub image: Texture,
    /// W·sr⁻¹·nm⁻¹ per unit image value before the law's factor.
    pub spectrum: Spectrum,
    pub law: ProjectorLaw,
}

impl ProjectorLight {
    /// Bounds for the light tree: an emitter at its position, of every direction
    /// (conservative: its frustum is not bounded more tightly), with `phi` the power, W, of
    /// which the tree takes 4π times the mean intensity over the frustum's solid angle
    /// 4·asin(sin α·sin β) (α, β its half-angles): [`LightBounds::phi`] with the mean for the
    /// peak, which the image would only sharpen.
    pub fn bounds(&self, phi: f32) -> LightBounds {
        let (a, b) = (self.tan_x.atan(), self.tan_y.atan());
        let omega = 4.0 * (a.sin() * b.sin()).asin();
        LightBounds::point(self.position, LightBounds::phi_of(phi, omega))
    }

    /// The image coordinates of the local direction `d` (z > 0), or None outside the image.
    #[inline]
    fn uv(&self, d: Vec3) -> Option<Vec2> {
        if !(d.z > 0.0) {
            return None;
        }
        let uv = Vec2::new(
            0.5 * (1.0 - d.x / (d.z * self.tan_x)),
            0.5 * (1.0 - d.y / (d.z * self.tan_y)),
        );
        (uv.cmpge(Vec2::ZERO).all() && uv.cmple(Vec2::ONE).all()).then_some(uv)
    }

    /// Intensity toward the world direction `dir` (unit, from the projector), W·sr⁻¹·nm⁻¹.
    #[inline]
    pub fn intensity<const N: usize>(
        &self,
        dir: Vec3,
        w: &SampledWavelengths<N>,
    ) -> Option<SampledSpectrum<N>> {
        let d = self.frame.transpose() * dir;
        let uv = self.uv(d)?;
        Some(self.image.sample(uv, w) * self.spectrum.sample(w) * self.law.factor(d.z))
    }

    /// li = I(ω)/r² toward `p`; None outside the image.
    pub fn sample_li<const N: usize>(
        &self,
        p: Vec3,
        w: &SampledWavelengths<N>,
    ) -> Option<LightSample<N>> {
        super::point_like_sample(self.position, p, |wi| self.intensity(-wi, w))
    }

    /// The power, W, for `band` the spectrum's integral over the band: Mitsuba's law through
    /// the image on the plane z = 1, π·band·mean(image)·area; pbrt-v4's over the frustum's
    /// solid angle, band·mean(image)·4·asin(sin α·sin β) (the image's mean over its texels
    /// standing for its mean over solid angle).
    pub fn power(&self, band: f64) -> f64 {
        let mean = self.image.mean() as f64;
        match self.law {
            ProjectorLaw::PlaneIrradiance => {
                std::f64::consts::PI * band * mean * self.image_area() as f64
            }
            ProjectorLaw::Intensity => {
                let (a, b) = (self.tan_x.atan() as f64, self.tan_y.atan() as f64);
                band * mean * 4.0 * (a.sin() * b.sin()).asin()
            }
        }
    }

    /// Area of the image on the plane z = 1, m² per m² of distance.
    pub fn image_area(&self) -> f32 {
        4.0 * self.tan_x * self.tan_y
    }

    /// A particle (light tracing, `bdpt`): a point uniform on the image plane z = 1 (u in
    /// [0, 1)², which is also its image coordinate) gives the direction, with
    /// pdf_dir = 1/(area·cos³θ) sr⁻¹; `le` is the intensity there (its [`ProjectorLaw`]).
    pub fn sample_le<const N: usize>(
        &self,
        w: &SampledWavelengths<N>,
        u: Vec2,
    ) -> EmissionSample<N> {
        let d = Vec3::new(
            (1.0 - 2.0 * u.x) * self.tan_x,
            (1.0 - 2.0 * u.y) * self.tan_y,
            1.0,
        )
        .normalize();
        let cos3 = d.z * d.z * d.z;
        let le = self.image.sample(u, w) * self.spectrum.sample(w) * self.law.factor(d.z);
        EmissionSample::from_point(
            self.position,
            self.frame * d,
            le,
            1.0 / (self.image_area() * cos3),
        )
    }

    /// Densities of [`ProjectorLight::sample_le`] for the world direction `dir` (unit): a delta
    /// position (0) and 1/(area·cos³θ) inside the image, else 0.
    pub fn pdf_le(&self, dir: Vec3) -> EmissionPdf {
        let d = self.frame.transpose() * dir;
        let dir = match self.uv(d) {
            Some(_) => 1.0 / (self.image_area() * d.z * d.z * d.z),
            None => 0.0,
        };
        EmissionPdf { pos: 0.0, dir }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A projector at the origin along +z, of half-angle tangents 0.5 × 0.25, a uniform image
    /// of 2 and a constant `spectrum`.
    fn projector(spectrum: f32, law: ProjectorLaw) -> ProjectorLight {
        ProjectorLight {
            position: Vec3::ZERO,
            frame: Mat3::IDENTITY,
            tan_x: 0.5,
            tan_y: 0.25,
            image: Spectrum::Constant(2.0).into(),
            spectrum: Spectrum::Constant(spectrum),
            law,
        }
    }

    fn waves() -> SampledWavelengths<4> {
        SampledWavelengths {
            lambda: [550.0; 4],
            pdf: [1.0; 4],
        }
    }

    /// A uniform image lights the plane z = 1 with irradiance π·spectrum everywhere inside the
    /// image: E = I cos θ / r² with r = 1/cos θ, I = π/cos³θ.
    #[test]
    fn uniform_image_lights_its_plane_uniformly() {
        let l = projector(1.0, ProjectorLaw::PlaneIrradiance);
        let w = waves();
        for (x, y) in [(0.0, 0.0), (0.4, 0.2), (-0.49, -0.24)] {
            let p = Vec3::new(x, y, 1.0);
            let s = l.sample_li(p + Vec3::ZERO, &w).expect("inside the image");
            let e = s.li.0[0] * (-s.wi).z;
            assert!(
                (e - 2.0 * std::f32::consts::PI).abs() < 1e-4,
                "({x}, {y}): E = {e}"
            );
        }
        assert!(
            l.sample_li(Vec3::new(0.6, 0.0, 1.0), &w).is_none(),
            "outside"
        );
        assert!(
            l.sample_li(Vec3::new(0.0, 0.0, -1.0), &w).is_none(),
            "behind"
        );
    }

    /// pbrt-v4's law: a uniform image is a uniform intensity, so the plane z = 1 gets
    /// E = I cos³θ; and a particle's weight le/pdf_dir integrates to the power I·Ω.
    #[test]
    fn pbrt_law_is_uniform_intensity() {
        let l = projector(1.5, ProjectorLaw::Intensity);
        let w = waves();
        for (x, y) in [(0.0, 0.0), (0.4, 0.2), (-0.49, -0.24)] {
            let p = Vec3::new(x, y, 1.0);
            let s = l.sample_li(p, &w).expect("inside the image");
            let cos = 1.0 / p.length();
            let e = s.li.0[0] * (-s.wi).z;
            assert!(
                (e - 3.0 * cos * cos * cos).abs() < 1e-4,
                "({x}, {y}): E = {e}"
            );
        }
        // Σ le/pdf over stratified samples → I·Ω with Ω = 4·asin(sin α·sin β)
        let n = 256;
        let mut sum = 0.0f64;
        for i in 0..n {
            for j in 0..n {
                let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                let e = l.sample_le(&w, u);
                let pdf = l.pdf_le(e.d).dir;
                sum += (e.le.0[0] / pdf) as f64;
            }
        }
        let omega = 4.0 * ((0.5f64.atan().sin()) * (0.25f64.atan().sin())).asin();
        let got = sum / (n * n) as f64;
        assert!(
            (got / (3.0 * omega) - 1.0).abs() < 1e-3,
            "{got} vs {}",
            3.0 * omega
        );
    }
}
