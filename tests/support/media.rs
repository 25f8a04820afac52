//! The scenes shared by the media tests (`tests/media.rs`, `tests/media_bdpt.rs`).

/// A ball (centre (0, 0.6, 0), radius 0.6) of a spectrally scattering and absorbing fog (σs 3 →
/// 0.5 m⁻¹ across the spectrum, σa 0.3 m⁻¹, Henyey–Greenstein g = 0.4) bounded by `boundary`
/// (the lines of a `[materials.boundary]` table), on a diffuse floor (reflectance 0.6, 8 m
/// square), lit by a square D65 lamp facing down: side `lamp_side` m, centred at `lamp_at`,
/// of radiance `lamp_radiance` W·m⁻²·sr⁻¹. Seen from (0, 1.2, −4), 48 × 48 pixels at `spp`.
pub fn fog_ball(
    boundary: &str,
    lamp_side: f64,
    lamp_at: [f64; 3],
    lamp_radiance: f64,
    spp: u32,
) -> String {
    let [x, y, z] = lamp_at;
    let scale = lamp_side / 2.0;
    format!(
        r#"
[camera]
eye = [0, 1.2, -4]
target = [0, 0.3, 0]
fov = "40 deg"
[film]
width = 48
height = 48
spp = {spp}
[integrator]
max_depth = 16
[media.fog]
sigma_s = {{ spectrum = {{ samples = [[360, 3.0], [830, 0.5]] }}, scale = "1 1/m" }}
sigma_a = "0.3 1/m"
phase = {{ type = "hg", g = 0.4 }}
[materials.boundary]
{boundary}
[materials.floor]
type = "diffuse"
reflectance = 0.6
[[shapes]]
type = "sphere"
center = [0, 0.6, 0]
radius = 0.6
material = "boundary"
interior = "fog"
[[shapes]]
type = "rectangle"
material = "floor"
transform = [{{ scale = 4 }}, {{ rotate = {{ axis = [1, 0, 0], angle = "-90 deg" }} }}]
[[shapes]]
type = "rectangle"
transform = [{{ scale = {scale} }}, {{ rotate = {{ axis = [1, 0, 0], angle = "90 deg" }} }}, {{ translate = [{x}, {y}, {z}] }}]
emission = {{ spectrum = "cie-d65", radiance = "{lamp_radiance} W/m^2/sr" }}
"#
    )
}
