//! The immutable render-ready scene, and `build`, which makes it from a description.

use crate::loader::{LoadError, SceneDesc};

/// Placeholder until the build step lands.
pub struct Scene;

pub fn build(_desc: &SceneDesc) -> Result<Scene, LoadError> {
    Ok(Scene)
}
