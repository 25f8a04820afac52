//! pbrt-v4 scene files (`.pbrt`) → [`SceneDesc`], read as pbrt-v4 reads them
//! (`src/pbrt/parser.cpp`, `scene.cpp`): the directives, the graphics state they change
//! (transformation, material, area light, orientation) and the parameter lists of each kind,
//! every error located at file:line:column; a parameter a kind does not read is an error, as
//! pbrt-v4 reports it.
//!
//! What is read so far is the subset in the README's pbrt-v4 table; any other directive or kind
//! is an error naming it.

mod area_light;
mod camera;
mod curves;
mod hair;
mod kinds;
mod lexer;
mod lights;
mod materials;
mod media;
mod meshes;
mod objects;
mod params;
mod placed;
mod quadrics;
mod roughness;
mod sensor;
mod shapes;
mod spectra;
mod textures;
mod transforms;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::DMat4;

use lexer::{Tok, Token, tokenize};
use params::{Params, R};

use super::desc::*;
use super::{LoadError, Loc};

/// Reads a pbrt-v4 scene file.
pub fn load(path: &Path) -> Result<SceneDesc, LoadError> {
    let text = read(path, path, Loc { line: 0, col: 0 })?;
    load_str(&text, path)
}

/// Reads pbrt-v4 scene text; `path` names it in errors and anchors relative file names.
pub fn load_str(text: &str, path: &Path) -> Result<SceneDesc, LoadError> {
    let mut r = Reader::new(path);
    r.run(text, path, 0)?;
    r.finish()
}

fn read(path: &Path, from: &Path, loc: Loc) -> R<String> {
    crate::files::read_text(path, crate::files::MAX_TEXT_BYTES).map_err(|e| {
        LoadError::new(
            from,
            loc,
            "",
            format!("cannot read {}: {e}", path.display()),
        )
    })
}

/// The graphics state `AttributeBegin` saves and `AttributeEnd` restores.
#[derive(Clone)]
struct State {
    /// The current transformation: object (or camera) space to world, pbrt's CTM inverted at
    /// use (pbrt stores world-from-object as its CTM).
    ctm: DMat4,
    /// The CTM at the shutter's close, which `ActiveTransform EndTime` changes alone; a
    /// consumer of the CTM refuses a scene where it differs from `ctm` (motion blur).
    ctm_end: DMat4,
    /// Which of (`ctm`, `ctm_end`) the transformation directives change (`ActiveTransform`).
    active: [bool; 2],
    reverse_orientation: bool,
    /// Index into the scene's materials (`None`: pbrt-v4's default diffuse, made on first use).
    material: Option<usize>,
    /// The current `AreaLightSource "diffuse"`, if any.
    area_light: Option<area_light::AreaLight>,
    /// `Attribute` parameters for shapes, lights, materials and textures, in the order given.
    attributes: Attributes,
    /// The current `MediumInterface`: the (inside, outside) media, indices into the scene's
    /// media (None: vacuum).
    media: (Option<usize>, Option<usize>),
}

/// The default parameters `Attribute "shape" | "light" | "material" | "texture"` set.
#[derive(Clone, Default)]
struct Attributes {
    shape: Vec<params::Param>,
    light: Vec<params::Param>,
    material: Vec<params::Param>,
    texture: Vec<params::Param>,
}

/// The reader's whole state, and the scene it builds.
struct Reader {
    root: PathBuf,
    state: State,
    stack: Vec<(State, Loc)>,
    named_materials: HashMap<String, usize>,
    /// Named coordinate systems: the CTM at the shutter's opening and close.
    coordinate_systems: HashMap<String, [DMat4; 2]>,
    in_world: bool,
    camera: Option<(DMat4, Params, String, Loc)>,
    film: Option<(Params, String, Loc)>,
    filter: Option<(Params, String, Loc)>,
    sampler: Option<(Params, String, Loc)>,
    integrator: Option<(Params, String, Loc)>,
    materials: Vec<MaterialDesc>,
    default_material: Option<usize>,
    shapes: Vec<ShapeDesc>,
    lights: Vec<LightDesc>,
    notes: Vec<String>,
    /// Named spectrum textures (`Texture "name" "spectrum" …`) and float ones (pbrt-v4 keeps
    /// the two apart: one name may be both).
    textures: HashMap<String, TextureDesc>,
    float_textures: HashMap<String, TextureDesc>,
    /// Media by name (`MakeNamedMedium`), and the camera's (the outside medium at `Camera`).
    media: Vec<MediumDesc>,
    named_media: HashMap<String, usize>,
    camera_medium: Option<usize>,
    /// Object definitions (`ObjectBegin`) by name, and the one being defined.
    groups: Vec<GroupDesc>,
    group_names: HashMap<String, usize>,
    defining: Option<usize>,
    instances: Vec<InstanceDesc>,
}

