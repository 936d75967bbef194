//! Option parsing as Soar's command line does it: `--long` accepts any unique prefix, short
//! options cluster (`-abc`), and an unknown letter is `No such option: x`.

/// One option a command accepts.
#[derive(Debug, Clone, Copy)]
pub struct OptSpec {
    pub short: Option<char>,
    pub long: &'static str,
    pub takes_arg: bool,
}

pub const fn opt(short: char, long: &'static str) -> OptSpec {
    OptSpec {
        short: Some(short),
        long,
        takes_arg: false,
    }
}

pub const fn opt_arg(short: char, long: &'static str) -> OptSpec {
    OptSpec {
        short: Some(short),
        long,
        takes_arg: true,
    }
}

pub const fn long_only(long: &'static str) -> OptSpec {
    OptSpec {
        short: None,
        long,
        takes_arg: false,
    }
}

/// The parsed options (by long name, in order) and the remaining positional words.
#[derive(Debug, Default, Clone, PartialEq)]
pub struct Parsed {
    pub options: Vec<(&'static str, Option<String>)>,
    pub args: Vec<String>,
}

impl Parsed {
    /// Whether the words after the options number `min` to `max`: 9.6's message when not.
    pub fn arg_count(&self, min: usize, max: usize) -> Result<(), &'static str> {
        if self.args.len() < min {
            Err("Too few arguments.")
        } else if self.args.len() > max {
            Err("Too many arguments.")
        } else {
            Ok(())
        }
    }

    pub fn has(&self, long: &str) -> bool {
        self.options.iter().any(|(l, _)| *l == long)
    }
    pub fn value(&self, long: &str) -> Option<&str> {
        self.options
            .iter()
            .rev()
            .find(|(l, _)| *l == long)
            .and_then(|(_, v)| v.as_deref())
    }
}

/// Parses `words` (without the command name). Numbers such as `-5` are positional.
pub fn parse(words: &[String], specs: &[OptSpec]) -> Result<Parsed, String> {
    let mut out = Parsed::default();
    let mut i = 0;
    while i < words.len() {
        let w = &words[i];
        if let Some(long) = w.strip_prefix("--") {
            if long.is_empty() {
                out.args.extend(words[i + 1..].iter().cloned());
                break;
            }
            let matches: Vec<&OptSpec> =
                specs.iter().filter(|s| s.long.starts_with(long)).collect();
            let exact = specs.iter().find(|s| s.long == long);
            let spec = match (exact, matches.as_slice()) {
                (Some(s), _) => s,
                (None, [one]) => *one,
                (None, []) => return Err(format!("No such option: {long}")),
                (None, _) => return Err(format!("Ambiguous option: {long}")),
            };
            i += 1;
            let arg = if spec.takes_arg {
                let a = words
                    .get(i)
                    .cloned()
                    .ok_or_else(|| format!("Option '{}' requires an argument.", spec.long))?;
                i += 1;
                Some(a)
            } else {
                None
            };
            out.options.push((spec.long, arg));
            continue;
        }
        if w.len() > 1
            && w.starts_with('-')
            && !w[1..].starts_with(|c: char| c.is_ascii_digit() || c == '.')
        {
            i += 1;
            let letters: Vec<char> = w[1..].chars().collect();
            for (k, c) in letters.iter().enumerate() {
                let spec = specs
                    .iter()
                    .find(|s| s.short == Some(*c))
                    .ok_or_else(|| format!("No such option: {c}"))?;
                if spec.takes_arg && k + 1 != letters.len() {
                    // The rest of the cluster is the argument, as in 9.6's getopt-style
                    // parser: `-depth 0` is `-d epth` ("Non-negative depth expected.").
                    let rest: String = letters[k + 1..].iter().collect();
                    out.options.push((spec.long, Some(rest)));
                    break;
                }
                let arg = if spec.takes_arg {
                    let a = words
                        .get(i)
                        .cloned()
                        .ok_or_else(|| format!("Option '{}' requires an argument.", spec.long))?;
                    i += 1;
                    Some(a)
                } else {
                    None
                };
                out.options.push((spec.long, arg));
            }
            continue;
        }
        out.args.push(w.clone());
        i += 1;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPECS: &[OptSpec] = &[
        opt('a', "all"),
        opt('d', "disable"),
        opt('e', "enable"),
        opt_arg('n', "count"),
    ];

    fn w(s: &str) -> Vec<String> {
        s.split_whitespace().map(str::to_string).collect()
    }

    #[test]
    fn long_prefixes() {
        let p = parse(&w("--dis x"), SPECS).unwrap();
        assert_eq!(p.options, vec![("disable", None)]);
        assert_eq!(p.args, vec!["x"]);
    }

    #[test]
    fn clusters_and_unknown_letters() {
        let p = parse(&w("-ad"), SPECS).unwrap();
        assert_eq!(p.options.len(), 2);
        // Soar 8's `-off` is the cluster -o -f -f: the first unknown letter is reported.
        assert_eq!(parse(&w("-df"), SPECS).unwrap_err(), "No such option: f");
    }

    #[test]
    fn negative_numbers_are_arguments() {
        assert_eq!(parse(&w("-5"), SPECS).unwrap().args, vec!["-5"]);
    }

    #[test]
    fn option_arguments() {
        assert_eq!(parse(&w("-n 3"), SPECS).unwrap().value("count"), Some("3"));
        assert!(parse(&w("--count"), SPECS).is_err());
    }
}
