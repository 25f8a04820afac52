#!/usr/bin/env python3
"""Writes a synthetic RGL measured-BRDF file (`.bsdf`, the tensor format of Dupuy & Jakob 2018,
"An Adaptive Parameterization for Efficient Material Acquisition and Rendering", read by
pbrt-v4's and Mitsuba 3's `measured` material) for an analytic isotropic GGX conductor.

No RGL measurement is reachable from this machine (pbrt-v4-scenes, which holds some, is 1.47 GB),
so the reference scene `tests/reference/pbrt/measured` uses this file instead. It is built the
way the paper's data are laid out, from a known BRDF, so that a reader can be checked both
against pbrt-v4's renders of the same file and against the closed form it came from:

- ndf D(u_m) and sigma σ(u_o) = ∫ D(m) max(0, ω_o·m) dm = (cos θ + √(cos² θ + α² sin² θ))/2,
  on the u-square u = (√(2θ/π), φ/2π + ½);
- vndf per θ_i: the visible-normal density D_ωo(m) = G1(ω_o) max(0, ω_o·m) D(m) / cos θ_o
  times the Jacobian 2π² u_θ sin θ_m of u → m (φ relative to φ_o: the file is isotropic);
- spectra per θ_i and λ on the sample square: the factor R with
  f = R D / (4 σ cos θ_i), i.e. R = F(λ, ω_o·m) G2(ω_o, ω_i) / G1(ω_o) (height-correlated
  Smith), at the half vector the vndf warp maps each node to (the warp as pbrt-v4's
  `PiecewiseLinear2D::Sample` computes it, in f64 here);
- luminance: the mean of R over the wavelengths, the density the sampler follows first.

F is Schlick's with F0(λ) rising from 0.25 at 380 nm to 0.95 at 780 nm (a made-up metal).

Usage: python3 scripts/gen_rgl_bsdf.py tests/reference/pbrt/measured/ggx.bsdf [alpha]
"""
import struct
import sys

import numpy as np

ALPHA = float(sys.argv[2]) if len(sys.argv) > 2 else 0.3
N_THETA_I = 9
THETA_I = np.radians(np.linspace(0.0, 80.0, N_THETA_I))
WAVELENGTHS = np.linspace(380.0, 780.0, 9)
NDF_RES = (8, 64)  # rows (u_phi), columns (u_theta)
VNDF_RES = 48
SAMPLE_RES = 32


def u2theta(u):
    return u * u * np.pi / 2


def u2phi(u):
    return (2 * u - 1) * np.pi


def ggx_d(cos_t):
    a2 = ALPHA * ALPHA
    return a2 / (np.pi * ((a2 - 1) * cos_t * cos_t + 1) ** 2)


def smith_lambda(cos_t):
    cos_t = np.clip(cos_t, 1e-9, 1.0)
    tan2 = (1 - cos_t * cos_t) / (cos_t * cos_t)
    return (-1 + np.sqrt(1 + ALPHA * ALPHA * tan2)) / 2


def sigma(cos_t):
    sin2 = 1 - cos_t * cos_t
    return (cos_t + np.sqrt(cos_t * cos_t + ALPHA * ALPHA * sin2)) / 2


def f0(lam):
    return 0.25 + 0.70 * (lam - 380.0) / 400.0


def direction(theta, phi):
    return np.array([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)])


def vndf_slice(theta_o):
    """Visible normals on the u-square of the half vector (rows u_phi, columns u_theta)."""
    wo = direction(theta_o, 0.0)
    n = VNDF_RES
    x = np.linspace(0, 1, n)
    out = np.zeros((n, n))
    g1 = 1 / (1 + smith_lambda(np.cos(theta_o)))
    for j in range(n):
        for i in range(n):
            tm, pm = u2theta(x[i]), u2phi(x[j])
            m = direction(tm, pm)
            d = max(0.0, wo @ m) * ggx_d(m[2]) * g1 / np.cos(theta_o)
            out[j, i] = d * 2 * np.pi**2 * x[i] * np.sin(tm)
    return out


