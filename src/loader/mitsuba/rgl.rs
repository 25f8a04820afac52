//! RGL measured-BRDF files (`.bsdf`, Dupuy & Jakob 2018's format, read by pbrt-v4's and
//! Mitsuba 3's `measured`): a tensor file (`super::tensor`) with the fields
//! - `theta_i`, `phi_i` (radians) and `wavelengths` (nm), 1-D f32 grids;
//! - `ndf` and `sigma`, 2-D f32 (rows of u_φ, columns of u_θ);
//! - `vndf` and `luminance`, 4-D f32: φ_i × θ_i × rows × columns;
//! - `spectra`, 5-D f32: φ_i × θ_i × λ × rows × columns, on luminance's square grid;
//! - `description` (1-D u8) and `jacobian` (one u8: whether `spectra` is to be multiplied by
//!   D/(4σ), which Mitsuba 3 heeds and pbrt-v4 assumes).
//!
//! The structure is checked as pbrt-v4 checks it (`MeasuredBxDFData::Create`), with an error
//! naming the file and the field in place of its "invalid BRDF file structure".

use std::collections::HashMap;
use std::path::Path;

use super::tensor::{Field, fields, values};
use crate::loader::desc::RglTable;

/// Field `name`'s values (f32) and shape, which must have `rank` dimensions.
fn f32_field(
    f: &HashMap<String, Field<'_>>,
    name: &str,
    rank: usize,
) -> Result<(Vec<f32>, Vec<usize>), String> {
    let Some(field) = f.get(name) else {
        return Err(format!("no field `{name}`"));
    };
    if field.dtype != 10 || field.shape.len() != rank {
        return Err(format!(
            "field `{name}` must be {rank}-D float32 (it is {}-D of type code {})",
            field.shape.len(),
            field.dtype
        ));
    }
    let (v, shape) = values(f, name)?;
    Ok((v, shape.iter().map(|&d| d as usize).collect()))
}

/// A grid: 1-D, finite, strictly increasing, at least one value.
fn grid(f: &HashMap<String, Field<'_>>, name: &str, unit: &str) -> Result<Vec<f32>, String> {
    let (v, _) = f32_field(f, name, 1)?;
    if v.is_empty() || v.iter().any(|x| !x.is_finite()) || v.windows(2).any(|p| !(p[1] > p[0])) {
        return Err(format!(
            "field `{name}` must hold finite, strictly increasing {unit}"
        ));
    }
    Ok(v)
}

