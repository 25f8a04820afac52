//! The sun's position from place and time: NOAA's "General Solar Position Calculations"
//! (the NOAA Solar Calculator spreadsheet, gml.noaa.gov/grad/solcalc/calcdetails.html, after
//! Meeus, *Astronomical Algorithms*), with its standard-atmosphere refraction. NOAA states
//! 0.01° for 1800–2100 at latitudes within ±72°; `tests/daylight.rs` measures it against NREL's
//! SPA (Reda & Andreas 2004, via pvlib) at 14 instants: within 0.012°.
//!
//! Angles in degrees; azimuth clockwise from north; longitude east-positive; time in UTC.

/// An instant in UTC: civil date and time of day.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UtcTime {
    pub year: i32,
    pub month: u32,
    pub day: u32,
    /// Seconds since midnight UTC (may be negative or ≥ 86400 after a zone offset; the Julian
    /// day absorbs it).
    pub seconds: f64,
}

impl UtcTime {
    /// Parses ISO 8601 `YYYY-MM-DDTHH:MM[:SS[.s]]` followed by `Z` or an offset `±HH:MM`
    /// (required: a local time without a zone is ambiguous).
    pub fn parse(s: &str) -> Result<Self, String> {
        let bad = || {
            format!(
                "\"{s}\": expected an ISO 8601 time with a zone, e.g. \"2026-06-21T12:00:00Z\" or \"2026-06-21T14:00+02:00\""
            )
        };
        let s = s.trim();
        let (date, rest) = s.split_once(['T', ' ']).ok_or_else(bad)?;
        let d: Vec<&str> = date.split('-').collect();
        if d.len() != 3 {
            return Err(bad());
        }
        let year: i32 = d[0].parse().map_err(|_| bad())?;
        let month: u32 = d[1].parse().map_err(|_| bad())?;
        let day: u32 = d[2].parse().map_err(|_| bad())?;
        let (time, offset) = if let Some(t) = rest.strip_suffix('Z') {
            (t, 0.0)
        } else if let Some(i) = rest.rfind(['+', '-']) {
            let (t, z) = rest.split_at(i);
            let sign = if z.starts_with('-') { -1.0 } else { 1.0 };
            let (h, m) = z[1..].split_once(':').ok_or_else(bad)?;
            let h: f64 = h.parse().map_err(|_| bad())?;
            let m: f64 = m.parse().map_err(|_| bad())?;
            if !(0.0..=14.0).contains(&h) || !(0.0..60.0).contains(&m) {
                return Err(bad());
            }
            (t, sign * (h * 3600.0 + m * 60.0))
        } else {
            return Err(bad());
        };
        let t: Vec<&str> = time.split(':').collect();
        if !(2..=3).contains(&t.len()) {
            return Err(bad());
        }
        let hh: f64 = t[0].parse().map_err(|_| bad())?;
        let mm: f64 = t[1].parse().map_err(|_| bad())?;
        let ss: f64 = t.get(2).map_or(Ok(0.0), |x| x.parse()).map_err(|_| bad())?;
        let days_in = match month {
            1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
            4 | 6 | 9 | 11 => 30,
            2 if (year % 4 == 0 && year % 100 != 0) || year % 400 == 0 => 29,
            2 => 28,
            _ => 0,
        };
        if !(1..=days_in).contains(&day)
            || !(0.0..24.0).contains(&hh)
            || !(0.0..60.0).contains(&mm)
            || !(0.0..61.0).contains(&ss)
            || !(1000..=9999).contains(&year)
        {
            return Err(bad());
        }
        Ok(Self {
            year,
            month,
            day,
            seconds: hh * 3600.0 + mm * 60.0 + ss - offset,
        })
    }

    /// Julian day (UT).
    pub fn julian_day(&self) -> f64 {
        // days from the civil date (Howard Hinnant's days_from_civil), then JD of 1970-01-01
        let y = self.year as i64 - (self.month <= 2) as i64;
        let era = y.div_euclid(400);
        let yoe = y - era * 400;
        let m = self.month as i64;
        let doy = (153 * (m + if m > 2 { -3 } else { 9 }) + 2) / 5 + self.day as i64 - 1;
        let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
        let days = era * 146_097 + doe - 719_468;
        2_440_587.5 + days as f64 + self.seconds / 86_400.0
    }
}