impl Reader {
    fn new(root: &Path) -> Self {
        Reader {
            root: root.to_path_buf(),
            state: State {
                ctm: DMat4::IDENTITY,
                ctm_end: DMat4::IDENTITY,
                active: [true; 2],
                reverse_orientation: false,
                material: None,
                area_light: None,
                attributes: Attributes::default(),
                media: (None, None),
            },
            stack: Vec::new(),
            textures: HashMap::new(),
            float_textures: HashMap::new(),
            media: Vec::new(),
            named_media: HashMap::new(),
            camera_medium: None,
            groups: Vec::new(),
            group_names: HashMap::new(),
            defining: None,
            instances: Vec::new(),
            named_materials: HashMap::new(),
            coordinate_systems: HashMap::new(),
            in_world: false,
            camera: None,
            film: None,
            filter: None,
            sampler: None,
            integrator: None,
            materials: Vec::new(),
            default_material: None,
            shapes: Vec::new(),
            lights: Vec::new(),
            notes: Vec::new(),
        }
    }

    /// Reads the directives of `text` (the file `file`, included `depth` deep).
    fn run(&mut self, text: &str, file: &Path, depth: u32) -> R<()> {
        let toks = tokenize(text, file)?;
        let mut i = 0;
        while i < toks.len() {
            let Token { kind, loc } = &toks[i];
            let loc = *loc;
            let Tok::Word(d) = kind else {
                return Err(LoadError::new(
                    file,
                    loc,
                    "",
                    "expected a directive (such as Shape or WorldBegin)",
                ));
            };
            i += 1;
            self.directive(d, &toks, &mut i, file, loc, depth)?;
        }
        Ok(())
    }

    fn directive(
        &mut self,
        d: &str,
        toks: &[Token],
        i: &mut usize,
        file: &Path,
        loc: Loc,
        depth: u32,
    ) -> R<()> {
        let err = |m: String| LoadError::new(file, loc, "", m);
        self.check_static(d, file, loc)?;
        match d {
            "Identity" | "Translate" | "Scale" | "Rotate" | "LookAt" | "Transform"
            | "ConcatTransform" | "CoordinateSystem" | "CoordSysTransform" => {
                self.transform(d, toks, i, file, loc)?;
            }
            "ReverseOrientation" => self.state.reverse_orientation ^= true,
            "AttributeBegin" | "TransformBegin" => self.stack.push((self.state.clone(), loc)),
            "AttributeEnd" | "TransformEnd" => {
                let Some((s, _)) = self.stack.pop() else {
                    return Err(err(format!("{d} without a matching begin")));
                };
                if d == "TransformEnd" {
                    (self.state.ctm, self.state.ctm_end) = (s.ctm, s.ctm_end);
                    self.state.active = s.active;
                } else {
                    self.state = s;
                }
            }
            "WorldBegin" => {
                self.in_world = true;
                self.coordinate_systems
                    .insert("world".into(), [DMat4::IDENTITY; 2]);
                (self.state.ctm, self.state.ctm_end) = (DMat4::IDENTITY, DMat4::IDENTITY);
                self.state.active = [true; 2];
            }
            "Include" | "Import" => {
                let name = Self::string_arg(toks, i, file, d, loc)?;
                if depth >= 32 {
                    return Err(err("files include each other more than 32 deep".into()));
                }
                let path = self.resolve(file, &name);
                let text = read(&path, file, loc)?;
                self.run(&text, &path, depth + 1)?;
            }
            "Camera" | "Film" | "Sampler" | "Integrator" | "PixelFilter" | "Accelerator"
            | "ColorSpace" | "Option" => {
                let kind = Self::string_arg(toks, i, file, d, loc)?;
                if d == "Option" {
                    // `Option "type name" value`: the name was the declaration; skip its value
                    self.notes.push(format!(
                        "{}:{loc}: Option \"{kind}\" ignored",
                        file.display()
                    ));
                    skip_values(toks, i);
                    return Ok(());
                }
                let p = Params::parse(toks, i, file)?;
                self.options(d, kind, p, loc, file)?;
            }
            "MakeNamedMaterial" | "Material" | "NamedMaterial" => {
                self.material_directive(d, toks, i, file, loc)?;
            }
            "AreaLightSource" => {
                let kind = Self::string_arg(toks, i, file, d, loc)?;
                let p = Params::parse(toks, i, file)?.with_defaults(&self.state.attributes.light);
                self.state.area_light = Some(area_light::area_light(&kind, &p, loc, self)?);
                p.check_unused(&format!("area light \"{kind}\""))?;
            }
            "LightSource" => {
                let kind = Self::string_arg(toks, i, file, d, loc)?;
                let p = Params::parse(toks, i, file)?.with_defaults(&self.state.attributes.light);
                let l = lights::light(&kind, &p, &self.state.ctm, loc, self)?;
                p.check_unused(&format!("light \"{kind}\""))?;
                self.lights.push(l);
            }
            "Shape" => {
                let kind = Self::string_arg(toks, i, file, d, loc)?;
                let p = Params::parse(toks, i, file)?.with_defaults(&self.state.attributes.shape);
                let shapes = shapes::shape(&kind, &p, loc, self, file)?;
                p.check_unused(&format!("shape \"{kind}\""))?;
                self.add_shapes(shapes).map_err(err)?;
            }
            "ObjectBegin" | "ObjectInstance" => {
                let name = Self::string_arg(toks, i, file, d, loc)?;
                self.instancing(d, Some(name), loc).map_err(err)?;
            }
            "ObjectEnd" => self.instancing(d, None, loc).map_err(err)?,
            "Texture" => self.texture_directive(d, toks, i, file, loc)?,
            "Attribute" => {
                let target = Self::string_arg(toks, i, file, d, loc)?;
                let p = Params::parse(toks, i, file)?;
                let a = &mut self.state.attributes;
                let list = match target.as_str() {
                    "shape" => &mut a.shape,
                    "light" => &mut a.light,
                    "material" => &mut a.material,
                    "texture" => &mut a.texture,
                    "medium" => {
                        return Err(err(
                            "Attribute \"medium\" is not read yet (spectrace's pbrt-v4 reader reads no media)".into(),
                        ));
                    }
                    other => {
                        return Err(err(format!(
                            "unknown Attribute target \"{other}\" (pbrt-v4's are shape, light, material, medium and texture)"
                        )));
                    }
                };
                list.extend(p.list);
            }
            "MakeNamedMedium" | "MediumInterface" => {
                self.medium_directive(d, toks, i, file, loc)?;
            }
            "TransformTimes" | "ActiveTransform" => self.transform(d, toks, i, file, loc)?,
            other => return Err(err(format!("unknown directive \"{other}\""))),
        }
        Ok(())
    }

