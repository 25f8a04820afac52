//! Load errors that name the file, line, column and field.

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// A 1-based line and column in a scene file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Loc {
    pub line: u32,
    pub col: u32,
}

impl fmt::Display for Loc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.line, self.col)
    }
}

/// Maps byte offsets of a source text to lines and columns.
pub struct SourceMap<'a> {
    text: &'a str,
    /// Byte offsets of the line starts, found on the first lookup (a loader asks for the
    /// location of every item: counting lines from the start each time was quadratic, 1.1 G
    /// instructions for a file of 1024 lights).
    line_starts: std::cell::OnceCell<Vec<usize>>,
}

impl<'a> SourceMap<'a> {
    pub fn new(text: &'a str) -> Self {
        Self {
            text,
            line_starts: std::cell::OnceCell::new(),
        }
    }
    /// Line and column (1-based, columns in characters) of byte offset `at`.
    pub fn loc(&self, at: usize) -> Loc {
        loc_in(
            self.text,
            self.line_starts.get_or_init(|| line_starts(self.text)),
            at,
        )
    }
    /// Where `needle` first occurs in `span` at or after byte `from` (within `span`), for
    /// locating an element of an array, whose value carries no span of its own; `span` itself
    /// if it does not occur.
    pub fn find_in(&self, span: &Range<usize>, from: usize, needle: &str) -> Range<usize> {
        let start = from.clamp(span.start, span.end);
        self.text
            .get(start..span.end)
            .and_then(|t| t.find(needle))
            .map(|i| start + i..start + i + needle.len())
            .unwrap_or_else(|| span.clone())
    }

    pub fn span(&self, span: &Range<usize>) -> Loc {
        self.loc(span.start)
    }
}

/// Byte offsets of the starts of `text`'s lines, for [`loc_in`].
pub fn line_starts(text: &str) -> Vec<usize> {
    std::iter::once(0)
        .chain(text.match_indices('\n').map(|(i, _)| i + 1))
        .collect()
}

/// Line and column (1-based, columns in characters) of byte offset `at` of `text`, whose
/// [`line_starts`] are `starts`: O(log lines + the line's length).
pub fn loc_in(text: &str, starts: &[usize], at: usize) -> Loc {
    let at = floor_char_boundary(text, at.min(text.len()));
    // the last line start at or before `at`
    let line = starts.partition_point(|&s| s <= at);
    let col = text[starts[line - 1]..at].chars().count() + 1;
    Loc {
        line: line as u32,
        col: col as u32,
    }
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// A scene that could not be loaded or built: `file:line:col: field: message`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub struct LoadError {
    pub file: PathBuf,
    pub loc: Loc,
    /// Dotted path of the offending field, e.g. `shapes[2].radius` (empty for syntax errors).
    pub field: String,
    pub message: String,
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: ", self.file.display(), self.loc)?;
        if !self.field.is_empty() {
            write!(f, "{}: ", self.field)?;
        }
        f.write_str(&self.message)
    }
}

impl LoadError {
    pub fn new(
        file: &Path,
        loc: Loc,
        field: impl Into<String>,
        message: impl Into<String>,
    ) -> Self {
        Self {
            file: file.to_path_buf(),
            loc,
            field: field.into(),
            message: shorten_quoted(&message.into()),
        }
    }
}

/// Longest quoted value an error message repeats whole, in characters.
const MAX_QUOTED: usize = 80;

/// `message` with every quoted value ("…") longer than `MAX_QUOTED` characters cut to its
/// start, an ellipsis and its length: an error about a 1 MB value must not print it.
pub fn shorten_quoted(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(4 * MAX_QUOTED + 200));
    let mut rest = message;
    while let Some(open) = rest.find('"') {
        out.push_str(&rest[..=open]);
        let after = &rest[open + 1..];
        let Some(close) = after.find('"') else {
            rest = after;
            // an unpaired quote: cut what follows if long
            if rest.chars().count() > MAX_QUOTED {
                let cut: String = rest.chars().take(MAX_QUOTED / 2).collect();
                out.push_str(&format!("{cut}… ({} characters)", rest.chars().count()));
                rest = "";
            }
            break;
        };
        let inner = &after[..close];
        let n = inner.chars().count();
        if n > MAX_QUOTED {
            let cut: String = inner.chars().take(MAX_QUOTED / 2).collect();
            out.push_str(&format!("{cut}…\" ({n} characters)"));
        } else {
            out.push_str(inner);
            out.push('"');
        }
        rest = &after[close + 1..];
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locations_count_lines_and_characters() {
        let text = "a = 1\nλ = \"x\"\n\n  b = [1, 2]\nend";
        let map = SourceMap::new(text);
        for at in 0..=text.len() + 3 {
            // the definition: lines before the offset, characters since the last newline
            let cut = floor_char_boundary(text, at.min(text.len()));
            let before = &text[..cut];
            let line = before.matches('\n').count() as u32 + 1;
            let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) as u32 + 1;
            assert_eq!(map.loc(at), Loc { line, col }, "offset {at}");
        }
    }

    #[test]
    fn long_quoted_values_are_cut_with_their_length() {
        let long = "x".repeat(1_000_000);
        let m = shorten_quoted(&format!("unknown spectrum \"{long}\"; see the list"));
        assert!(m.len() < 200, "{m}");
        assert!(
            m.contains("(1000000 characters)") && m.ends_with("; see the list"),
            "{m}"
        );
        let short = "value \"abc\" and \"d\"";
        assert_eq!(shorten_quoted(short), short);
        let m = shorten_quoted(&format!("unpaired \"{long}"));
        assert!(m.len() < 200 && m.contains("1000000 characters"), "{m}");
    }
}
