//! Mitsuba `<transform>` children → transform steps, in order.

use super::cx::{Cx, R};
use super::xml::Element;
use crate::loader::desc::TransformStep;
use crate::units::{Angle, Length, angle, length};

impl Cx<'_> {
    /// `to_world` steps in order.
    pub(super) fn transform(&self, t: &Element) -> R<Vec<TransformStep>> {
        let m = |x: f64| Length::new::<length::meter>(x);
        let mut steps = Vec::new();
        for c in &t.children {
            steps.push(match c.tag.as_str() {
                "translate" => TransformStep::Translate(self.vec3(c)?.map(m)),
                "scale" => TransformStep::Scale({
                    let mut s = self.vec3(c)?;
                    if c.attr("value").is_none() {
                        for (i, k) in ["x", "y", "z"].iter().enumerate() {
                            if c.attr(k).is_none() {
                                s[i] = 1.0;
                            }
                        }
                    }
                    s
                }),
                "rotate" => {
                    let a = c
                        .attr("angle")
                        .ok_or_else(|| self.err(c, "missing angle (degrees)"))?;
                    let deg = self.floats(c, a)?.first().copied().unwrap_or(0.0);
                    let axis = match c.attr("value") {
                        Some(_) => self.vec3(c)?,
                        None => self.vec3(c)?,
                    };
                    if axis == [0.0; 3] {
                        return Err(self.err(c, "the rotation axis is zero"));
                    }
                    TransformStep::Rotate {
                        axis,
                        angle: Angle::new::<angle::degree>(deg),
                    }
                }
                "matrix" => {
                    let v = c
                        .attr("value")
                        .ok_or_else(|| self.err(c, "missing value"))?;
                    let f = self.floats(c, v)?;
                    if f.len() != 16 {
                        return Err(self.err(c, format!("expected 16 numbers, found {}", f.len())));
                    }
                    let mut a = [0.0; 16];
                    a.copy_from_slice(&f);
                    TransformStep::Matrix(a)
                }
                "lookat" => {
                    let g = |k: &str| -> R<[f64; 3]> {
                        let v = c
                            .attr(k)
                            .ok_or_else(|| self.err(c, format!("missing {k}")))?;
                        let f = self.floats(c, v)?;
                        if f.len() != 3 {
                            return Err(self.err(c, format!("{k}: expected 3 numbers")));
                        }
                        Ok([f[0], f[1], f[2]])
                    };
                    TransformStep::LookAt {
                        eye: g("origin")?.map(m),
                        target: g("target")?.map(m),
                        up: if c.attr("up").is_some() {
                            g("up")?
                        } else {
                            [0.0, 1.0, 0.0]
                        },
                    }
                }
                other => return Err(self.unsupported(c, "transform", other)),
            });
        }
        Ok(steps)
    }
}
