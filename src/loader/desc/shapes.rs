//! Shapes, their transforms and emission, groups and instances.

use super::*;

#[derive(Clone, Debug)]
pub enum TransformStep {
    Translate(Point),
    Rotate {
        axis: [f64; 3],
        angle: Angle,
    },
    Scale([f64; 3]),
    /// Row-major 4×4; the translation column is in the scene's length unit, converted to metres.
    Matrix([f64; 16]),
    LookAt {
        eye: Point,
        target: Point,
        up: [f64; 3],
    },
}

#[derive(Clone, Debug)]
pub enum ShapeKind {
    Sphere {
        center: Point,
        radius: Length,
    },
    /// The square [-1, 1]² in the object's z = 0 plane, normal +z, scaled by the length unit.
    Rectangle,
    /// The cube [-1, 1]³, scaled by the length unit.
    Box,
    /// The unit disk in the object's z = 0 plane, normal +z, scaled by the length unit.
    Disk,
    /// pbrt-v4's sphere: the sphere of `radius` about the object origin, the part at heights
    /// `z` (either order) and azimuths [0, `phi_max`] from object +x toward +y, with pbrt-v4's
    /// uv (whole: z = ±radius, φ_max = 360°).
    PbrtSphere {
        radius: Length,
        z: [Length; 2],
        phi_max: crate::units::Angle,
    },
    /// pbrt-v4's cylinder: the open tube of `radius` around object z between the heights `z`,
    /// at azimuths [0, `phi_max`] from object +x toward +y, with pbrt-v4's uv.
    PbrtCylinder {
        radius: Length,
        z: [Length; 2],
        phi_max: crate::units::Angle,
    },
    /// pbrt-v4's disk: [`ShapeKind::Disk`] without the disk of radius `inner` (a fraction of
    /// the disk's radius) and beyond azimuth `phi_max`, with pbrt-v4's uv.
    PbrtDisk {
        inner: f64,
        phi_max: crate::units::Angle,
    },
    /// The open tube of `radius` around the segment `p0`–`p1` (Mitsuba's `cylinder`), normals
    /// away from the axis unless `flipped`.
    Cylinder {
        p0: Point,
        p1: Point,
        radius: Length,
        flipped: bool,
    },
    /// A Wavefront OBJ mesh; coordinates in the scene's length unit.
    Obj {
        path: PathBuf,
        normals: MeshNormals,
    },
    /// Mesh `shape_index` of a Mitsuba `.serialized` file; coordinates in the scene's length
    /// unit.
    Serialized {
        path: PathBuf,
        shape_index: usize,
        normals: MeshNormals,
    },
    /// A Stanford PLY mesh; coordinates in the scene's length unit.
    Ply {
        path: PathBuf,
        normals: MeshNormals,
    },
    /// Mitsuba's `linearcurve` file (`x y z radius` per control point, an empty line between
    /// curves); positions in the scene's length unit, radii in m untouched by the transform.
    LinearCurve {
        path: PathBuf,
    },
    /// Mitsuba's `bsplinecurve`, from a file like `linearcurve`'s (four control points or more
    /// per curve).
    BSplineCurve {
        path: PathBuf,
    },
    /// Uniform cubic B-spline curves written in the scene (as `BSplineCurve`'s): per curve,
    /// four control points or more, each a point in the scene's length unit (placed by the
    /// shape's transform) and a radius in m (not transformed; a control radius may be ≤ 0
    /// where the spline's radius stays positive, as a taper's outer control values are).
    BSplinePoints {
        curves: Vec<Vec<([f64; 3], f64)>>,
        /// Hit and shaded as pbrt-v4's curves of this type (`BSplineCurve::with_pbrt_shading`);
        /// None: round tubes, as Mitsuba's.
        pbrt: Option<crate::geometry::shape::PbrtCurve>,
        /// A pbrt-v4 `ribbon`'s normals at each segment's start and end (in the shape's
        /// frame, placed by its transform as normals); empty for other curves.
        ribbon_normals: Vec<[[f64; 3]; 2]>,
    },
    /// Mitsuba's `sdfgrid`: distances at `res` points (x fastest) over the object's unit cube;
    /// `smooth` shading normals or the gradient's.
    SdfGrid {
        res: [usize; 3],
        values: std::sync::Arc<Vec<f32>>,
        smooth: bool,
    },
    /// A triangle mesh written in the scene file: vertices in the scene's length unit and
    /// 0-based triangle indices; optional per-vertex shading normals (object space, any
    /// length) and surface coordinates.
    Inline {
        vertices: Vec<[f64; 3]>,
        faces: Vec<[u32; 3]>,
        normals: Option<Vec<[f64; 3]>>,
        uvs: Option<Vec<[f64; 2]>>,
    },
}

