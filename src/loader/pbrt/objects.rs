//! pbrt-v4's object instancing (`ObjectBegin`, `ObjectEnd`, `ObjectInstance`) and where a
//! `Shape`'s shapes go: the scene, or the object being defined.

use super::Reader;
use crate::loader::Loc;
use crate::loader::desc::{GroupDesc, InstanceDesc, ShapeDesc};

impl Reader {
    /// `ObjectBegin "name"`, `ObjectEnd` and `ObjectInstance "name"`: an object's shapes are
    /// defined under their own transformations and placed by the CTM at each instance.
    pub(super) fn instancing(
        &mut self,
        d: &str,
        name: Option<String>,
        loc: Loc,
    ) -> Result<(), String> {
        let name = name.unwrap_or_default();
        match d {
            "ObjectBegin" => {
                if self.defining.is_some() {
                    return Err("ObjectBegin inside another object definition".into());
                }
                if self.group_names.contains_key(&name) {
                    return Err(format!("the object \"{name}\" is defined twice"));
                }
                // pbrt-v4: an object definition opens an attribute block
                self.stack.push((self.state.clone(), loc));
                self.groups.push(GroupDesc {
                    id: name.clone(),
                    shapes: Vec::new(),
                    loc,
                });
                self.group_names.insert(name, self.groups.len() - 1);
                self.defining = Some(self.groups.len() - 1);
            }
            "ObjectEnd" => {
                let (Some(_), Some((s, _))) = (self.defining.take(), self.stack.pop()) else {
                    return Err("ObjectEnd without ObjectBegin".into());
                };
                self.state = s;
            }
            _ => {
                if self.defining.is_some() {
                    return Err("ObjectInstance inside an object definition".into());
                }
                let Some(&g) = self.group_names.get(&name) else {
                    return Err(format!("no object named \"{name}\""));
                };
                self.instances.push(InstanceDesc {
                    group: g,
                    transform: vec![super::placed::matrix_step(&self.state.ctm)],
                    unit_m: 1.0,
                    loc,
                });
            }
        }
        Ok(())
    }

    /// A `Shape`'s shapes, into the object being defined or the scene. An area light inside an
    /// object is an error (pbrt-v4 drops its emission).
    pub(super) fn add_shapes(&mut self, shapes: Vec<ShapeDesc>) -> Result<(), String> {
        match self.defining {
            Some(g) => {
                if self.state.area_light.is_some() {
                    return Err("an area light inside an object definition (pbrt-v4 does not support it and drops its emission)".into());
                }
                self.groups[g].shapes.extend(shapes);
            }
            None => self.shapes.extend(shapes),
        }
        Ok(())
    }
}
