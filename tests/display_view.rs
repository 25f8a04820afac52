//! The PNG's display transform (`--view`, issue 30): a sweep of 5 nm spectral lines keeps the
//! order of hues and has no plateaus or jumps, in-gamut colours below white pass unchanged,
//! and the EXR is never transformed.

mod support;

use spectrace::colour::view::View;
use support::cli::{spectrace, tmpdir};

/// CIE XYZ to linear sRGB (IEC 61966-2-1), typed here.
fn srgb(xyz: [f64; 3]) -> [f32; 3] {
    let m = [
        [3.2406, -1.5372, -0.4986],
        [-0.9689, 1.8758, 0.0415],
        [0.0557, -0.2040, 1.0570],
    ];
    m.map(|r| (r[0] * xyz[0] + r[1] * xyz[1] + r[2] * xyz[2]) as f32)
}

/// HSV hue in degrees, [0, 360).
fn hue(c: [f32; 3]) -> f64 {
    let [r, g, b] = c.map(|v| v as f64);
    let (max, min) = (r.max(g).max(b), r.min(g).min(b));
    let d = max - min;
    assert!(d > 1e-6, "achromatic: {c:?}");
    let h = if max == r {
        60.0 * ((g - b) / d)
    } else if max == g {
        60.0 * ((b - r) / d + 2.0)
    } else {
        60.0 * ((r - g) / d + 4.0)
    };
    h.rem_euclid(360.0)
}

/// Hues of 5 nm lines from 400 to 700 nm (the CIE 1931 2° observer, `colour-science`'s table
/// as shipped in `spectra/`) at luminance `y` of white, through `view`; unwrapped so that
/// they run downward from violet.
fn sweep(view: View, y: f64) -> Vec<(u32, f64)> {
    let cmf = spectrace::colour::cie::cmf();
    let mut out: Vec<(u32, f64)> = Vec::new();
    for l in (400..=700).step_by(5) {
        let [x, yy, z] = cmf.eval(l as f32).map(|v| v as f64);
        let k = y / yy;
        let mut h = hue(view.apply(srgb([x * k, yy * k, z * k])));
        // violet sits above 240°; red near 0° may wrap to 359°
        if let Some(&(_, prev)) = out.last()
            && h > prev + 180.0
        {
            h -= 360.0;
        }
        out.push((l, h));
    }
    out
}

#[test]
fn spectral_lines_keep_their_order_of_hues_without_plateaus_or_jumps() {
    for y in [0.05, 0.2, 0.5] {
        let s = sweep(View::Standard, y);
        let line: Vec<String> = s.iter().map(|(l, h)| format!("{l}:{h:.1}")).collect();
        eprintln!("standard, Y = {y}: {}", line.join(" "));
        for w in s.windows(2) {
            let ((l0, h0), (l1, h1)) = (w[0], w[1]);
            let step = h0 - h1;
            assert!(
                step > -1e-3,
                "Y {y}: hue rises from {l0} to {l1} nm: {h0} → {h1}"
            );
            // the locus itself turns fastest near 488 nm, 15° in 5 nm; the clamp's jumps
            // between plateaus are up to 60°
            assert!(step < 20.0, "Y {y}: hue jumps {step}° from {l0} to {l1} nm");
            // the spectral locus itself barely moves below 420 nm and above 650 nm
            if (420..650).contains(&l0) {
                assert!(
                    step > 0.2,
                    "Y {y}: hue plateau from {l0} to {l1} nm: {h0} → {h1}"
                );
            }
        }
        // the sweep runs from violet (above blue) to red
        assert!(s[0].1 > 240.0 && s.last().unwrap().1 < 20.0, "{line:?}");
    }
    // the per-channel clamp fails this test: its hues sit on plateaus
    let clip = sweep(View::Clip, 0.2);
    let plateau = clip
        .windows(2)
        .any(|w| (420..650).contains(&w[0].0) && (w[0].1 - w[1].1).abs() < 0.2);
    assert!(plateau, "clip was expected to posterise: {clip:?}");
}

#[test]
fn in_gamut_colours_below_white_pass_within_one_percent() {
    let mut worst = 0.0f32;
    let steps = 20;
    for r in 0..=steps {
        for g in 0..=steps {
            for b in 0..=steps {
                let c = [r, g, b].map(|v| v as f32 / steps as f32);
                let y = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
                if y >= 0.999 {
                    continue;
                }
                let d = View::Standard.apply(c);
                for k in 0..3 {
                    worst = worst.max((d[k] - c[k]).abs());
                }
            }
        }
    }
    eprintln!("largest change of an in-gamut colour: {worst} of white");
    assert!(worst <= 0.01, "{worst}");
}

/// A lamp of a 5 nm line at 470 nm (far out of the sRGB gamut) filling the view: `--view`
/// changes the PNG and not one value of the EXR, whose Y stays the lamp's luminance in cd/m².
#[test]
fn the_view_shapes_the_png_only() {
    let dir = tmpdir("display-view");
    std::fs::write(
        dir.join("line.toml"),
        r#"
[camera]
eye = [0, 0, 2]
target = [0, 0, 0]
fov = "20 deg"
[film]
width = 16
height = 16
spp = 64
[[shapes]]
type = "rectangle"
transform = [{ scale = 3 }]
emission = { spectrum = { samples = [[467.5, 0], [470, 1], [472.5, 0]] }, luminance = "50 cd/m^2" }
"#,
    )
    .unwrap();
    for view in ["standard", "clip"] {
        let out = format!("{view}.exr");
        let (ok, err) = spectrace(
            &dir,
            &["render", "line.toml", "-o", &out, "--view", view, "--quiet"],
        );
        assert!(ok, "{err}");
    }
    let read = |f: &str| spectrace::image_io::read_exr(&dir.join(f)).unwrap();
    let (a, b) = (read("standard.exr"), read("clip.exr"));
    for name in ["X", "Y", "Z", "R", "G", "B", "L"] {
        assert_eq!(a.channel(name), b.channel(name), "channel {name}");
    }
    // Y is the lamp's luminance (the noise of the mean is about 0.3 %)
    let y = a.channel("Y").unwrap();
    let m = y.iter().map(|v| *v as f64).sum::<f64>() / y.len() as f64;
    assert!((m / 50.0 - 1.0).abs() < 0.02, "mean Y {m} cd/m²");
    let png = |f: &str| std::fs::read(dir.join(f)).unwrap();
    assert_ne!(png("standard.png"), png("clip.png"));
    // an unknown view is refused by name
    let (ok, err) = spectrace(&dir, &["render", "line.toml", "--view", "agx"]);
    assert!(!ok && err.contains("agx"), "{err}");
}
