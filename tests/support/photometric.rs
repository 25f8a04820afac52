//! Photometric files written from a closed-form intensity I(γ, C) in cd, for the luminaire
//! tests: the truth is the formula at the file's angles, independent of the reader.

/// An IES LM-63-2002 type C file: vertical angles `v`, horizontal `h` (deg), I(γ, C) in cd,
/// written with a candela multiplier of 2 (the values halved) and absolute photometry.
pub fn ies(v: &[f64], h: &[f64], i: &dyn Fn(f64, f64) -> f64) -> String {
    let mut s = String::from(
        "IESNA:LM-63-2002\n[TEST] closed form\n[MANUFAC] spectrace tests\nTILT=NONE\n",
    );
    s += &format!("1 -1 2 {} {} 1 2 0.1 0.1 0\n1 1 10\n", v.len(), h.len());
    let row = |xs: &[f64]| {
        xs.iter()
            .map(|x| format!("{x}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    s += &row(v);
    s += "\n";
    s += &row(h);
    s += "\n";
    for &c in h {
        let vals: Vec<f64> = v.iter().map(|&g| i(g, c) / 2.0).collect();
        s += &format!(
            "{}\n",
            vals.iter()
                .map(|x| format!("{x:.12}"))
                .collect::<Vec<_>>()
                .join(" ")
        );
    }
    s
}

/// A EULUMDAT file: Mc C-planes at `dc` spacing from 0, γ angles `g`, I(γ, C) in cd for a lamp
/// set of `flux` lm (values written in cd/klm), symmetry `isym`, light output ratio `lor` (%).
pub fn ldt(
    isym: u32,
    mc: u32,
    dc: f64,
    g: &[f64],
    flux: f64,
    lor: f64,
    i: &dyn Fn(f64, f64) -> f64,
) -> String {
    let mut l: Vec<String> = vec![
        "spectrace tests".into(),
        "1".into(),
        isym.to_string(),
        mc.to_string(),
        dc.to_string(),
        g.len().to_string(),
        "5".into(),
        "report".into(),
        "closed form".into(),
        "1".into(),
        "t.ldt".into(),
        "2026-11-29".into(),
    ];
    for _ in 0..10 {
        l.push("100".into());
    }
    l.push(format!("{lor}"));
    l.push("1".into());
    l.push("0".into());
    l.extend(["1", "1", "LED"].map(String::from));
    l.push(format!("{flux}"));
    l.extend(["3000K", "80", "20"].map(String::from));
    for _ in 0..10 {
        l.push("0.5".into());
    }
    let cs: Vec<f64> = (0..mc).map(|k| k as f64 * dc).collect();
    l.extend(cs.iter().map(|c| c.to_string()));
    l.extend(g.iter().map(|a| a.to_string()));
    let stored: Vec<f64> = match isym {
        0 => cs.clone(),
        1 => vec![0.0],
        2 => cs.iter().copied().filter(|&c| c <= 180.0).collect(),
        3 => {
            let mut v: Vec<f64> = cs.iter().copied().filter(|&c| c >= 270.0).collect();
            v.extend(cs.iter().copied().filter(|&c| c <= 90.0));
            v
        }
        _ => cs.iter().copied().filter(|&c| c <= 90.0).collect(),
    };
    for c in stored {
        for &a in g {
            l.push(format!("{:.12}", i(a, c) * 1000.0 / flux));
        }
    }
    l.join("\r\n") + "\r\n"
}
