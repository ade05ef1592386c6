//! Finds where a field sits in RON source text, so that a validation error can
//! name its line and column. A small scanner: it skips comments and strings and
//! tracks the nesting of `key: (...)` and list elements.

#[derive(Debug, Clone, PartialEq)]
enum Seg {
    Key(String),
    Index(usize),
}

/// Parses `lights[1].intensity` into segments.
fn parse_path(path: &str) -> Vec<Seg> {
    let mut segs = Vec::new();
    for part in path.split('.') {
        let mut rest = part;
        if let Some(open) = rest.find('[') {
            segs.push(Seg::Key(rest[..open].to_owned()));
            rest = &rest[open..];
            while let Some(close) = rest.find(']') {
                if let Ok(i) = rest[1..close].parse() {
                    segs.push(Seg::Index(i));
                }
                rest = &rest[close + 1..];
            }
        } else {
            segs.push(Seg::Key(rest.to_owned()));
        }
    }
    segs
}

struct Frame {
    seg: Option<Seg>,
    is_list: bool,
    index: usize,
    pending_key: Option<String>,
}

/// 1-based line and column of the field at `path` itself, if it is written in
/// `src`; `None` when it is not (an error about it then names no line that does
/// not hold it).
#[must_use]
pub fn locate_exact(src: &str, path: &str) -> Option<(usize, usize)> {
    let depth = parse_path(path).len();
    locate_deepest(src, path).and_then(|(d, at)| (d == depth).then_some(at))
}

/// The deepest field on `path` written in `src`, with its depth (path segments).
#[expect(
    clippy::too_many_lines,
    reason = "a tokenizer: one match arm per RON token"
)]
fn locate_deepest(src: &str, path: &str) -> Option<(usize, (usize, usize))> {
    let target = parse_path(path);
    let chars: Vec<char> = src.chars().collect();
    let mut line_starts = vec![0usize];
    for (i, c) in chars.iter().enumerate() {
        if *c == '\n' {
            line_starts.push(i + 1);
        }
    }
    let pos_of = |i: usize| {
        let line = line_starts.partition_point(|&s| s <= i);
        (line, i - line_starts[line - 1] + 1)
    };
    let mut stack = vec![Frame {
        seg: None,
        is_list: false,
        index: 0,
        pending_key: None,
    }];
    let mut best: Option<(usize, (usize, usize))> = None;
    let path_of = |stack: &[Frame], last: Option<Seg>| -> Vec<Seg> {
        stack
            .iter()
            .filter_map(|f| f.seg.clone())
            .chain(last)
            .collect()
    };
    let consider = |segs: Vec<Seg>, at: usize, best: &mut Option<(usize, (usize, usize))>| {
        if segs.len() <= target.len()
            && target[..segs.len()] == segs[..]
            && best.is_none_or(|(d, _)| segs.len() > d)
        {
            *best = Some((segs.len(), pos_of(at)));
        }
        segs == target
    };
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        match c {
            '/' if chars.get(i + 1) == Some(&'/') => {
                while i < chars.len() && chars[i] != '\n' {
                    i += 1;
                }
            }
            '/' if chars.get(i + 1) == Some(&'*') => {
                let mut depth = 0;
                while i < chars.len() {
                    if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                        depth += 1;
                        i += 1;
                    } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                        depth -= 1;
                        i += 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    i += 1;
                }
            }
            '"' => {
                i += 1;
                while i < chars.len() && chars[i] != '"' {
                    if chars[i] == '\\' {
                        i += 1;
                    }
                    i += 1;
                }
            }
            '(' | '[' | '{' => {
                let top = stack.last_mut().expect("the root frame is never popped");
                let seg = match top.pending_key.take() {
                    Some(k) => Some(Seg::Key(k)),
                    None if top.is_list => Some(Seg::Index(top.index)),
                    None => None,
                };
                if let Some(s) = &seg
                    && matches!(s, Seg::Index(_))
                    && consider(path_of(&stack, Some(s.clone())), i, &mut best)
                {
                    return best;
                }
                stack.push(Frame {
                    seg,
                    is_list: c == '[',
                    index: 0,
                    pending_key: None,
                });
            }
            ')' | ']' | '}' if stack.len() > 1 => {
                stack.pop();
            }
            ',' => {
                let top = stack.last_mut().expect("the root frame is never popped");
                top.pending_key = None;
                if top.is_list {
                    top.index += 1;
                }
            }
            c if c.is_alphabetic() || c == '_' => {
                let start = i;
                while i + 1 < chars.len() && (chars[i + 1].is_alphanumeric() || chars[i + 1] == '_')
                {
                    i += 1;
                }
                let name: String = chars[start..=i].iter().collect();
                let mut j = i + 1;
                while j < chars.len() && chars[j].is_whitespace() {
                    j += 1;
                }
                if chars.get(j) == Some(&':') && chars.get(j + 1) != Some(&':') {
                    let key = Seg::Key(name.clone());
                    if consider(path_of(&stack, Some(key)), start, &mut best) {
                        return best;
                    }
                    stack
                        .last_mut()
                        .expect("the root frame is never popped")
                        .pending_key = Some(name);
                }
            }
            _ => {}
        }
        i += 1;
    }
    best
}

#[cfg(test)]
mod tests {
    use super::locate_exact;

    const SRC: &str = "// comment: radius: 1\n(\n  cradle: (\n    balls: 5, /* gap: 1 */\n    radius: 0.02,\n  ),\n  lights: [\n    Ambient(color: (1, 1, 1), intensity: 0.1),\n    Point(position: (0, 1, 2), color: (1, 1, 1), intensity: -3),\n  ],\n)\n";

    #[test]
    fn finds_nested_keys_past_comments() {
        assert_eq!(locate_exact(SRC, "cradle.radius"), Some((5, 5)));
        assert_eq!(locate_exact(SRC, "cradle.balls"), Some((4, 5)));
    }

    #[test]
    fn finds_fields_inside_list_elements() {
        assert_eq!(locate_exact(SRC, "lights[1].intensity"), Some((9, 50)));
        assert_eq!(locate_exact(SRC, "lights[0].intensity"), Some((8, 31)));
    }

    #[test]
    fn a_field_not_written_is_not_located_at_its_section() {
        // `gap` appears only inside a comment: no line holds it, and an error about
        // it must not point at `cradle`'s line.
        assert_eq!(locate_exact(SRC, "cradle.gap"), None);
        assert_eq!(locate_exact(SRC, "camera.fov_deg"), None);
    }
}
