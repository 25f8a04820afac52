//! Daylight: the sun's position from place and time (`solar.rs`, NOAA's algorithm) and the CIE
//! sky luminance distributions (`sky.rs`, CIE S 011/E:2003 and the Moon–Spencer overcast sky).
//! Pure functions of angles; the build step bakes a sky into an environment map.

pub mod sky;
pub mod solar;

/// The world direction (unit) toward a point of the sky at zenith angle `zenith` and azimuth
/// `azimuth` (deg, clockwise from north seen from above), for unit `up` and a `north`
/// perpendicular to it: up·cos Z + sin Z·(north·cos A + east·sin A), east = north × up.
pub fn sky_direction(zenith: f64, azimuth: f64, up: [f64; 3], north: [f64; 3]) -> [f64; 3] {
    let (z, a) = (zenith.to_radians(), azimuth.to_radians());
    let east = [
        north[1] * up[2] - north[2] * up[1],
        north[2] * up[0] - north[0] * up[2],
        north[0] * up[1] - north[1] * up[0],
    ];
    [0, 1, 2].map(|k| up[k] * z.cos() + z.sin() * (north[k] * a.cos() + east[k] * a.sin()))
}

#[cfg(test)]
mod tests {
    #[test]
    fn azimuth_is_clockwise_from_north() {
        // y up, north −z: east is +x
        let d = super::sky_direction(90.0, 90.0, [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]);
        assert!((d[0] - 1.0).abs() < 1e-12 && d[1].abs() < 1e-12 && d[2].abs() < 1e-12);
        let d = super::sky_direction(0.0, 123.0, [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]);
        assert!((d[1] - 1.0).abs() < 1e-12);
    }
}
