#!/usr/bin/env python3
"""Writes, from colour-science 0.4.7 (BSD-3-Clause; CIE data):
- spectra/illuminants/cie_led.csv: the CIE LED illuminants of CIE 015:2018 (LED-B1 … B5,
  BH1, RGB1, V1, V2), 380–780 nm at 5 nm, relative SPD as tabulated.
- spectra/illuminants/cie_daylight_basis.csv: the CIE daylight basis functions S0, S1, S2
  (CIE 015:2018 Table 6), 300–830 nm at 5 nm, from which `cie-d:<T>K` is built.
- tests/data/cie_daylight_cct.csv: colour-science's D-series SPDs for chromaticities from
  CCTs (its own x_D(T) and M1, M2), independent test vectors for `cie-d:<T>K`.
Run: pip install colour-science==0.4.7; python3 scripts/gen_led_daylight.py
"""
import os

import colour
import numpy as np

ROOT = os.path.join(os.path.dirname(__file__), "..")
leds = ["LED-B1", "LED-B2", "LED-B3", "LED-B4", "LED-B5", "LED-BH1", "LED-RGB1", "LED-V1", "LED-V2"]
wl = np.arange(380, 781, 5)
with open(os.path.join(ROOT, "spectra/illuminants/cie_led.csv"), "w") as f:
    f.write("# CIE LED illuminants (CIE 015:2018 Table 11.4): relative spectral power as the CIE tabulates it\n")
    f.write("# source: colour-science 0.4.7 SDS_ILLUMINANTS (BSD-3-Clause; CIE data), scripts/gen_led_daylight.py\n")
    f.write("# units: wavelength nm; relative SPD\n")
    f.write("wavelength_nm," + ",".join(l.lower().replace("led-", "") for l in leds) + "\n")
    for w in wl:
        f.write(f"{w}," + ",".join(f"{colour.SDS_ILLUMINANTS[l][w]:.10g}" for l in leds) + "\n")
basis = colour.colorimetry.datasets.illuminants.sds_d_illuminant_series.SDS_BASIS_FUNCTIONS_CIE_ILLUMINANT_D_SERIES
with open(os.path.join(ROOT, "spectra/illuminants/cie_daylight_basis.csv"), "w") as f:
    f.write("# CIE daylight basis functions S0, S1, S2 (CIE 015:2018 Table 6)\n")
    f.write("# source: colour-science 0.4.7 SDS_BASIS_FUNCTIONS_CIE_ILLUMINANT_D_SERIES (BSD-3-Clause; CIE data), scripts/gen_led_daylight.py\n")
    f.write("# units: wavelength nm; relative\n")
    f.write("wavelength_nm,s0,s1,s2\n")
    for w in np.arange(300, 831, 5):
        f.write(f"{w},{basis['S0'][w]:.10g},{basis['S1'][w]:.10g},{basis['S2'][w]:.10g}\n")
with open(os.path.join(ROOT, "tests/data/cie_daylight_cct.csv"), "w") as f:
    f.write("# CIE D-series SPDs from CCT by colour-science 0.4.7: xy = CCT_to_xy_CIE_D(T), sd_CIE_illuminant_D_series(xy),\n")
    f.write("# normalised to 100 at 560 nm; scripts/gen_led_daylight.py\n")
    cct = [4000, 5000, 6504, 7500, 10000]
    f.write("wavelength_nm," + ",".join(f"t{t}" for t in cct) + "\n")
    sds = []
    for t in cct:
        xy = colour.temperature.CCT_to_xy_CIE_D(t)
        sd = colour.sd_CIE_illuminant_D_series(xy)
        sds.append(sd)
    for w in np.arange(300, 831, 10):
        f.write(f"{w}," + ",".join(f"{sd[w] / sd[560] * 100:.8g}" for sd in sds) + "\n")
with open(os.path.join(ROOT, "tests/data/cie_led_xy.csv"), "w") as f:
    f.write("# chromaticities x, y (CIE 1931 2 degree) of the CIE LED illuminants by colour-science 0.4.7\n")
    f.write("# (sd_to_XYZ, its ASTM E308 integration of the 5 nm table); scripts/gen_led_daylight.py\n")
    f.write("name,x,y\n")
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    for l in leds:
        xyz = colour.sd_to_XYZ(colour.SDS_ILLUMINANTS[l], cmfs)
        x, y = colour.XYZ_to_xy(xyz)
        f.write(f"cie-{l.lower()},{x:.6f},{y:.6f}\n")
