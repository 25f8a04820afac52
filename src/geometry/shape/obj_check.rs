//! A reader between an OBJ file and tobj that checks every face index as the lines pass.
//!
//! tobj 4.0.5 resolves a negative (relative) index past the start of its list to a wrapped
//! `usize` near 2⁶⁴ and then multiplies it unchecked (`vt * 2 + 1`, `vn * 3 + 2`): an overflow
//! panic where overflow checks are on (found by the `obj` fuzz target). Indices are checked here
//! first, line by line, without reading the file twice: a relative index must name an element
//! defined before the face, and no index may exceed 2⁴⁰.

use std::io::{self, BufRead, Read};

/// Largest face index accepted (far beyond any mesh a file can hold).
const MAX_INDEX: i64 = 1 << 40;

/// Serves `inner`'s lines after checking the face indices in them; the first bad index makes
/// the read fail, with its description kept in [`IndexCheck::error`].
pub(super) struct IndexCheck<R> {
    inner: R,
    line: Vec<u8>,
    pos: usize,
    /// Positions, texture coordinates and normals defined so far.
    counts: [i64; 3],
    lineno: usize,
    pub error: Option<String>,
}

impl<R: BufRead> IndexCheck<R> {
    pub fn new(inner: R) -> Self {
        Self {
            inner,
            line: Vec::new(),
            pos: 0,
            counts: [0; 3],
            lineno: 0,
            error: None,
        }
    }

    /// Counts an element or checks a face on the current line.
    fn check(&mut self) -> Result<(), String> {
        let text = String::from_utf8_lossy(&self.line);
        let mut words = text.split_whitespace();
        let slot = match words.next() {
            Some("v") => 0,
            Some("vt") => 1,
            Some("vn") => 2,
            Some("f") => 3,
            _ => return Ok(()),
        };
        if slot < 3 {
            self.counts[slot] += 1;
            return Ok(());
        }
        let kind = "face";
        const NAMES: [&str; 3] = ["vertex", "texture coordinate", "normal"];
        for word in words {
            for (k, part) in word.split('/').take(3).enumerate() {
                let Ok(i) = part.parse::<i64>() else {
                    continue; // empty or not a number: tobj reports it
                };
                let count = self.counts[k];
                if i < 0 && -i > count {
                    return Err(format!(
                        "line {}: {kind} index {i} refers before the first {} ({count} defined above it)",
                        self.lineno, NAMES[k]
                    ));
                }
                if i > MAX_INDEX {
                    return Err(format!(
                        "line {}: {kind} index {i} is beyond any mesh (at most {MAX_INDEX})",
                        self.lineno
                    ));
                }
            }
        }
        Ok(())
    }
}

impl<R: BufRead> Read for IndexCheck<R> {
    fn read(&mut self, out: &mut [u8]) -> io::Result<usize> {
        let n = {
            let buf = self.fill_buf()?;
            let n = buf.len().min(out.len());
            out[..n].copy_from_slice(&buf[..n]);
            n
        };
        self.consume(n);
        Ok(n)
    }
}

impl<R: BufRead> BufRead for IndexCheck<R> {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        if self.pos >= self.line.len() {
            self.line.clear();
            self.pos = 0;
            if self.inner.read_until(b'\n', &mut self.line)? > 0 {
                self.lineno += 1;
                if let Err(e) = self.check() {
                    self.error = Some(e.clone());
                    self.line.clear();
                    return Err(io::Error::new(io::ErrorKind::InvalidData, e));
                }
            }
        }
        Ok(&self.line[self.pos..])
    }

    fn consume(&mut self, amt: usize) {
        self.pos = (self.pos + amt).min(self.line.len());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(text: &str) -> (String, Option<String>) {
        let mut r = IndexCheck::new(io::Cursor::new(text.as_bytes()));
        let mut out = String::new();
        let _ = r.read_to_string(&mut out);
        (out, r.error)
    }

    #[test]
    fn relative_indices_before_the_start_and_huge_indices_are_refused() {
        let ok = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf -3/1 -2/-1 -1/1\n";
        assert_eq!(run(ok), (ok.to_string(), None));
        let (_, e) = run("v 0 0 0\nvt 0 0\nf 1/-9 1/1 1/1\n");
        let e = e.unwrap();
        assert!(
            e.contains("line 3") && e.contains("index -9") && e.contains("texture"),
            "{e}"
        );
        let (_, e) = run("v 0 0 0\nf 1 1 99999999999999\n");
        assert!(e.unwrap().contains("beyond any mesh"));
        // an index defined after the face is refused too, as relative indices count backwards
        let (_, e) = run("f -1 -1 -1\nv 0 0 0\n");
        assert!(e.unwrap().contains("line 1"));
    }
}
