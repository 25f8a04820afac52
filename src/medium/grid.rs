//! Volumes: a quantity that varies in space, as a constant spectrum or a voxel grid over the
//! unit cube of its own frame (Mitsuba's `constvolume` and `gridvolume`).
//!
//! A grid of `res` voxels covers [0, 1]³ of its frame with voxel centres at (i + ½)/res, and is
//! looked up by trilinear interpolation between the eight nearest centres, coordinates outside
//! wrapped by its [`Wrap`] (Mitsuba 3's `gridvolume` with `filter_type` trilinear and
//! `use_grid_bbox` false). A grid holds one value per voxel (the same at every wavelength) or
//! an RGB colour, kept as Jakob–Hanika sigmoid coefficients with a scale; a lookup
//! interpolates the eight corners' sigmoid spectra and, apart, their scales, and multiplies
//! the two (Mitsuba 3's spectral `gridvolume`, `interpolate_spectral`: values checked against
//! `mi.load_dict({"type": "gridvolume"}).eval` in the tests).

use std::sync::Arc;

use glam::{Mat4, Vec3};

use crate::spectrum::rgb2spec::SigmoidPolynomial;
use crate::spectrum::{SampledSpectrum, SampledWavelengths, Spectrum};
pub use crate::texture::Wrap;

/// A voxel grid. Values are dimensionless; a medium scales them.
#[derive(Clone, Debug)]
pub struct Grid {
    /// Voxels along x, y, z.
    pub res: [usize; 3],
    /// Per voxel, x fastest then y then z: one value (`rgb` false) or four, the sigmoid
    /// coefficients (for the normalised wavelength of [`SigmoidPolynomial`]) and the scale.
    data: Vec<f32>,
    rgb: bool,
    pub wrap: Wrap,
    /// The largest value any lookup can return, at any wavelength.
    max: f32,
}

impl Grid {
    /// A grid of `res` voxels from `values` (x fastest, then y, then z; `channels` per voxel,
    /// 1 or 3). Three channels are RGB colours, upsampled each with the unbounded sigmoid
    /// (scale 2·max(rgb), as Mitsuba's spectral variants do). Errors name what is wrong.
    pub fn new(
        res: [usize; 3],
        channels: usize,
        values: &[f32],
        wrap: Wrap,
    ) -> Result<Grid, String> {
        let n = res[0]
            .checked_mul(res[1])
            .and_then(|n| n.checked_mul(res[2]))
            .ok_or("the grid's size overflows")?;
        if n == 0 {
            return Err("the grid has no voxels".into());
        }
        if channels != 1 && channels != 3 {
            return Err(format!("a grid needs 1 or 3 channels, not {channels}"));
        }
        if values.len() != n * channels {
            return Err(format!(
                "{} values for {} × {} × {} voxels of {channels} channels",
                values.len(),
                res[0],
                res[1],
                res[2]
            ));
        }
        if let Some(v) = values.iter().find(|v| !v.is_finite() || **v < 0.0) {
            return Err(format!(
                "the grid holds {v}; values must be finite and not negative"
            ));
        }
        let (data, max) = if channels == 1 {
            let max = values.iter().copied().fold(0.0, f32::max);
            (values.to_vec(), max)
        } else {
            let mut data = Vec::with_capacity(n * 4);
            let mut max = 0.0f32;
            for rgb in values.chunks_exact(3) {
                let (c, scale) = upsample([rgb[0], rgb[1], rgb[2]]);
                data.extend_from_slice(&[c[0], c[1], c[2], scale]);
                max = max.max(scale);
            }
            (data, max)
        };
        Ok(Grid {
            res,
            data,
            rgb: channels == 3,
            wrap,
            max,
        })
    }

    /// An upper bound of every value a lookup returns.
    pub fn max(&self) -> f32 {
        self.max
    }

