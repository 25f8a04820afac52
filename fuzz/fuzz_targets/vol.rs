//! Mitsuba's `.vol` grid files, then the grid built from them and looked up.
#![no_main]

use libfuzzer_sys::fuzz_target;
use spectrace::medium::{Grid, Wrap};
use spectrace::spectrum::SampledWavelengths;

fuzz_target!(|data: &[u8]| {
    let Ok(v) = spectrace::loader::mitsuba::parse_vol(data) else {
        return;
    };
    let Ok(g) = Grid::new(v.res, v.channels, &v.values, Wrap::Repeat) else {
        return;
    };
    let w = SampledWavelengths::<4> {
        lambda: [400.0, 500.0, 600.0, 700.0],
        pdf: [1.0; 4],
    };
    for p in [glam::Vec3::ZERO, glam::Vec3::splat(0.5), glam::Vec3::new(-3.2, 7.9, 1.0)] {
        let x = g.eval(p, &w);
        assert!(x.is_finite(), "non-finite lookup {x:?}");
    }
});