def warp_sample(data, s):
    """pbrt-v4's PiecewiseLinear2D::Sample for one slice (rows y, columns x), in f64."""
    ny, nx = data.shape
    cond = np.zeros_like(data)
    cond[:, 1:] = np.cumsum(0.5 * (data[:, :-1] + data[:, 1:]), axis=1)
    marg = np.zeros(ny)
    marg[1:] = np.cumsum(0.5 * (cond[:-1, -1] + cond[1:, -1]))
    norm = 1 / marg[-1]
    cond, marg, data = cond * norm, marg * norm, data * norm

    def lin(s, c0, c1):
        if abs(c0 - c1) < 1e-4 * (c0 + c1):
            return 2 * s / (c0 + c1)
        return (c0 - np.sqrt(max(0.0, c0 * c0 - 2 * s * (c0 - c1)))) / (c0 - c1)

    sx, sy = min(max(s[0], 1e-7), 1 - 1e-7), min(max(s[1], 1e-7), 1 - 1e-7)
    row = int(np.clip(np.searchsorted(marg, sy, side="left") - 1, 0, ny - 2))
    sy -= marg[row]
    r0, r1 = cond[row, -1], cond[row + 1, -1]
    sy = lin(sy, r0, r1)
    sx *= (1 - sy) * r0 + sy * r1
    c = (1 - sy) * cond[row] + sy * cond[row + 1]
    col = int(np.clip(np.searchsorted(c, sx, side="left") - 1, 0, nx - 2))
    sx -= c[col]
    c0 = (1 - sy) * data[row, col] + sy * data[row + 1, col]
    c1 = (1 - sy) * data[row, col + 1] + sy * data[row + 1, col + 1]
    sx = lin(sx, c0, c1)
    return (col + sx) / (nx - 1), (row + sy) / (ny - 1)


def spectra_slice(theta_o, vndf):
    """R per wavelength on the sample square (λ × rows × columns)."""
    wo = direction(theta_o, 0.0)
    lam_o = smith_lambda(np.cos(theta_o))
    n = SAMPLE_RES
    x = np.linspace(0, 1, n)
    out = np.zeros((len(WAVELENGTHS), n, n))
    for j in range(n):
        for i in range(n):
            ut, up = warp_sample(vndf, (x[i], x[j]))
            m = direction(u2theta(ut), u2phi(up))
            wi = 2 * (wo @ m) * m - wo
            if wi[2] <= 0:
                continue
            c = max(0.0, wo @ m)
            g2_over_g1 = (1 + lam_o) / (1 + lam_o + smith_lambda(wi[2]))
            fres = f0(WAVELENGTHS) + (1 - f0(WAVELENGTHS)) * (1 - c) ** 5
            out[:, j, i] = fres * g2_over_g1
    return out


def tensor_file(fields):
    """The bytes of a tensor file: (name, type code, array) per field, data 8-byte aligned."""
    head = b"tensor_file\0" + bytes([1, 0]) + struct.pack("<I", len(fields))
    header_len = len(head) + sum(2 + len(n) + 2 + 1 + 8 + 8 * a.ndim for n, _, a in fields)
    offset = -(-header_len // 8) * 8
    blobs = []
    for name, code, a in fields:
        head += struct.pack("<H", len(name)) + name.encode() + struct.pack("<HBQ", a.ndim, code, offset)
        head += b"".join(struct.pack("<Q", d) for d in a.shape)
        blob = a.tobytes()
        blob += b"\0" * (-len(blob) % 8)
        blobs.append(blob)
        offset += len(blob)
    head += b"\0" * (-len(head) % 8)
    return head + b"".join(blobs)


def main():
    out = sys.argv[1]
    ry, rx = NDF_RES
    ut = np.linspace(0, 1, rx)
    ndf = np.tile(ggx_d(np.cos(u2theta(ut))), (ry, 1))
    sig = np.tile(sigma(np.cos(u2theta(ut))), (ry, 1))
    vndf = np.zeros((1, N_THETA_I, VNDF_RES, VNDF_RES))
    spectra = np.zeros((1, N_THETA_I, len(WAVELENGTHS), SAMPLE_RES, SAMPLE_RES))
    for k, t in enumerate(THETA_I):
        vndf[0, k] = vndf_slice(t)
        spectra[0, k] = spectra_slice(t, vndf[0, k])
    luminance = spectra.mean(axis=2)
    desc = f"synthetic GGX conductor, alpha {ALPHA}, scripts/gen_rgl_bsdf.py".encode()
    f32 = lambda a: np.ascontiguousarray(a, dtype="<f4")  # noqa: E731
    fields = [
        ("description", 1, np.frombuffer(desc, dtype=np.uint8)),
        ("jacobian", 1, np.array([1], dtype=np.uint8)),
        ("theta_i", 10, f32(THETA_I)),
        ("phi_i", 10, f32([0.0])),
        ("wavelengths", 10, f32(WAVELENGTHS)),
        ("ndf", 10, f32(ndf)),
        ("sigma", 10, f32(sig)),
        ("vndf", 10, f32(vndf)),
        ("luminance", 10, f32(luminance)),
        ("spectra", 10, f32(spectra)),
    ]
    with open(out, "wb") as f:
        f.write(tensor_file(fields))
    print(f"{out}: alpha {ALPHA}, {len(THETA_I)} incidence angles, {len(WAVELENGTHS)} wavelengths")


if __name__ == "__main__":
    main()