    /// The value at `p` in the grid's frame (the grid spans [0, 1]³), at the wavelengths `w`.
    #[inline]
    pub fn eval<const N: usize>(&self, p: Vec3, w: &SampledWavelengths<N>) -> SampledSpectrum<N> {
        let mut idx = [[0usize; 2]; 3];
        let mut frac = [0.0f32; 3];
        for a in 0..3 {
            let x = p[a] * self.res[a] as f32 - 0.5;
            let x0 = x.floor();
            frac[a] = x - x0;
            idx[a] = [
                self.wrap_index(x0 as i64, a),
                self.wrap_index(x0 as i64 + 1, a),
            ];
        }
        let mut value = SampledSpectrum::<N>::zero();
        let mut scale = 0.0f32;
        for corner in 0..8 {
            let (i, j, k) = (corner & 1, (corner >> 1) & 1, corner >> 2);
            let wgt = (if i == 1 { frac[0] } else { 1.0 - frac[0] })
                * (if j == 1 { frac[1] } else { 1.0 - frac[1] })
                * (if k == 1 { frac[2] } else { 1.0 - frac[2] });
            if wgt == 0.0 {
                continue;
            }
            let v = (idx[2][k] * self.res[1] + idx[1][j]) * self.res[0] + idx[0][i];
            if self.rgb {
                // Mitsuba's `interpolate_spectral`: the corners' sigmoid spectra and their
                // scales interpolated apart, then multiplied
                let d = &self.data[v * 4..v * 4 + 4];
                let poly = SigmoidPolynomial {
                    c: [d[0], d[1], d[2]],
                };
                for (out, &l) in value.0.iter_mut().zip(&w.lambda) {
                    *out += wgt * poly.eval(l);
                }
                scale += wgt * d[3];
            } else {
                scale += wgt * self.data[v];
            }
        }
        if self.rgb {
            value * scale
        } else {
            SampledSpectrum::splat(scale)
        }
    }

    fn wrap_index(&self, i: i64, axis: usize) -> usize {
        self.wrap.index(i, self.res[axis])
    }
}

/// The unbounded sigmoid upsampling of an RGB colour: the sRGB table's coefficients of
/// rgb/scale (looked up, not refined: a grid may hold millions of voxels) and the scale
/// 2·max(rgb) (0 for black).
fn upsample(rgb: [f32; 3]) -> ([f32; 3], f32) {
    let m = rgb[0].max(rgb[1]).max(rgb[2]);
    if m <= 0.0 {
        return (SigmoidPolynomial::constant(0.5).c, 0.0);
    }
    let scale = 2.0 * m;
    let poly = crate::spectrum::rgb2spec::srgb_table().lookup(rgb.map(|v| v / scale));
    (poly.c, scale)
}

/// A quantity in space: a spectrum everywhere, or a grid placed by a transform.
#[derive(Clone, Debug)]
pub enum Volume {
    Constant(Spectrum),
    Grid {
        grid: Arc<Grid>,
        /// World space (m) to the grid's frame.
        to_local: Mat4,
    },
}

