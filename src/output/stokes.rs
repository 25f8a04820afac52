//! A polarised render's EXR channels: the Stokes components S1–S3, the degree and angle of
//! linear polarisation, and a polarisation camera's analyser images.

use super::Image;

/// A polarised render's channels (none for an unpolarised image), S0 being the image itself:
/// `S1.X`, `S1.Y`, `S1.Z`, `S1.R`, `S1.G`, `S1.B` and the same for `S2` and `S3` (the Stokes
/// components as XYZ and linear sRGB on the image's scale; frame: the basis vector points
/// right in the image, S1 > 0 horizontal, S2 > 0 polarised along the diagonal up and to the
/// right, S3 > 0 right-circular, Mitsuba 3's `stokes` conventions); `DoLP` (degree of linear
/// polarisation of the luminance, √(S1² + S2²)/S0 of Y, 0 where Y is 0); `AoLP` (its angle in
/// degrees, counter-clockwise from the image's horizontal, in (−90, 90]); `pol0.Y`, `pol45.Y`,
/// `pol90.Y`, `pol135.Y` (the luminance behind an ideal linear analyser at that angle, as a
/// polarisation camera's four sub-pixels see it: ½(S0 + S1 cos 2θ + S2 sin 2θ)); in a
/// spectral file also `S1.<λ>nm`, `S2.<λ>nm`, `S3.<λ>nm` per bin (W·m⁻²·sr⁻¹·nm⁻¹), the
/// polarised form of the spectral layout (Fichet et al. 2021); with the header text stating
/// them.
pub fn stokes_channels(img: &Image) -> (Vec<(String, Vec<f32>)>, String) {
    if img.stokes.is_empty() {
        return (Vec::new(), String::new());
    }
    let n = img.width * img.height;
    let mut out = Vec::new();
    for c in 0..3 {
        let rgb: Vec<[f64; 3]> = (0..n)
            .map(|i| crate::colour::spaces::xyz_to_srgb(img.stokes[i][c].map(f64::from)))
            .collect();
        for (a, name) in ["X", "Y", "Z"].iter().enumerate() {
            let v = (0..n).map(|i| img.stokes[i][c][a]).collect();
            out.push((format!("S{}.{name}", c + 1), v));
        }
        for (a, name) in ["R", "G", "B"].iter().enumerate() {
            let v = rgb.iter().map(|p| p[a] as f32).collect();
            out.push((format!("S{}.{name}", c + 1), v));
        }
    }
    let y = |i: usize| {
        let s = &img.stokes[i];
        (img.xyz[i][1] as f64, s[0][1] as f64, s[1][1] as f64)
    };
    let dolp = (0..n)
        .map(|i| {
            let (s0, s1, s2) = y(i);
            if s0 > 0.0 {
                (s1.hypot(s2) / s0) as f32
            } else {
                0.0
            }
        })
        .collect();
    let aolp = (0..n)
        .map(|i| {
            let (_, s1, s2) = y(i);
            let a = 0.5 * s2.atan2(s1).to_degrees();
            (if a <= -90.0 { a + 180.0 } else { a }) as f32
        })
        .collect();
    // a spectral file's polarised channels (the layout's S1–S3 beside its S0)
    if let Some(bins) = &img.bins
        && !img.stokes_spectral.is_empty()
    {
        for k in 0..3 {
            for b in 0..bins.count {
                let name = crate::image_io::stokes_channel_name(k + 1, bins.centre(b));
                out.push((name, img.stokes_spectral[k * bins.count + b].clone()));
            }
        }
    }
    out.push(("DoLP".into(), dolp));
    out.push(("AoLP".into(), aolp));
    for deg in [0u32, 45, 90, 135] {
        let (s, c) = (2.0 * (deg as f64).to_radians()).sin_cos();
        let v = (0..n)
            .map(|i| {
                let (s0, s1, s2) = y(i);
                (0.5 * (s0 + s1 * c + s2 * s)) as f32
            })
            .collect();
        out.push((format!("pol{deg}.Y"), v));
    }
    let text = "S1.*,S2.*,S3.*: Stokes components as X,Y,Z and R,G,B on the image's scale (basis: \
                the image's horizontal; S1>0 horizontal, S2>0 +45deg (up-right), S3>0 right \
                circular); DoLP: degree of linear polarisation of Y (dimensionless); AoLP: its \
                angle in degrees, counter-clockwise from the horizontal; pol0.Y,pol45.Y,pol90.Y,\
                pol135.Y: Y behind an ideal linear analyser at that angle; S1.<l>nm,S2.<l>nm,\
                S3.<l>nm: the Stokes components per spectral bin in W.m^-2.sr^-1.nm^-1";
    (out, text.to_string())
}