/// The vertex normals a mesh file is shaded with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshNormals {
    /// The file's normals; face normals (flat shading) if it has none. spectrace's native
    /// reading.
    FromFile,
    /// The file's normals; if it has none, smooth normals computed from the faces, weighted by
    /// angle (Mitsuba 3's default for `obj` and `ply`).
    FromFileOrSmooth,
    /// Face normals only, whatever the file holds (Mitsuba's `face_normals = true`).
    Flat,
}

#[derive(Clone, Debug)]
pub enum EmitAmount {
    Radiance(Radiance),
    Luminance(Luminance),
    Power(Power),
    LuminousFlux(LuminousFlux),
    /// The spectrum is already spectral radiance in W·m⁻²·sr⁻¹·nm⁻¹; multiply by this.
    Scale(f64),
}

#[derive(Clone, Debug)]
pub struct EmissionDesc {
    pub spectrum: Spectrum,
    /// A radiance that varies over the surface (Mitsuba's textured `radiance`), in place of
    /// `spectrum`, read as given (W·m⁻²·sr⁻¹·nm⁻¹ per texel value).
    pub texture: Option<TextureDesc>,
    pub amount: EmitAmount,
    pub two_sided: bool,
    /// As [`LightDesc::sampling_weight`].
    pub sampling_weight: f64,
    pub loc: Loc,
}

#[derive(Clone, Debug)]
pub struct ShapeDesc {
    pub kind: ShapeKind,
    /// Applied in order, first to last, after converting the object to metres.
    pub transform: Vec<TransformStep>,
    /// Index into `SceneDesc::materials`; None for a pure emitter (black).
    pub material: Option<usize>,
    pub two_sided: bool,
    pub emission: Option<EmissionDesc>,
    /// Indices into `SceneDesc::media` of the media inside and outside the shape (the sides
    /// its normal points away from and to); None for vacuum. A shape that names neither does
    /// not change the medium of a ray that crosses it.
    pub interior: Option<usize>,
    pub exterior: Option<usize>,
    /// Metres per scene length unit (for OBJ coordinates and unit shapes).
    pub unit_m: f64,
    /// An alpha test (pbrt-v4's `alpha`): a grey texture in [0, 1], the fraction of rays that
    /// meet the surface where it is looked up (`crate::geometry::Accel::with_alpha`); None:
    /// opaque. Not in a group.
    pub alpha: Option<TextureDesc>,
    pub loc: Loc,
}

/// Shapes in their own object space, drawn once per instance: one BVH per group, so that a
/// thousand instances cost one group's memory (Mitsuba's `shapegroup`). No emitters.
#[derive(Clone, Debug)]
pub struct GroupDesc {
    pub id: String,
    pub shapes: Vec<ShapeDesc>,
    pub loc: Loc,
}

/// A group placed by a transform (Mitsuba's `instance`).
#[derive(Clone, Debug)]
pub struct InstanceDesc {
    /// Index into `SceneDesc::groups`.
    pub group: usize,
    /// Applied in order, first to last (metres; a matrix's translation in `unit_m` metres).
    pub transform: Vec<TransformStep>,
    /// Metres per scene length unit.
    pub unit_m: f64,
    pub loc: Loc,
}
