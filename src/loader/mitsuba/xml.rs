//! A small element tree from quick-xml, with byte offsets for error locations.

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

/// One XML element: tag, attributes in order, children, and the byte offset of its start tag.
#[derive(Clone, Debug)]
pub struct Element {
    pub tag: String,
    pub attrs: Vec<(String, String)>,
    pub children: Vec<Element>,
    pub pos: usize,
    /// Which source file the element came from (index into the importer's file list).
    pub src: usize,
}

impl Element {
    /// Marks this element and its descendants as coming from source `src`.
    pub fn set_source(&mut self, src: usize) {
        self.src = src;
        for c in &mut self.children {
            c.set_source(src);
        }
    }

    pub fn attr(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }
}

/// Why the XML could not be read: a byte offset and a message.
#[derive(Debug, Clone)]
pub struct XmlError {
    pub pos: usize,
    pub message: String,
}

fn start(e: &BytesStart<'_>, pos: usize) -> Result<Element, XmlError> {
    let tag = AsRef::<str>::as_ref(&e.name()).to_string();
    let mut attrs = Vec::new();
    for a in e.attributes() {
        let a = a.map_err(|err| XmlError {
            pos,
            message: format!("bad attribute in <{tag}>: {err}"),
        })?;
        let key = AsRef::<str>::as_ref(&a.key).to_string();
        let value = a
            .normalized_value(quick_xml::XmlVersion::Implicit1_0)
            .map_err(|err| XmlError {
                pos,
                message: format!("bad value of {key} in <{tag}>: {err}"),
            })?
            .into_owned();
        attrs.push((key, value));
    }
    Ok(Element {
        tag,
        attrs,
        children: Vec::new(),
        pos,
        src: 0,
    })
}

/// Elements nested in one another at most: real scenes nest a few levels; the tree's
/// recursive walks (and its drop) must not exhaust the stack.
const MAX_NESTING: usize = 64;

/// Parses a document into its root element.
pub fn parse(text: &str) -> Result<Element, XmlError> {
    let mut r = Reader::from_str(text);
    let mut stack: Vec<Element> = Vec::new();
    let mut root: Option<Element> = None;
    loop {
        let pos = r.buffer_position() as usize;
        let ev = r.read_event().map_err(|e| XmlError {
            pos: r.error_position() as usize,
            message: e.to_string(),
        })?;
        match ev {
            Event::Start(e) => {
                if stack.len() >= MAX_NESTING {
                    return Err(XmlError {
                        pos,
                        message: format!("elements nest more than {MAX_NESTING} deep"),
                    });
                }
                stack.push(start(&e, pos)?)
            }
            Event::Empty(e) => {
                let el = start(&e, pos)?;
                match stack.last_mut() {
                    Some(parent) => parent.children.push(el),
                    None => root = Some(el),
                }
            }
            Event::End(_) => {
                let Some(el) = stack.pop() else {
                    return Err(XmlError {
                        pos,
                        message: "closing tag without an opening tag".into(),
                    });
                };
                match stack.last_mut() {
                    Some(parent) => parent.children.push(el),
                    None => root = Some(el),
                }
            }
            Event::Eof => break,
            _ => {}
        }
    }
    if let Some(open) = stack.last() {
        return Err(XmlError {
            pos: open.pos,
            message: format!("<{}> is never closed", open.tag),
        });
    }
    root.ok_or(XmlError {
        pos: 0,
        message: "the file has no XML element".into(),
    })
}