/// The sun seen from a place at a time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunPosition {
    /// Zenith angle without refraction, deg.
    pub zenith_true: f64,
    /// Zenith angle as seen, refracted by the NOAA standard atmosphere, deg.
    pub zenith: f64,
    /// Azimuth clockwise from north, deg in [0, 360).
    pub azimuth: f64,
}

/// NOAA's solar position (see the module doc) at `latitude`, `longitude` (deg, east positive).
pub fn sun_position(latitude: f64, longitude: f64, t: UtcTime) -> SunPosition {
    let (r, d) = (f64::to_radians, f64::to_degrees);
    let jd = t.julian_day();
    let tc = (jd - 2_451_545.0) / 36_525.0;
    let l0 = (280.46646 + tc * (36000.76983 + 0.0003032 * tc)).rem_euclid(360.0);
    let m = 357.52911 + tc * (35999.05029 - 0.0001537 * tc);
    let e = 0.016_708_634 - tc * (0.000_042_037 + 0.000_000_126_7 * tc);
    let c = r(m).sin() * (1.914602 - tc * (0.004817 + 0.000014 * tc))
        + r(2.0 * m).sin() * (0.019993 - 0.000101 * tc)
        + r(3.0 * m).sin() * 0.000289;
    let true_long = l0 + c;
    let omega = 125.04 - 1934.136 * tc;
    let app_long = true_long - 0.00569 - 0.00478 * r(omega).sin();
    let eps0 =
        23.0 + (26.0 + (21.448 - tc * (46.815 + tc * (0.00059 - 0.001813 * tc))) / 60.0) / 60.0;
    let eps = eps0 + 0.00256 * r(omega).cos();
    let decl = d((r(eps).sin() * r(app_long).sin()).asin());
    let y = r(eps / 2.0).tan().powi(2);
    let eot = 4.0
        * d(y * r(2.0 * l0).sin() - 2.0 * e * r(m).sin()
            + 4.0 * e * y * r(m).sin() * r(2.0 * l0).cos()
            - 0.5 * y * y * r(4.0 * l0).sin()
            - 1.25 * e * e * r(2.0 * m).sin());
    // true solar time, minutes, and the hour angle (positive in the afternoon)
    let minutes = (jd + 0.5).rem_euclid(1.0) * 1440.0;
    let tst = (minutes + eot + 4.0 * longitude).rem_euclid(1440.0);
    let ha = if tst / 4.0 < 0.0 {
        tst / 4.0 + 180.0
    } else {
        tst / 4.0 - 180.0
    };
    let (phi, delta, h) = (r(latitude), r(decl), r(ha));
    let cos_z = (phi.sin() * delta.sin() + phi.cos() * delta.cos() * h.cos()).clamp(-1.0, 1.0);
    let zenith_true = d(cos_z.acos());
    // the azimuth in a form without NOAA's division by sin Z cos φ (equal elsewhere)
    let azimuth =
        d((-h.sin() * delta.cos())
            .atan2(delta.sin() * phi.cos() - delta.cos() * phi.sin() * h.cos()))
        .rem_euclid(360.0);
    let elev = 90.0 - zenith_true;
    let te = r(elev).tan();
    let refraction_arcsec = if elev > 85.0 {
        0.0
    } else if elev > 5.0 {
        58.1 / te - 0.07 / te.powi(3) + 0.000086 / te.powi(5)
    } else if elev > -0.575 {
        1735.0 + elev * (-518.2 + elev * (103.4 + elev * (-12.79 + elev * 0.711)))
    } else {
        -20.772 / te
    };
    SunPosition {
        zenith_true,
        zenith: zenith_true - refraction_arcsec / 3600.0,
        azimuth,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn julian_days() {
        let t = UtcTime::parse("2000-01-01T12:00:00Z").unwrap();
        assert_eq!(t.julian_day(), 2_451_545.0);
        let t = UtcTime::parse("1970-01-01T00:00Z").unwrap();
        assert_eq!(t.julian_day(), 2_440_587.5);
        // an offset moves the instant: 14:00+02:00 is 12:00Z
        let a = UtcTime::parse("2024-03-01T14:00:00+02:00").unwrap();
        let b = UtcTime::parse("2024-03-01T12:00:00Z").unwrap();
        assert_eq!(a.julian_day(), b.julian_day());
        for bad in [
            "2024-02-30T12:00Z",
            "2024-06-21T12:00",
            "noon",
            "2024-06-21T25:00Z",
        ] {
            assert!(UtcTime::parse(bad).is_err(), "{bad}");
        }
    }
}
