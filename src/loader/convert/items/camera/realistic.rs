//! `type = "realistic"`: a lens file (pbrt-v4's format) in front of a film.
//!
//! ```toml
//! [camera]
//! type = "realistic"
//! eye = [0, 0.1, 2]              # the centre of the film
//! target = [0, 0.1, 0]
//! lens_file = "dgauss50.lens"
//! film_diagonal = "43.3 mm"      # default 35 mm, as pbrt-v4
//! aperture_diameter = "10 mm"    # optional: stop the lens down
//! focus_distance = "2 m"         # optional, from the film; or film_distance = "40 mm"
//! ```

use super::*;
use crate::loader::desc::LensFocus;

pub(super) fn realistic(cx: &Cx<'_>, c: &RawCamera, sp: &Range<usize>) -> R<CameraKind> {
    let file = cx.required(
        &c.lens_file,
        sp,
        "camera.lens_file",
        "a lens file (pbrt-v4's format: radius thickness index aperture per line, mm)",
    )?;
    let lens = crate::loader::lens::read(&cx.path(file.get_ref()))?;
    let positive = |v: &S<Value>, field: &str| -> R<Length> {
        let l = cx.length(v, field)?;
        if l.get::<length::meter>() > 0.0 && l.get::<length::meter>().is_finite() {
            Ok(l)
        } else {
            Err(cx.err(&v.span(), field, "expected a positive length"))
        }
    };
    let film_diagonal = match &c.film_diagonal {
        Some(v) => positive(v, "camera.film_diagonal")?,
        None => Length::new::<length::millimeter>(35.0),
    };
    let aperture_diameter = match &c.aperture_diameter {
        Some(v) => Some(positive(v, "camera.aperture_diameter")?),
        None => None,
    };
    let focus = match (&c.focus_distance, &c.film_distance) {
        (Some(_), Some(f)) => {
            return Err(cx.err(
                &f.span(),
                "camera.film_distance",
                "give either `focus_distance` or `film_distance`, not both",
            ));
        }
        (Some(v), None) => LensFocus::Distance(positive(v, "camera.focus_distance")?),
        (None, Some(v)) => LensFocus::FilmDistance(positive(v, "camera.film_distance")?),
        (None, None) => LensFocus::AsWritten,
    };
    Ok(CameraKind::Realistic {
        lens,
        film_diagonal,
        aperture_diameter,
        focus,
        irradiance_pixels: false,
    })
}
