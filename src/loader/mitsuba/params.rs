//! Mitsuba XML properties for a kind's own reader (see [`crate::params`]): dispatch by plugin
//! name through the kind's registry, errors located at the property's element. A property no
//! reader asked for is caught by [`Cx::check_unreferenced`] like any other.

use super::cx::{Cx, R};
use super::xml::Element;
use crate::params::{self, Dialect, Kind, ParamError, Params};

struct XmlParams<'c, 'a, 'e> {
    cx: &'c Cx<'a>,
    e: &'e Element,
}

impl Params for XmlParams<'_, '_, '_> {
    fn dialect(&self) -> Dialect {
        Dialect::Mitsuba
    }

    fn float(&mut self, name: &str) -> Result<Option<f64>, ParamError> {
        self.cx
            .opt_float(self.e, name)
            .map_err(|e| ParamError::new(name, e.message))
    }
}

/// Reads plugin element `e` (`what` is its tag, e.g. "rfilter") as the kind of `registry`
/// its `type` names.
pub(super) fn read_kind<D>(cx: &Cx<'_>, registry: &[Kind<D>], what: &str, e: &Element) -> R<D> {
    let Some(name) = e.attr("type") else {
        return Err(cx.err(e, "missing type"));
    };
    let Some(kind) = params::find(registry, Dialect::Mitsuba, name) else {
        return Err(cx.unsupported(e, what, name));
    };
    (kind.read)(&mut XmlParams { cx, e }).map_err(|p| {
        let at = p.param.as_deref().and_then(|n| cx.child(e, n)).unwrap_or(e);
        cx.err(at, p.message)
    })
}
