//! Tests of `named`.

use super::*;

#[test]
fn looks_up_families() {
    assert!(matches!(
        lookup("cie-d65"),
        Ok(Named::Curve {
            kind: CurveKind::Illuminant,
            ..
        })
    ));
    assert!(matches!(lookup("glass:n-bk7"), Ok(Named::Dielectric(_))));
    assert!(matches!(lookup("metal:Au"), Ok(Named::Conductor(_))));
    assert!(matches!(
        lookup("colorchecker:dark-skin"),
        Ok(Named::Curve { .. })
    ));
    assert!(matches!(
        lookup("blackbody:6500K"),
        Ok(Named::Curve {
            kind: CurveKind::Blackbody,
            ..
        })
    ));
    assert!(lookup("blackbody:-5K").is_err());
    assert!(lookup("blackbody:6500 W").is_err());
}

#[test]
fn unknown_names_suggest() {
    let e = lookup("glass:BK7").unwrap_err();
    assert_eq!(
        e.suggestions.first().map(String::as_str),
        Some("glass:N-BK7"),
        "{e}"
    );
    let e = lookup("cie-d56").unwrap_err();
    assert!(e.suggestions.iter().any(|s| s == "cie-d65"), "{e}");
    assert!(e.to_string().contains("did you mean"));
    // a name longer than any known one is not compared (a fuzzed 20 000-character name took
    // 2 s of string distances)
    let long = "x".repeat(super::MAX_SUGGESTED + 1);
    assert!(lookup(&long).unwrap_err().suggestions.is_empty());
    let e = lookup(&format!("cie-d56{}", " ".repeat(super::MAX_SUGGESTED - 7))).unwrap_err();
    assert!(e.suggestions.len() <= 3);
}

#[test]
fn lists_every_family() {
    let n = names();
    for want in [
        "cie-d65",
        "cie-f11",
        "glass:N-BK7",
        "glass:diamond",
        "metal:Cu",
        "colorchecker:cyan",
    ] {
        assert!(n.iter().any(|(k, _)| k == want), "{want} missing");
    }
    assert_eq!(
        n.iter()
            .filter(|(k, _)| k.starts_with("colorchecker:"))
            .count(),
        24
    );
}
