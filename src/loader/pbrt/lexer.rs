//! pbrt-v4's scene-file tokens (`src/pbrt/parser.cpp`, `Tokenizer`): `#` comments to the end of
//! the line, double-quoted strings (with `\n`, `\t`, `\\`, `\"` escapes, not spanning lines),
//! `[` and `]`, and bare words (directives, numbers, `true`/`false` inside brackets), each with
//! its line and column.

use std::path::Path;

use crate::loader::{LoadError, Loc};

/// One token and where it starts.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Token {
    pub kind: Tok,
    pub loc: Loc,
}

#[derive(Clone, Debug, PartialEq)]
pub(super) enum Tok {
    /// A bare word: a directive name or a number.
    Word(String),
    /// A quoted string, its escapes resolved.
    Str(String),
    Open,
    Close,
}

/// The tokens of `text` (from the file `path`, named in errors).
pub(super) fn tokenize(text: &str, path: &Path) -> Result<Vec<Token>, LoadError> {
    let mut out = Vec::new();
    let (mut line, mut col) = (1u32, 1u32);
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        let loc = Loc { line, col };
        col += 1;
        match c {
            '\n' => {
                line += 1;
                col = 1;
            }
            c if c.is_whitespace() => {}
            '#' => {
                while let Some(&n) = chars.peek() {
                    if n == '\n' {
                        break;
                    }
                    chars.next();
                }
            }
            '[' => out.push(Token {
                kind: Tok::Open,
                loc,
            }),
            ']' => out.push(Token {
                kind: Tok::Close,
                loc,
            }),
            '"' => {
                let mut s = String::new();
                loop {
                    let Some(n) = chars.next() else {
                        return Err(LoadError::new(path, loc, "", "unterminated string"));
                    };
                    col += 1;
                    match n {
                        '"' => break,
                        '\n' => {
                            return Err(LoadError::new(
                                path,
                                loc,
                                "",
                                "a string runs past the end of its line (a missing \")",
                            ));
                        }
                        '\\' => {
                            col += 1;
                            s.push(match chars.next() {
                                Some('n') => '\n',
                                Some('t') => '\t',
                                Some('b') => '\u{8}',
                                Some('f') => '\u{c}',
                                Some('r') => '\r',
                                Some(e @ ('\\' | '\'' | '"')) => e,
                                e => {
                                    return Err(LoadError::new(
                                        path,
                                        Loc { line, col: col - 1 },
                                        "",
                                        format!("unknown escape \\{}", e.unwrap_or(' ')),
                                    ));
                                }
                            });
                        }
                        n => s.push(n),
                    }
                }
                out.push(Token {
                    kind: Tok::Str(s),
                    loc,
                });
            }
            c => {
                let mut w = String::from(c);
                while let Some(&n) = chars.peek() {
                    if n.is_whitespace() || matches!(n, '"' | '[' | ']' | '#') {
                        break;
                    }
                    w.push(n);
                    chars.next();
                    col += 1;
                }
                out.push(Token {
                    kind: Tok::Word(w),
                    loc,
                });
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(s: &str) -> Vec<Tok> {
        tokenize(s, Path::new("t.pbrt"))
            .unwrap()
            .into_iter()
            .map(|t| t.kind)
            .collect()
    }

    #[test]
    fn words_strings_brackets_and_comments() {
        assert_eq!(
            kinds("Shape \"sphere\" # a comment \"x\"\n \"float radius\" [2.5]"),
            vec![
                Tok::Word("Shape".into()),
                Tok::Str("sphere".into()),
                Tok::Str("float radius".into()),
                Tok::Open,
                Tok::Word("2.5".into()),
                Tok::Close,
            ]
        );
        assert_eq!(kinds(r#""a\"b\\c""#), vec![Tok::Str("a\"b\\c".into())]);
        assert_eq!(
            kinds("[1 2]"),
            vec![
                Tok::Open,
                Tok::Word("1".into()),
                Tok::Word("2".into()),
                Tok::Close
            ]
        );
    }

    #[test]
    fn locations_and_errors() {
        let t = tokenize("WorldBegin\n  Shape \"x\"", Path::new("t.pbrt")).unwrap();
        assert_eq!(t[1].loc, Loc { line: 2, col: 3 });
        assert_eq!(t[2].loc, Loc { line: 2, col: 9 });
        let e = tokenize("Shape \"sphere", Path::new("t.pbrt")).unwrap_err();
        assert!(e.to_string().contains("unterminated string"), "{e}");
    }
}