impl Volume {
    /// The value at the world point `p` (m) at the wavelengths `w`.
    #[inline]
    pub fn eval<const N: usize>(&self, p: Vec3, w: &SampledWavelengths<N>) -> SampledSpectrum<N> {
        match self {
            Volume::Constant(s) => s.sample(w),
            Volume::Grid { grid, to_local } => grid.eval(to_local.transform_point3(p), w),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn w() -> SampledWavelengths<4> {
        SampledWavelengths {
            lambda: [450.0, 550.0, 600.0, 650.0],
            pdf: [1.0; 4],
        }
    }

    /// Trilinear between voxel centres: a ramp along x of 2 voxels is 0 at and left of the
    /// first centre (clamped), 1 at and right of the second, linear between.
    #[test]
    fn trilinear_between_centres() {
        let g = Grid::new([2, 1, 1], 1, &[0.0, 1.0], Wrap::Clamp).expect("valid");
        for (x, want) in [
            (0.0, 0.0),
            (0.25, 0.0),
            (0.5, 0.5),
            (0.625, 0.75),
            (0.75, 1.0),
            (1.0, 1.0),
        ] {
            let v = g.eval(Vec3::new(x, 0.5, 0.5), &w())[0];
            assert!((v - want).abs() < 1e-6, "x {x}: {v} vs {want}");
        }
        let r = Grid::new([2, 1, 1], 1, &[0.0, 1.0], Wrap::Repeat).expect("valid");
        // repeat: left of the first centre interpolates toward the last voxel
        assert!((r.eval(Vec3::new(0.0, 0.5, 0.5), &w())[0] - 0.5).abs() < 1e-6);
        assert_eq!(g.max(), 1.0);
    }

    #[test]
    fn sizes_must_agree() {
        assert!(Grid::new([2, 2, 2], 1, &[0.0; 7], Wrap::Clamp).is_err());
        assert!(Grid::new([2, 2, 2], 2, &[0.0; 16], Wrap::Clamp).is_err());
        assert!(Grid::new([1, 1, 1], 1, &[-1.0], Wrap::Clamp).is_err());
        assert!(Grid::new([1, 1, 1], 1, &[f32::NAN], Wrap::Clamp).is_err());
        assert!(Grid::new([usize::MAX, 2, 2], 1, &[0.0], Wrap::Clamp).is_err());
    }

    /// A one-voxel RGB grid reads as Mitsuba 3.9.1's spectral `gridvolume` does:
    /// `mi.load_dict({"type": "gridvolume", "grid": mi.VolumeGrid(rgb)}).eval(it)` at 450,
    /// 550, 600 and 650 nm (values printed by that call, `scalar_spectral`).
    #[test]
    fn rgb_voxels_read_as_mitsuba_reads_them() {
        for (rgb, want) in [
            ([1.0, 0.0, 0.5], [0.344663, 0.093027, 0.314746, 1.83349]),
            (
                [0.46364042, 0.0, 0.0],
                [0.00761938, 0.0244526, 0.143609, 0.853379],
            ),
            ([0.2, 0.4, 0.6], [0.582751, 0.384079, 0.282312, 0.19799]),
            ([2.0, 1.0, 0.5], [0.554706, 1.06129, 1.55149, 2.20087]),
        ] {
            let g = Grid::new([1, 1, 1], 3, &rgb, Wrap::Clamp).expect("valid");
            let v = g.eval(Vec3::splat(0.5), &w());
            for j in 0..4 {
                assert!(
                    (v[j] - want[j]).abs() < 0.01 * want[j].max(0.05),
                    "{rgb:?} at {} nm: {} vs Mitsuba {}",
                    w().lambda[j],
                    v[j],
                    want[j]
                );
            }
        }
    }

    /// Between two RGB voxels a lookup interpolates their sigmoid spectra and their scales
    /// apart and multiplies them, as Mitsuba 3.9.1 does: voxels (1, 0, 0.36021623) and
    /// (0.7711827, 0, 0) (the first two of mitsuba-data's `participating_media/textures/
    /// albedo.vol`), a quarter and half of the way, against `gridvolume.eval` there.
    #[test]
    fn rgb_lookups_between_voxels_follow_mitsuba() {
        let g = Grid::new(
            [2, 1, 1],
            3,
            &[1.0, 0.0, 0.36021623, 0.7711827, 0.0, 0.0],
            Wrap::Clamp,
        )
        .expect("valid");
        for (f, want) in [
            (0.25, [0.17124316, 0.07077627, 0.28755155, 1.7436707]),
            (0.5, [0.1120865, 0.05989007, 0.2715046, 1.6352564]),
        ] {
            let v = g.eval(Vec3::new((0.5 + f) / 2.0, 0.5, 0.5), &w());
            for j in 0..4 {
                assert!(
                    (v[j] - want[j]).abs() < 0.01 * want[j].max(0.05),
                    "{f} at {} nm: {} vs Mitsuba {}",
                    w().lambda[j],
                    v[j],
                    want[j]
                );
            }
        }
    }
}