/// The table of the RGL `.bsdf` file `path`; errors name the file and the field.
pub(crate) fn read_rgl_bsdf(path: &Path) -> Result<RglTable, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let at = |e: String| format!("{}: {e}", path.display());
    let f = fields(&bytes).map_err(at)?;
    let names = [
        "theta_i",
        "phi_i",
        "wavelengths",
        "ndf",
        "sigma",
        "vndf",
        "luminance",
        "spectra",
        "description",
        "jacobian",
    ];
    if let Some(missing) = names.iter().find(|n| !f.contains_key(**n)) {
        return Err(at(format!(
            "not an RGL BRDF file: no field `{missing}` (it needs {})",
            names.join(", ")
        )));
    }
    for (name, rank) in [("description", None), ("jacobian", Some(1))] {
        match f.get(name) {
            Some(x)
                if x.dtype == 1 && x.shape.len() == 1 && rank.is_none_or(|r| x.shape[0] == r) => {}
            _ => {
                return Err(at(format!(
                    "field `{name}` must be 1-D uint8{}",
                    if rank.is_some() { " of one value" } else { "" }
                )));
            }
        }
    }
    let theta_i = grid(&f, "theta_i", "angles (radians)").map_err(at)?;
    let phi_i = grid(&f, "phi_i", "angles (radians)").map_err(at)?;
    let wavelengths = grid(&f, "wavelengths", "wavelengths (nm)").map_err(at)?;
    let (ndf, ndf_shape) = f32_field(&f, "ndf", 2).map_err(at)?;
    let (sigma, sigma_shape) = f32_field(&f, "sigma", 2).map_err(at)?;
    let (vndf, vs) = f32_field(&f, "vndf", 4).map_err(at)?;
    let (luminance, ls) = f32_field(&f, "luminance", 4).map_err(at)?;
    let (spectra, ss) = f32_field(&f, "spectra", 5).map_err(at)?;
    let (np, nt, nl) = (phi_i.len(), theta_i.len(), wavelengths.len());
    let check = |name: &str, shape: &[usize], want: &[usize]| {
        if shape == want {
            Ok(())
        } else {
            Err(at(format!(
                "field `{name}` has shape {shape:?}; phi_i, theta_i and wavelengths make it \
                 {want:?}"
            )))
        }
    };
    check("vndf", &vs, &[np, nt, vs[2], vs[3]])?;
    check("luminance", &ls, &[np, nt, ls[2], ls[2]])?;
    check("spectra", &ss, &[np, nt, nl, ls[2], ls[3]])?;
    for (name, s) in [
        ("ndf", &ndf_shape),
        ("sigma", &sigma_shape),
        ("vndf", &vs[2..].to_vec()),
    ] {
        if s[0] < 2 || s[1] < 2 {
            return Err(at(format!(
                "field `{name}`'s table is {s:?}: at least 2 × 2 is needed"
            )));
        }
    }
    if ls[2] < 2 {
        return Err(at(
            "field `luminance`'s table needs at least 2 × 2 nodes".into()
        ));
    }
    if np > 2 {
        // pbrt-v4 reads only files covering the full circle of azimuths (its "reduction" 1)
        let reduction = (2.0 * std::f32::consts::PI / (phi_i[np - 1] - phi_i[0])).round();
        if reduction != 1.0 {
            return Err(at(format!(
                "phi_i covers 1/{reduction} of the circle: only files covering all azimuths \
                 (reduction 1) are read, as in pbrt-v4"
            )));
        }
    }
    let finite = |name: &str, v: &[f32]| {
        if v.iter().all(|x| x.is_finite()) {
            Ok(())
        } else {
            Err(at(format!(
                "field `{name}` holds a value that is not finite"
            )))
        }
    };
    for (name, v) in [
        ("ndf", &ndf),
        ("sigma", &sigma),
        ("vndf", &vndf),
        ("luminance", &luminance),
        ("spectra", &spectra),
    ] {
        finite(name, v)?;
    }
    let jacobian = values(&f, "jacobian").map_err(at)?.0[0] != 0.0;
    Ok(RglTable {
        jacobian,
        theta_i,
        phi_i,
        wavelengths,
        ndf,
        ndf_size: [ndf_shape[1], ndf_shape[0]],
        sigma,
        sigma_size: [sigma_shape[1], sigma_shape[0]],
        vndf,
        vndf_size: [vs[3], vs[2]],
        luminance,
        sample_size: [ls[3], ls[2]],
        spectra,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::loader::mitsuba::tensor::write_tensor_file;

    /// The fields of a small valid file: 2 incidence angles, 1 azimuth, 2 wavelengths,
    /// 3 × 3 tables, with `spectra` given the shape `spectra_shape`.
    fn file(spectra_shape: Vec<u64>, drop: Option<&str>) -> Vec<u8> {
        let ones = |s: &[u64]| vec![1.0; s.iter().product::<u64>() as usize];
        let fields: Vec<(&str, u8, Vec<u64>, Vec<f32>)> = vec![
            ("description", 1, vec![3], vec![65.0, 66.0, 67.0]),
            ("jacobian", 1, vec![1], vec![1.0]),
            ("theta_i", 10, vec![2], vec![0.0, 1.0]),
            ("phi_i", 10, vec![1], vec![0.0]),
            ("wavelengths", 10, vec![2], vec![400.0, 700.0]),
            ("ndf", 10, vec![3, 3], ones(&[3, 3])),
            ("sigma", 10, vec![3, 3], ones(&[3, 3])),
            ("vndf", 10, vec![1, 2, 3, 3], ones(&[1, 2, 3, 3])),
            ("luminance", 10, vec![1, 2, 3, 3], ones(&[1, 2, 3, 3])),
            ("spectra", 10, spectra_shape.clone(), ones(&spectra_shape)),
        ];
        let kept: Vec<_> = fields.into_iter().filter(|f| Some(f.0) != drop).collect();
        write_tensor_file(&kept)
    }

    /// A valid file reads with its sizes; a missing field, a `spectra` whose wavelength count
    /// disagrees with `wavelengths`, and a truncated file are refused naming what is wrong.
    #[test]
    fn rgl_files_are_read_or_refused_with_the_field() {
        let dir = std::env::temp_dir().join(format!("spectrace-rgl-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("t.bsdf");
        std::fs::write(&p, file(vec![1, 2, 2, 3, 3], None)).unwrap();
        let t = read_rgl_bsdf(&p).expect("reads");
        assert_eq!(
            (t.theta_i.len(), t.sample_size, t.vndf_size),
            (2, [3, 3], [3, 3])
        );
        std::fs::write(&p, file(vec![1, 2, 2, 3, 3], Some("sigma"))).unwrap();
        assert!(read_rgl_bsdf(&p).unwrap_err().contains("no field `sigma`"));
        std::fs::write(&p, file(vec![1, 2, 5, 3, 3], None)).unwrap();
        let e = read_rgl_bsdf(&p).unwrap_err();
        assert!(e.contains("`spectra` has shape [1, 2, 5, 3, 3]"), "{e}");
        let bytes = file(vec![1, 2, 2, 3, 3], None);
        std::fs::write(&p, &bytes[..bytes.len() - 8]).unwrap();
        assert!(
            read_rgl_bsdf(&p)
                .unwrap_err()
                .contains("runs past the file's end")
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}
