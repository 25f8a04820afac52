#!/usr/bin/env python3
"""Solar-position test vectors (tests/daylight.rs): pip install pvlib==0.16.1 pandas, then
python3 scripts/gen_solar_vectors.py.

Reference values: NREL SPA (Reda & Andreas 2004) as implemented in pvlib
(pvlib.solarposition.spa_python, how='numpy'), with
    altitude = 0 m, pressure = 101325 Pa, temperature = 12 C,
    atmos_refract = 0.5667 deg (pvlib default),
    delta_t = pvlib.spa.calculate_deltat(year, month)  (written to the CSV).
'zenith_true_deg'     = SPA topocentric zenith WITHOUT refraction (pvlib 'zenith')
'apparent_zenith_deg' = SPA topocentric zenith WITH refraction   (pvlib 'apparent_zenith')
'azimuth_deg'         = SPA topocentric azimuth, clockwise from north (refraction
                        does not change azimuth)

Extra columns (after the 6 requested ones) give a straight Python port of the
NOAA "General Solar Position Calculations" spreadsheet (NOAA_Solar_Calculations_day.xls,
https://gml.noaa.gov/grad/solcalc/calcdetails.html) so a Rust port can be checked to ~1e-9
against it, and the NOAA-vs-SPA differences show what tolerance to expect.
"""
import math
import os
import datetime as dt

import numpy as np
import pandas as pd
import pvlib

# ----------------------------------------------------------------- NOAA port
def noaa(utc: dt.datetime, lat: float, lon: float):
    """NOAA spreadsheet chain; lon east-positive; time zone 0 (UTC input)."""
    r, d = math.radians, math.degrees
    # Julian day: spreadsheet F = D + 2415018.5 + E - tz/24 (Excel serial date D).
    # Same thing for UTC: JD = unix_seconds/86400 + 2440587.5
    jd = utc.replace(tzinfo=dt.timezone.utc).timestamp() / 86400.0 + 2440587.5
    T = (jd - 2451545.0) / 36525.0                                          # G
    L0 = (280.46646 + T * (36000.76983 + T * 0.0003032)) % 360.0            # I
    M = 357.52911 + T * (35999.05029 - 0.0001537 * T)                       # J
    e = 0.016708634 - T * (0.000042037 + 0.0000001267 * T)                  # K
    C = (math.sin(r(M)) * (1.914602 - T * (0.004817 + 0.000014 * T))
         + math.sin(r(2 * M)) * (0.019993 - 0.000101 * T)
         + math.sin(r(3 * M)) * 0.000289)                                   # L
    true_long = L0 + C                                                      # M
    omega = 125.04 - 1934.136 * T
    app_long = true_long - 0.00569 - 0.00478 * math.sin(r(omega))           # P
    eps0 = 23 + (26 + ((21.448 - T * (46.815 + T * (0.00059 - T * 0.001813)))) / 60) / 60  # Q
    eps = eps0 + 0.00256 * math.cos(r(omega))                               # R
    decl = d(math.asin(math.sin(r(eps)) * math.sin(r(app_long))))          # T
    y = math.tan(r(eps / 2)) ** 2                                           # U
    eot = 4 * d(y * math.sin(2 * r(L0)) - 2 * e * math.sin(r(M))
                + 4 * e * y * math.sin(r(M)) * math.cos(2 * r(L0))
                - 0.5 * y * y * math.sin(4 * r(L0))
                - 1.25 * e * e * math.sin(2 * r(M)))                        # V (minutes)
    minutes = utc.hour * 60 + utc.minute + utc.second / 60 + utc.microsecond / 6e7
    tst = (minutes + eot + 4 * lon) % 1440.0                                # AB (tz = 0)
    ha = tst / 4 + 180 if tst / 4 < 0 else tst / 4 - 180                    # AC
    cosz = (math.sin(r(lat)) * math.sin(r(decl))
            + math.cos(r(lat)) * math.cos(r(decl)) * math.cos(r(ha)))
    zen = d(math.acos(max(-1.0, min(1.0, cosz))))                           # AD
    el = 90 - zen                                                           # AE
    te = math.tan(r(el))
    if el > 85:
        refr = 0.0
    elif el > 5:
        refr = 58.1 / te - 0.07 / te ** 3 + 0.000086 / te ** 5
    elif el > -0.575:
        refr = 1735 + el * (-518.2 + el * (103.4 + el * (-12.79 + el * 0.711)))
    else:
        refr = -20.772 / te
    refr /= 3600.0                                                          # AF (deg)
    cosaz = ((math.sin(r(lat)) * math.cos(r(zen)) - math.sin(r(decl)))
             / (math.cos(r(lat)) * math.sin(r(zen))))
    acos_ = d(math.acos(max(-1.0, min(1.0, cosaz))))
    az = (acos_ + 180) % 360 if ha > 0 else (540 - acos_) % 360             # AH
    return dict(jd=jd, T=T, L0=L0, M=M, e=e, C=C, app_long=app_long, eps=eps,
                decl=decl, eot=eot, ha=ha, zen=zen, refr=refr,
                app_zen=zen - refr, az=az)