    /// The named materials defined so far, by name (for `mix`).
    fn named(&self) -> materials::Named<'_> {
        materials::Named {
            index: &self.named_materials,
            materials: &self.materials,
            textures: &self.textures,
            float_textures: &self.float_textures,
            base: self.root.parent().unwrap_or(Path::new(".")),
        }
    }

    pub(super) fn resolve(&self, from: &Path, name: &str) -> PathBuf {
        let p = Path::new(name);
        if p.is_absolute() {
            return p.to_path_buf();
        }
        // pbrt-v4 resolves against the directory of the first file read
        let base = self
            .root
            .parent()
            .or(from.parent())
            .unwrap_or(Path::new("."));
        base.join(p)
    }

    /// The scene-wide options (`Camera`, `Film`, `Sampler`, `Integrator`, …), read at the end.
    fn options(&mut self, d: &str, kind: String, p: Params, loc: Loc, file: &Path) -> R<()> {
        let slot = match d {
            "Camera" => {
                // the camera's space is where the CTM stands; pbrt names it "camera"
                self.coordinate_systems.insert(
                    "camera".into(),
                    [self.state.ctm.inverse(), self.state.ctm_end.inverse()],
                );
                self.camera = Some((self.state.ctm, p, kind, loc));
                self.camera_medium = self.state.media.1;
                return Ok(());
            }
            "Film" => &mut self.film,
            "PixelFilter" => &mut self.filter,
            "ColorSpace" if kind != "srgb" => {
                return Err(p.err(
                    loc,
                    format!("the colour space \"{kind}\" is not read yet (spectrace reads srgb)"),
                ));
            }
            "Sampler" => &mut self.sampler,
            "Integrator" => &mut self.integrator,
            _ => {
                // accelerators and the sRGB colour space change nothing spectrace computes
                drop(p);
                self.notes
                    .push(format!("{}:{loc}: {d} \"{kind}\" ignored", file.display()));
                return Ok(());
            }
        };
        *slot = Some((p, kind, loc));
        Ok(())
    }

    fn finish(self) -> Result<SceneDesc, LoadError> {
        kinds::finish(self)
    }
}

/// Skips an `Option`'s value (one token or a bracketed list).
fn skip_values(toks: &[Token], i: &mut usize) {
    match toks.get(*i) {
        Some(Token {
            kind: Tok::Open, ..
        }) => {
            while let Some(t) = toks.get(*i) {
                *i += 1;
                if t.kind == Tok::Close {
                    break;
                }
            }
        }
        Some(_) => *i += 1,
        None => {}
    }
}
