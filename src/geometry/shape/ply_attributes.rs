//! A PLY file's other vertex and face properties as Mitsuba 3's mesh attributes
//! (`src/shapes/ply.h`, `find_other_fields`): consecutive properties `{prefix}_{x|y|z|w}`,
//! `_{r|g|b|a}`, `_{0|1|2|3}` or `_{1|2|3|4}` form one attribute `{vertex|face}_{prefix}` of one or
//! three fields (`_color` appended for `r g b`), and bare `r g b` (or `red green blue`) form
//! `{vertex|face}_color`. A fourth field (alpha, w) is dropped; groups of two fields and
//! properties without a postfix are skipped, as Mitsuba skips them. Integer values are kept as
//! stored (a uchar colour is 0–255, as in Mitsuba).

use super::ply_header::Elem;

/// One attribute: `dim` (1 or 3) values per vertex of the file, or per triangle of the fans a
/// face is split into (`per_face`), flattened.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshAttribute {
    /// Mitsuba's name: `vertex_color`, `face_weight`, …
    pub name: String,
    pub per_face: bool,
    pub dim: usize,
    pub values: Vec<f32>,
}

/// The attribute columns of one element while its entries are read.
pub(super) struct Columns {
    /// (name, property indices of its fields) per attribute.
    groups: Vec<(String, Vec<usize>)>,
    /// Values per property index, for the properties some group uses.
    values: Vec<Vec<f32>>,
}

const POSTFIXES: [[&str; 4]; 4] = [
    ["x", "y", "z", "w"],
    ["r", "g", "b", "a"],
    ["0", "1", "2", "3"],
    ["1", "2", "3", "4"],
];

impl Columns {
    /// The attribute groups of element `elem` (none if the file has no such element), named
    /// with `kind` (`vertex_` or `face_`).
    pub(super) fn new(kind: &str, elems: &[Elem], elem: &str) -> Columns {
        let mut groups = Vec::new();
        let n_props = elems
            .iter()
            .find(|e| e.name == elem)
            .map_or(0, |e| e.props.len());
        if let Some(e) = elems.iter().find(|e| e.name == elem) {
            let reserved = [
                "x",
                "y",
                "z",
                "nx",
                "ny",
                "nz",
                "u",
                "v",
                "s",
                "t",
                "texture_u",
                "texture_v",
            ];
            let names: Vec<&str> = e.props.iter().map(|p| p.name.as_str()).collect();
            let scalar = |i: usize| e.props[i].list.is_none();
            // bare colours
            let find = |a: &str, b: &str| {
                names
                    .iter()
                    .position(|n| *n == a || *n == b)
                    .filter(|&i| scalar(i))
            };
            let bare = [find("r", "red"), find("g", "green"), find("b", "blue")];
            if let [Some(r), Some(g), Some(b)] = bare {
                groups.push((format!("{kind}color"), vec![r, g, b]));
            }
            let mut i = 0;
            while i < names.len() {
                let name = names[i];
                let skip = reserved.contains(&name)
                    || !scalar(i)
                    || ["r", "g", "b", "a", "red", "green", "blue", "alpha"].contains(&name);
                let Some((prefix, post)) = name.rsplit_once('_').filter(|_| !skip) else {
                    i += 1;
                    continue;
                };
                let Some(cat) = POSTFIXES.iter().position(|c| c[0] == post) else {
                    i += 1;
                    continue;
                };
                // the longest run prefix_{c0}, prefix_{c1}, … of consecutive scalar properties
                let mut fields = vec![i];
                while fields.len() < 4 {
                    let j = i + fields.len();
                    let want = format!("{prefix}_{}", POSTFIXES[cat][fields.len()]);
                    if j < names.len() && names[j] == want && scalar(j) {
                        fields.push(j);
                    } else {
                        break;
                    }
                }
                i += fields.len();
                if fields.len() == 2 {
                    continue;
                }
                fields.truncate(if fields.len() == 1 { 1 } else { 3 });
                let colour = if cat == 1 { "_color" } else { "" };
                groups.push((format!("{kind}{prefix}{colour}"), fields));
            }
        }
        Columns {
            groups,
            values: vec![Vec::new(); n_props],
        }
    }

    /// Records property `prop`'s value for the current entry.
    pub(super) fn push(&mut self, prop: usize, x: f64) {
        if self.groups.iter().any(|(_, f)| f.contains(&prop)) {
            self.values[prop].push(x as f32);
        }
    }

    /// The attributes read.
    pub(super) fn attributes(self, per_face: bool) -> Vec<MeshAttribute> {
        self.groups
            .iter()
            .map(|(name, fields)| {
                let n = self.values[fields[0]].len();
                let mut values = Vec::with_capacity(n * fields.len());
                for k in 0..n {
                    for &f in fields {
                        values.push(self.values[f].get(k).copied().unwrap_or(0.0));
                    }
                }
                MeshAttribute {
                    name: name.clone(),
                    per_face,
                    dim: fields.len(),
                    values,
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use crate::geometry::shape::Mesh;
    use crate::geometry::transform::Transform;
    use std::path::Path;

    /// Mitsuba's grouping: `color_0..2` per vertex is `vertex_color`, bare `red green blue` per
    /// face is `face_color`, `weight_0` is a one-field `face_weight`, `n_x n_y` (two fields) and
    /// `temperature` (no postfix) are skipped; face values repeat for each fan triangle.
    #[test]
    fn attributes_are_grouped_as_mitsuba_groups_them() {
        let ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty float color_0\nproperty float color_1\nproperty float color_2\nproperty float n_x\nproperty float n_y\nproperty float temperature\nelement face 1\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nproperty float weight_0\nend_header\n0 0 0 .1 .2 .3 9 9 9\n1 0 0 .4 .5 .6 9 9 9\n1 1 0 .7 .8 .9 9 9 9\n0 1 0 1 1 1 9 9 9\n4 0 1 2 3 255 128 0 0.25\n";
        let (mesh, attrs) =
            Mesh::parse_ply(ply.as_bytes(), Path::new("a.ply"), &Transform::identity()).unwrap();
        assert_eq!(mesh.triangle_count(), 2);
        let names: Vec<(&str, bool, usize)> = attrs
            .iter()
            .map(|a| (a.name.as_str(), a.per_face, a.dim))
            .collect();
        assert_eq!(
            names,
            [
                ("vertex_color", false, 3),
                ("face_color", true, 3),
                ("face_weight", true, 1)
            ]
        );
        assert_eq!(attrs[0].values.len(), 12);
        assert_eq!(attrs[0].values[3..6], [0.4, 0.5, 0.6]);
        assert_eq!(attrs[1].values, [255.0, 128.0, 0.0, 255.0, 128.0, 0.0]);
        assert_eq!(attrs[2].values, [0.25, 0.25]);
    }
}
