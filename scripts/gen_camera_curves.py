#!/usr/bin/env python3
"""Writes spectra/cameras/*.csv: measured camera spectral sensitivities from colour-science
0.4.7 (`colour.MSDS_CAMERA_SENSITIVITIES`, BSD-3-Clause), whose source is the NPL reference
data of Darrodi, Finlayson, Goodman & Mackiewicz (2015), "Reference data set for camera
spectral sensitivity estimation", JOSA A 32(3) 381, doi:10.1364/JOSAA.32.000381. Each channel
is normalised to a peak of 1, as published. The header states each channel's trapezoid
integral (nm), which tests/camera_sensor.rs checks.
Run: pip install colour-science==0.4.7; python3 scripts/gen_camera_curves.py
"""
import os

import colour
import numpy as np

OUT = os.path.join(os.path.dirname(__file__), "..", "spectra", "cameras")
CAMERAS = {"Nikon 5100 (NPL)": "nikon_d5100.csv", "Sigma SDMerill (NPL)": "sigma_sd_merrill.csv"}

os.makedirs(OUT, exist_ok=True)
for name, fname in CAMERAS.items():
    m = colour.MSDS_CAMERA_SENSITIVITIES[name]
    wl = m.wavelengths
    v = m.values
    integ = [float(np.trapezoid(v[:, k], wl)) for k in range(3)]
    with open(os.path.join(OUT, fname), "w") as f:
        f.write(f"# {name}: camera spectral sensitivity, relative (each channel's peak 1)\n")
        f.write("# source: Darrodi et al. 2015, JOSA A 32(3) 381 (NPL measurements), via colour-science 0.4.7 (BSD-3-Clause)\n")
        f.write("# units: wavelength nm; sensitivity dimensionless, peak-normalised per channel\n")
        f.write(f"# integral_nm: r={integ[0]:.6f} g={integ[1]:.6f} b={integ[2]:.6f}\n")
        f.write("wavelength_nm,r,g,b\n")
        for i, w in enumerate(wl):
            f.write(f"{w:g},{v[i, 0]:.8g},{v[i, 1]:.8g},{v[i, 2]:.8g}\n")
