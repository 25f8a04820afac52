//! Spectrum plots and the spectral probe read back against independent values: the SVG's
//! polyline mapped through its own tick labels gives the CIE D65 table and N-BK7's catalogue
//! index; `spectrace probe` reads a white furnace's spectral EXR as Le/(1 − ρ) per nm.

mod support;

use support::cli::{spectrace, tmpdir};

/// The values of an attribute `key="…"` in a tag.
fn attr(tag: &str, key: &str) -> f64 {
    let k = format!("{key}=\"");
    let i = tag.find(&k).unwrap() + k.len();
    tag[i..tag[i..].find('"').unwrap() + i].parse().unwrap()
}

/// (position, value) of the `class` tick labels.
fn ticks(svg: &str, class: &str, key: &str) -> Vec<(f64, f64)> {
    let pat = format!("<text class=\"{class}\"");
    svg.match_indices(&pat)
        .map(|(i, _)| {
            let end = svg[i..].find("</text>").unwrap() + i;
            let tag = &svg[i..end];
            let value: f64 = tag[tag.rfind('>').unwrap() + 1..].parse().unwrap();
            (attr(tag, key), value)
        })
        .collect()
}

/// The first polyline's points in data units, through the affine maps the first and last
/// ticks of each axis define.
fn curve(svg: &str) -> Vec<(f64, f64)> {
    let (xt, yt) = (ticks(svg, "xtick", "x"), ticks(svg, "ytick", "y"));
    let map = |t: &[(f64, f64)], p: f64| {
        let (a, b) = (t[0], t[t.len() - 1]);
        a.1 + (p - a.0) / (b.0 - a.0) * (b.1 - a.1)
    };
    let i = svg.find("<polyline").unwrap();
    let pts = &svg[i..];
    let k = pts.find("points=\"").unwrap() + 8;
    let pts = &pts[k..k + pts[k..].find('"').unwrap()];
    pts.split(' ')
        .map(|p| {
            let (x, y) = p.split_once(',').unwrap();
            (map(&xt, x.parse().unwrap()), map(&yt, y.parse().unwrap()))
        })
        .collect()
}

fn at(c: &[(f64, f64)], x: f64) -> f64 {
    c.iter()
        .min_by(|a, b| (a.0 - x).abs().total_cmp(&(b.0 - x).abs()))
        .unwrap()
        .1
}

#[test]
fn spectrum_plots_show_the_spectrum() {
    let dir = tmpdir("plots");
    let (ok, err) = spectrace(&dir, &["spectrum", "cie-d65", "--plot", "d65.svg"]);
    assert!(ok, "{err}");
    let svg = std::fs::read_to_string(dir.join("d65.svg")).unwrap();
    assert!(svg.contains("wavelength (nm)") && svg.contains("relative spectral power"));
    let c = curve(&svg);
    // CIE 015:2018 table of D65 at 5 nm steps
    for (nm, v) in [
        (400.0, 82.7549),
        (460.0, 117.812),
        (560.0, 100.0),
        (600.0, 90.0062),
        (700.0, 71.6091),
    ] {
        let got = at(&c, nm);
        assert!((got - v).abs() < 0.05, "D65({nm}) plotted {got}, table {v}");
    }
    let (ok, err) = spectrace(&dir, &["spectrum", "glass:N-BK7", "--plot", "bk7.svg"]);
    assert!(ok, "{err}");
    let svg = std::fs::read_to_string(dir.join("bk7.svg")).unwrap();
    assert!(svg.contains("refractive index n"));
    // SCHOTT catalogue: n_d = 1.5168 at 587.56 nm (the plot's nearest point is within 0.5 nm)
    let n = at(&curve(&svg), 587.56);
    assert!((n - 1.5168).abs() < 1e-4, "{n}");
    // a spectrum file plots as given
    std::fs::write(
        dir.join("s.csv"),
        "wavelength_nm,value\n400,1\n500,3\n600,2\n",
    )
    .unwrap();
    let (ok, err) = spectrace(&dir, &["spectrum", "s.csv", "--plot", "s.svg"]);
    assert!(ok, "{err}");
    let c = curve(&std::fs::read_to_string(dir.join("s.svg")).unwrap());
    assert!((at(&c, 450.0) - 2.0).abs() < 1e-3 && (at(&c, 600.0) - 2.0).abs() < 1e-3);
}

#[test]
fn probe_reads_spectral_radiance() {
    let dir = tmpdir("probe");
    let scene = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/furnace.toml");
    let (ok, err) = spectrace(
        &dir,
        &[
            "render",
            scene.to_str().unwrap(),
            "-o",
            "f.exr",
            "--spp",
            "256",
            "--spectral-bins",
            "47",
            "--quiet",
        ],
    );
    assert!(ok, "{err}");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_spectrace"))
        .current_dir(&dir)
        .args([
            "probe", "f.exr", "0", "0", "--size", "64", "--plot", "p.svg",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("wavelength_nm,spectral_radiance_W_m2_sr_nm")
    );
    // Le = 1 W·m⁻²·sr⁻¹ over 470 nm, ρ = 0.5: L = 2/470 W·m⁻²·sr⁻¹·nm⁻¹ in every bin
    let want = 2.0 / 470.0;
    let mut n = 0;
    for l in lines {
        let (wl, v) = l.split_once(',').unwrap();
        let v: f64 = v.parse().unwrap();
        assert!((v / want - 1.0).abs() < 0.015, "{wl} nm: {v}");
        n += 1;
    }
    assert_eq!(n, 47);
    let svg = std::fs::read_to_string(dir.join("p.svg")).unwrap();
    assert!(svg.contains("spectral radiance (W·m⁻²·sr⁻¹·nm⁻¹)"));
    let c = curve(&svg);
    assert!((at(&c, 555.0) / want - 1.0).abs() < 0.015);
    // errors
    let (ok, err) = spectrace(&dir, &["probe", "f.exr", "60", "60", "--size", "8"]);
    assert!(
        !ok && err.contains("does not fit in the 64×64 image"),
        "{err}"
    );
    let (ok, err) = spectrace(
        &dir,
        &[
            "render",
            scene.to_str().unwrap(),
            "-o",
            "g.exr",
            "--spp",
            "1",
            "--quiet",
        ],
    );
    assert!(ok, "{err}");
    let (ok, err) = spectrace(&dir, &["probe", "g.exr", "1", "1"]);
    assert!(!ok && err.contains("no spectral channels"), "{err}");
}