# ----------------------------------------------------------------- cases
CASES = [  # (utc ISO, lat, lon)   lon east-positive
    ("2024-06-21T12:00:00Z",  51.4779,   -0.0015),   # Greenwich, summer solstice noon
    ("2024-12-21T09:30:00Z",  51.4779,   -0.0015),   # Greenwich, winter morning, low sun
    ("2023-03-20T18:00:00Z",  40.7128,  -74.0060),   # New York, equinox afternoon
    ("2010-06-21T18:00:00Z",  40.0000, -105.0000),   # Boulder (NOAA sheet default site)
    ("2022-09-23T06:15:00Z", -33.8688,  151.2093),   # Sydney, spring afternoon (S hemisphere)
    ("2021-01-15T15:00:00Z", -70.0000,  -10.0000),   # Antarctic coast, S summer
    ("2021-07-01T10:00:00Z",  70.0000,   25.0000),   # N Norway, midnight-sun season
    ("2021-07-01T22:30:00Z",  70.0000,   25.0000),   # same, sun low in the north (az ~ 0/360)
    ("2020-03-01T04:00:00Z",   1.3521,  103.8198),   # Singapore, near-zenith sun (el > 85 branch)
    ("2019-11-05T08:20:00Z", -22.9068,  -43.1729),   # Rio, just after sunrise (el ~2.4: NOAA 5 > el > -0.575 branch)
    ("2019-11-05T08:10:00Z", -22.9068,  -43.1729),   # Rio, sun on the horizon (el ~0.2)
    ("2000-01-01T12:00:00Z",   0.0000,    0.0000),   # J2000 epoch at null island
    ("2099-08-15T08:40:00Z",  35.6762,  139.6503),   # Tokyo late afternoon (el ~9), far future
    ("1850-05-10T16:00:00Z",  48.8566,    2.3522),   # Paris, 19th century
]


def spa(times, lat, lon, elev=0.0, pressure=101325.0, temp=12.0, delta_t=None):
    if delta_t is None:
        delta_t = float(pvlib.spa.calculate_deltat(times.year[0], times.month[0]))
    sp = pvlib.solarposition.spa_python(times, lat, lon, altitude=elev, pressure=pressure,
                                        temperature=temp, delta_t=delta_t)
    return sp.iloc[0], delta_t


def main():
    rows = []
    for iso, lat, lon in CASES:
        t = pd.DatetimeIndex([pd.Timestamp(iso)])
        s, dT = spa(t, lat, lon)
        n = noaa(t[0].to_pydatetime().replace(tzinfo=None), lat, lon)
        rows.append(dict(utc=iso, lat=lat, lon=lon,
                         zenith_true_deg=round(float(s.zenith), 4),
                         apparent_zenith_deg=round(float(s.apparent_zenith), 4),
                         azimuth_deg=round(float(s.azimuth), 4),
                         spa_delta_t_s=round(dT, 2),
                         noaa_zenith_true_deg=round(n["zen"], 6),
                         noaa_apparent_zenith_deg=round(n["app_zen"], 6),
                         noaa_azimuth_deg=round(n["az"], 6),
                         noaa_decl_deg=round(n["decl"], 6),
                         noaa_eot_min=round(n["eot"], 6),
                         dz_true_noaa_minus_spa=round(n["zen"] - float(s.zenith), 4),
                         dz_app_noaa_minus_spa=round(n["app_zen"] - float(s.apparent_zenith), 4),
                         daz_noaa_minus_spa=round(((n["az"] - float(s.azimuth) + 180) % 360) - 180, 4)))
    df = pd.DataFrame(rows)
    df.to_csv(os.path.join(os.path.dirname(__file__), "..", "tests", "data", "solar_position_spa.csv"), index=False)
    pd.set_option("display.width", 250)
    print(df.to_string(index=False))

    # ---- sanity check: published SPA example (Reda & Andreas 2004, Table A5.1)
    t = pd.DatetimeIndex([pd.Timestamp("2003-10-17 12:30:30", tz="Etc/GMT+7")])  # = UTC-7
    s, _ = spa(t, 39.742476, -105.1786, elev=1830.14, pressure=82000.0, temp=11.0, delta_t=67.0)
    print("\nNREL SPA example: apparent(topocentric, refracted) zenith %.5f (expect 50.11162), "
          "azimuth %.5f (expect 194.34024), unrefracted zenith %.5f"
          % (s.apparent_zenith, s.azimuth, s.zenith))
    n = noaa(t[0].tz_convert("UTC").to_pydatetime().replace(tzinfo=None), 39.742476, -105.1786)
    print("NOAA port same instant: zenith(no refr) %.5f, apparent %.5f, azimuth %.5f"
          % (n["zen"], n["app_zen"], n["az"]))

    # ---- NOAA spreadsheet intermediate check (values printed in public copies of the
    # sheet's first row: date 6/21/2010, time 0:06 local, tz -6 -> 2010-06-21 06:06 UTC,
    # JD 2455368.754167 (displayed as 2455368.75), lat 40, lon -105):
    n = noaa(dt.datetime(2010, 6, 21, 6, 6, 0), 40.0, -105.0)
    print("\nNOAA intermediates @JD %.2f: L0 %.8f (89.33966362) M %.6f (4126.222292) e %.9f "
          "(0.016704232) C %.9f (0.446799918) app_long %.8f (89.78543918) eps %.8f "
          "(23.43848633) decl %.8f (23.43831216) EoT %.9f (-1.706307841)"
          % (n["jd"], n["L0"], n["M"], n["e"], n["C"], n["app_long"], n["eps"], n["decl"], n["eot"]))


if __name__ == "__main__":
    main()
