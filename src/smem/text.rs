//! The text form of `smem --add`, `--remove` and `--query` (Soar manual, ch. 9, `smem`):
//! clauses `(ID ^attr value...)` where an identifier is a variable `<x>` or an LTI `@N`,
//! and a value is a constant, a variable or an LTI. Parsing only.

use super::store::Val;

/// An identifier or value that is not a constant.
#[derive(Debug, Clone, PartialEq)]
pub enum Node {
    Var(String),
    Lti(i64),
}

/// A value in a clause.
#[derive(Debug, Clone, PartialEq)]
pub enum Item {
    Const(Val),
    Node(Node),
}

/// `(ID ^attr value ...)`: the identifier and its augmentations, in the text's order.
#[derive(Debug, Clone, PartialEq)]
pub struct Clause {
    pub id: Node,
    /// Each attribute with its values (an attribute alone, for `--remove`, has none).
    pub augs: Vec<(Val, Vec<Item>)>,
}

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Open,
    Close,
    Attr(String),
    Word(String, bool),
}

fn lex(text: &str) -> Option<Vec<Tok>> {
    let mut out = Vec::new();
    let mut chars = text.chars().peekable();
    while let Some(&c) = chars.peek() {
        match c {
            c if c.is_whitespace() => {
                chars.next();
            }
            '(' => {
                chars.next();
                out.push(Tok::Open);
            }
            ')' => {
                chars.next();
                out.push(Tok::Close);
            }
            '{' | '}' => {
                chars.next();
            }
            _ => {
                let attr = c == '^';
                if attr {
                    chars.next();
                }
                let mut word = String::new();
                let mut quoted = false;
                while let Some(&c) = chars.peek() {
                    if c == '|' {
                        quoted = true;
                        chars.next();
                        loop {
                            match chars.next() {
                                Some('|') => break,
                                Some(x) => word.push(x),
                                None => return None,
                            }
                        }
                    } else if c.is_whitespace() || c == '(' || c == ')' || c == '^' {
                        break;
                    } else {
                        word.push(c);
                        chars.next();
                    }
                }
                if word.is_empty() && !quoted {
                    return None;
                }
                out.push(if attr {
                    Tok::Attr(word)
                } else {
                    Tok::Word(word, quoted)
                });
            }
        }
    }
    Some(out)
}

/// A constant as Soar reads one: an integer, a float, else a string.
pub fn constant(word: &str, quoted: bool) -> Val {
    if !quoted {
        if let Ok(i) = word.parse::<i64>() {
            return Val::Int(i);
        }
        if word.contains(['.', 'e', 'E']) && word.starts_with(|c: char| c.is_ascii_digit() || c == '-' || c == '+' || c == '.') {
            if let Ok(f) = word.parse::<f64>() {
                return Val::Float(f);
            }
        }
    }
    Val::Str(word.to_string())
}

fn node(word: &str, quoted: bool) -> Option<Node> {
    if quoted {
        return None;
    }
    if let Some(n) = word.strip_prefix('@') {
        return n.parse().ok().filter(|&n: &i64| n > 0).map(Node::Lti);
    }
    if word.len() > 2 && word.starts_with('<') && word.ends_with('>') {
        return Some(Node::Var(word.to_string()));
    }
    None
}

fn item(word: &str, quoted: bool) -> Item {
    match node(word, quoted) {
        Some(n) => Item::Node(n),
        None => Item::Const(constant(word, quoted)),
    }
}

/// Parses clauses. `values_needed`: every attribute needs a value (`--add`, `--query`).
/// Fails with the number of the clause that is wrong, counted from 0 as 9.6 counts.
pub fn parse(text: &str, values_needed: bool) -> Result<Vec<Clause>, usize> {
    match parse_prefix(text, values_needed) {
        (clauses, None) => Ok(clauses),
        (_, Some(n)) => Err(n),
    }
}

/// The clauses before the first wrong one, and the wrong one's number (9.6's `--add`
/// stores the clauses before a wrong one).
pub fn parse_prefix(text: &str, values_needed: bool) -> (Vec<Clause>, Option<usize>) {
    let mut clauses = Vec::new();
    let Some(toks) = lex(text) else {
        return (clauses, Some(0));
    };
    let err = clauses_of(&toks, values_needed, &mut clauses).err();
    (clauses, err)
}

fn clauses_of(toks: &[Tok], values_needed: bool, clauses: &mut Vec<Clause>) -> Result<(), usize> {
    let mut i = 0;
    while i < toks.len() {
        let n = clauses.len();
        if toks[i] != Tok::Open {
            return Err(n);
        }
        i += 1;
        let id = match toks.get(i) {
            Some(Tok::Word(w, q)) => node(w, *q).ok_or(n)?,
            _ => return Err(n),
        };
        i += 1;
        let mut augs: Vec<(Val, Vec<Item>)> = Vec::new();
        loop {
            match toks.get(i) {
                Some(Tok::Close) => {
                    i += 1;
                    break;
                }
                Some(Tok::Attr(a)) => {
                    i += 1;
                    let mut values = Vec::new();
                    while let Some(Tok::Word(w, q)) = toks.get(i) {
                        values.push(item(w, *q));
                        i += 1;
                    }
                    if values.is_empty() && values_needed {
                        return Err(n);
                    }
                    augs.push((constant(a, false), values));
                }
                _ => return Err(n),
            }
        }
        clauses.push(Clause { id, augs });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clauses() {
        let c = parse("{(<a> ^k 1 2.5 ^s |hello world| ^z <b> ^l @3) (@5 ^x y)}", true).unwrap();
        assert_eq!(c.len(), 2);
        assert_eq!(c[0].id, Node::Var("<a>".into()));
        assert_eq!(
            c[0].augs[0].1,
            vec![Item::Const(Val::Int(1)), Item::Const(Val::Float(2.5))]
        );
        assert_eq!(c[0].augs[1].1, vec![Item::Const(Val::Str("hello world".into()))]);
        assert_eq!(c[1].id, Node::Lti(5));
    }

    #[test]
    fn malformed() {
        assert_eq!(parse("{(<a> ^k 1}", true), Err(0));
        assert_eq!(parse("{(a ^k 1)}", true), Err(0));
        assert_eq!(parse("{(<a> ^k)}", true), Err(0));
        assert_eq!(parse("{(<a> ^k 1) (<b> ^k)}", true), Err(1));
        assert!(parse("{(@1 ^k)}", false).is_ok());
        assert_eq!(parse("{(<a> ^k |open", true), Err(0));
    }
}
