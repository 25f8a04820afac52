//! Textures made of textures: pbrt-v4's `scale` (a product) and `mix` (a blend by a grey
//! amount), for reflectances, masks and bump heights alike.

use glam::{Vec2, Vec3};

use super::Texture;
use crate::spectrum::{SampledSpectrum, SampledWavelengths};

/// `tex` × `scale`, per wavelength (pbrt-v4's `ScaledTexture`); dimensionless factors, or the
/// product in `tex`'s unit.
#[derive(Clone, Debug, PartialEq)]
pub struct Scaled {
    pub tex: Texture,
    pub scale: Texture,
}

/// (1 − t)·`a` + t·`b` with t = `amount` at the point (pbrt-v4's `MixTexture`; t is read at
/// the hero wavelength, and is a grey texture where the reader builds one).
#[derive(Clone, Debug, PartialEq)]
pub struct Mix {
    pub a: Texture,
    pub b: Texture,
    pub amount: Texture,
}

/// A grey texture's value at `uv` (read at 550 nm), for gradients.
fn grey(t: &Texture, uv: Vec2) -> f32 {
    let w = SampledWavelengths::<1> {
        lambda: [550.0],
        pdf: [1.0],
    };
    t.sample(uv, &w).0[0]
}

impl Scaled {
    #[inline]
    pub fn sample<const N: usize>(
        &self,
        uv: Vec2,
        p: Vec3,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        self.tex.sample_p(uv, p, w) * self.scale.sample_p(uv, p, w)
    }

    /// ∇(tex·scale) = ∇tex·scale + tex·∇scale, for grey textures.
    pub fn gradient(&self, uv: Vec2) -> Vec2 {
        self.tex.gradient(uv) * grey(&self.scale, uv)
            + self.scale.gradient(uv) * grey(&self.tex, uv)
    }

    pub fn mean(&self) -> f32 {
        self.tex.mean() * self.scale.mean()
    }
}

impl Mix {
    #[inline]
    pub fn sample<const N: usize>(
        &self,
        uv: Vec2,
        p: Vec3,
        w: &SampledWavelengths<N>,
    ) -> SampledSpectrum<N> {
        let t = self.amount.sample_p(uv, p, w).0[0];
        self.a.sample_p(uv, p, w) * (1.0 - t) + self.b.sample_p(uv, p, w) * t
    }

    /// ∇((1 − t)a + t·b) = (1 − t)∇a + t∇b + (b − a)∇t, for grey textures.
    pub fn gradient(&self, uv: Vec2) -> Vec2 {
        let t = grey(&self.amount, uv);
        self.a.gradient(uv) * (1.0 - t)
            + self.b.gradient(uv) * t
            + self.amount.gradient(uv) * (grey(&self.b, uv) - grey(&self.a, uv))
    }

    /// The mean of the blend with the mean amount (exact when the amount is uniform).
    pub fn mean(&self) -> f32 {
        let t = self.amount.mean();
        (1.0 - t) * self.a.mean() + t * self.b.mean()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::Spectrum;

    #[test]
    fn scale_multiplies_and_mix_interpolates() {
        let c = |x: f32| Texture::Uniform(Spectrum::Constant(x));
        let w = SampledWavelengths::<2> {
            lambda: [450.0, 650.0],
            pdf: [1.0; 2],
        };
        let s = Scaled {
            tex: c(0.4),
            scale: c(0.5),
        };
        assert_eq!(s.sample(Vec2::ZERO, Vec3::ZERO, &w).0, [0.2, 0.2]);
        assert!((s.mean() - 0.2).abs() < 1e-6);
        let m = Mix {
            a: c(0.2),
            b: c(0.6),
            amount: c(0.25),
        };
        assert!((m.sample(Vec2::ZERO, Vec3::ZERO, &w).0[1] - 0.3).abs() < 1e-6);
        assert!((m.mean() - 0.3).abs() < 1e-6);
        assert_eq!(m.gradient(Vec2::ZERO), Vec2::ZERO);
    }
}
