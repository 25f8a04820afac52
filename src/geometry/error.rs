//! The one error type of the geometry module.
//!
//! Every constructor that takes user data (radii, matrices, meshes, camera parameters) checks it
//! and returns a [`GeometryError`] instead of panicking. Messages name the offending value so that
//! the scene loader can pass them on unchanged.

use std::path::PathBuf;

/// Invalid geometric input. The `Display` text is meant for users of scene files.
#[derive(Debug, thiserror::Error)]
pub enum GeometryError {
    /// A value that must be finite is NaN or infinite.
    #[error("{what} is not finite (got {value})")]
    NotFinite { what: &'static str, value: String },

    /// A length, radius or similar that must be > 0.
    #[error("{what} must be positive, got {value}")]
    NotPositive { what: &'static str, value: f32 },

    /// A value outside its allowed interval, e.g. a field of view outside (0, π).
    #[error("{what} = {value} is outside {allowed}")]
    OutOfRange {
        what: &'static str,
        value: f32,
        allowed: &'static str,
    },

    /// A zero-sized or absurdly large image resolution.
    #[error(
        "resolution {width}x{height} is invalid: each side must be in 1..=32768 and the \
         image at most 2^28 pixels"
    )]
    Resolution { width: u32, height: u32 },

    /// A matrix that cannot be inverted (or whose inverse is not finite).
    #[error("transform matrix is singular (determinant {determinant}); it cannot be inverted")]
    SingularMatrix { determinant: f32 },

    /// A matrix whose bottom row is not (0, 0, 0, 1).
    #[error(
        "transform matrix is projective (bottom row {row:?}); only affine transforms are supported"
    )]
    NotAffine { row: [f32; 4] },

    /// `look_at` with coincident eye and target or an up vector parallel to the view direction.
    #[error("look_at: {0}")]
    LookAt(&'static str),

    /// A rotation axis of zero length.
    #[error("rotation axis must be non-zero, got {0:?}")]
    ZeroAxis([f32; 3]),

    /// Spheres are kept as (centre, radius); a transform that is not a similarity would make
    /// an ellipsoid, which is not supported.
    #[error(
        "spheres do not support non-uniform scaling or shear (transform scales axes by \
         {scales:?}); use a mesh for ellipsoids"
    )]
    NonUniformScale { scales: [f32; 3] },

    /// A mesh with no triangles, or whose triangles all have zero area.
    #[error("mesh {0}")]
    EmptyMesh(&'static str),

    /// A vertex index that does not name a vertex.
    #[error(
        "mesh triangle {triangle} uses vertex index {index}, but the mesh has {count} vertices"
    )]
    IndexOutOfRange {
        triangle: usize,
        index: u32,
        count: usize,
    },

    /// A per-vertex attribute array of the wrong length.
    #[error("mesh has {positions} positions but {got} {what}; they must match")]
    AttributeCount {
        what: &'static str,
        got: usize,
        positions: usize,
    },

    /// A mesh attribute that is NaN or infinite.
    #[error("mesh {what} {index} is not finite: {value}")]
    NonFiniteAttribute {
        what: &'static str,
        index: usize,
        value: String,
    },

    /// A mesh file that cannot be opened or read.
    #[error("cannot open mesh {}: {source}", path.display())]
    MeshOpen {
        path: PathBuf,
        source: std::io::Error,
    },

    /// Curves whose control points cannot make a tube.
    #[error("curve: {0}")]
    Curve(String),

    /// A mesh file that cannot be parsed, or whose contents are invalid.
    #[error("malformed mesh file {}: {message}", path.display())]
    MeshParse { path: PathBuf, message: String },
}

/// `Ok(x)` if `x` is finite, else a [`GeometryError::NotFinite`] naming `what`.
pub(crate) fn check_finite(what: &'static str, x: f32) -> Result<f32, GeometryError> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(GeometryError::NotFinite {
            what,
            value: x.to_string(),
        })
    }
}

/// `Ok(v)` if every component of `v` is finite.
pub(crate) fn check_finite3(
    what: &'static str,
    v: glam::Vec3,
) -> Result<glam::Vec3, GeometryError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(GeometryError::NotFinite {
            what,
            value: format!("{v}"),
        })
    }
}

/// `Ok(x)` if `x` is finite and > 0.
pub(crate) fn check_positive(what: &'static str, x: f32) -> Result<f32, GeometryError> {
    check_finite(what, x)?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(GeometryError::NotPositive { what, value: x })
    }
}
