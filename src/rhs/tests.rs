//! Expected values are the official kernel's outputs (soar-sml 9.6.5), obtained with rules
//! that `(write |@n=| (f args) (crlf))` each call, run through small Python harnesses over
//! soar-sml (the exec tests register Python RHS functions `echo` -> `<agent|name|args>` and
//! `getlength` -> `len(args)`). An error line is the text the kernel printed instead.

use super::text::{self, accept_symbol, c_strtod, c_strtol, timestamp_text, Accepted};
use super::*;
use crate::symbols::{SymData, Symbols};
use crate::wm::WorkingMemory;

struct Kit {
    symbols: Symbols,
    wm: WorkingMemory,
    rng: Mt19937,
    reg: Registry,
    out: String,
    /// Named identifiers for `<x>` arguments.
    vars: Vec<(String, Sym)>,
    decision_count: u64,
    trace_level: u8,
    halt: bool,
    dont_learn: Option<Sym>,
    force_learn: Option<Sym>,
    fresh: bool,
    copies: Vec<(Sym, Sym, Sym)>,
    module: Vec<(Sym, Sym, Sym)>,
}

impl Kit {
    fn new() -> Kit {
        let mut symbols = Symbols::new();
        let s1 = symbols.new_id('S', 1);
        if let Some(d) = symbols.id_data_mut(s1) {
            d.is_goal = true;
        }
        let mut reg = Registry::new();
        reg.register(
            "echo",
            Box::new(|agent: &str, args: &str| format!("<{agent}|echo|{args}>")),
        );
        reg.register(
            "getlength",
            Box::new(|_: &str, args: &str| args.len().to_string()),
        );
        Kit {
            symbols,
            wm: WorkingMemory::new(),
            rng: Mt19937::new(7),
            reg,
            out: String::new(),
            vars: vec![("<s>".into(), s1)],
            decision_count: 0,
            trace_level: 1,
            halt: false,
            dont_learn: None,
            force_learn: None,
            fresh: false,
            copies: Vec::new(),
            module: Vec::new(),
        }
    }

    fn var(&self, name: &str) -> Sym {
        self.vars.iter().find(|(n, _)| n == name).unwrap().1
    }

    fn new_var(&mut self, name: &str, letter: char) -> Sym {
        let id = self.symbols.new_id(letter, 1);
        self.vars.push((name.into(), id));
        id
    }

    /// A literal as Soar's lexer reads it: `<x>` a named identifier, `|..|` a string,
    /// ints, floats (with a `.`), anything else a string (so `1e3` is a string).
    fn lit(&mut self, t: &str) -> Sym {
        if t.starts_with('<') && t.len() > 2 {
            return self.var(t);
        }
        if let Some(inner) = t.strip_prefix('|').and_then(|x| x.strip_suffix('|')) {
            return self.symbols.str(inner);
        }
        if crate::lexer::is_int_lexeme(t) {
            if let Ok(i) = t.parse::<i64>() {
                return self.symbols.int(i);
            }
        }
        if t.contains('.') {
            if let Ok(f) = t.parse::<f64>() {
                return self.symbols.float(f);
            }
        }
        self.symbols.str(t)
    }

    fn call_syms(&mut self, name: &str, args: &[Sym]) -> Result<Option<Sym>, String> {
        let mut run = |line: &str| -> String { format!("ran[{line}]\n") };
        let mut ctx = RhsContext::new(
            &mut self.symbols,
            &self.wm,
            &mut self.rng,
            &mut self.reg,
            &mut self.out,
            "a",
        );
        ctx.decision_count = self.decision_count;
        ctx.trace_flags = trace_flags_for_level(self.trace_level);
        ctx.command = Some(&mut run);
        let r = call(name, args, &mut ctx);
        self.halt |= ctx.halt;
        self.dont_learn = ctx.dont_learn.or(self.dont_learn);
        self.force_learn = ctx.force_learn.or(self.force_learn);
        self.fresh = ctx.error_fresh_line;
        if name == "deep-copy" || !ctx.deep_copy_wmes.is_empty() {
            self.copies = std::mem::take(&mut ctx.deep_copy_wmes);
        }
        self.module.append(&mut ctx.module_wmes);
        r
    }

    /// Evaluates `(name args...)`; args are literals or nested `(f ...)` expressions.
    fn eval_sym(&mut self, expr: &str) -> Result<Option<Sym>, String> {
        let toks = tokenize(expr);
        let mut pos = 0;
        self.eval_toks(&toks, &mut pos)
    }

    fn eval_toks(&mut self, toks: &[String], pos: &mut usize) -> Result<Option<Sym>, String> {
        assert_eq!(toks[*pos], "(");
        *pos += 1;
        let name = toks[*pos].clone();
        *pos += 1;
        let mut args = Vec::new();
        while toks[*pos] != ")" {
            if toks[*pos] == "(" {
                let v = self.eval_toks(toks, pos)?;
                args.push(v.expect("a nested call returns a value"));
            } else {
                let t = toks[*pos].clone();
                args.push(self.lit(&t));
                *pos += 1;
            }
        }
        *pos += 1;
        self.call_syms(&name, &args)
    }

    /// The text `(write |@n=| expr (crlf))` printed: the value, or the error line.
    fn w(&mut self, expr: &str) -> String {
        match self.eval_sym(expr) {
            Ok(Some(v)) => value_text(&self.symbols, v),
            Ok(None) => "<none>".into(),
            Err(e) => e,
        }
    }

    fn kind(&mut self, expr: &str) -> &'static str {
        match self.eval_sym(expr) {
            Ok(Some(v)) => match self.symbols.get(v) {
                SymData::Int(_) => "int",
                SymData::Float(_) => "float",
                SymData::Str(_) => "string",
                SymData::Id(_) => "id",
            },
            _ => "none",
        }
    }
}

fn tokenize(s: &str) -> Vec<String> {
    let mut out = Vec::new();
    let b: Vec<char> = s.chars().collect();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c.is_whitespace() {
            i += 1;
        } else if c == '(' || c == ')' {
            out.push(c.to_string());
            i += 1;
        } else if c == '|' {
            let mut t = String::from("|");
            i += 1;
            while i < b.len() && b[i] != '|' {
                if b[i] == '\\' && i + 1 < b.len() {
                    i += 1;
                }
                t.push(b[i]);
                i += 1;
            }
            t.push('|');
            i += 1;
            out.push(t);
        } else {
            let mut t = String::new();
            while i < b.len() && !b[i].is_whitespace() && b[i] != '(' && b[i] != ')' {
                t.push(b[i]);
                i += 1;
            }
            out.push(t);
        }
    }
    out
}

fn check(k: &mut Kit, table: &[(&str, &str)]) {
    for (expr, want) in table {
        assert_eq!(k.w(expr), *want, "{expr}");
    }
}

#[test]
fn arithmetic_as_the_official_kernel() {
    let mut k = Kit::new();
    check(
        &mut k,
        &[
            ("(+ 1 2)", "3"),
            ("(+ 1 2.5)", "3.500000"),
            ("(+ 1 2 3.5 4)", "10.500000"),
            ("(+)", "0"),
            ("(*)", "1"),
            ("(* 2 3)", "6"),
            ("(* 2 1.5 2)", "6.000000"),
            ("(- 5)", "-5"),
            ("(- 2.5)", "-2.500000"),
            ("(- 10 2.5 1)", "6.500000"),
            ("(-)", "Error: '-' function called with no arguments"),
            ("(/ 4)", "0.250000"),
            ("(/ 1 3)", "0.333333"),
            ("(/ 6 3)", "2.000000"),
            ("(/ 7 2 2)", "1.750000"),
            ("(/)", "Error: '/' function called with no arguments"),
            ("(/ 0)", "Error: attempt to divide ('/') by zero."),
            ("(/ 1 0)", "Error: attempt to divide ('/') by zero."),
            ("(/ 1 0.0)", "Error: attempt to divide ('/') by zero."),
            ("(+ 1 abc)", "Error: non-number (abc) passed to + function"),
            ("(* abc 1)", "Error: non-number (abc) passed to * function"),
            ("(- abc)", "Error: non-number (abc) passed to - function"),
            ("(/ abc)", "Error: non-number (abc) passed to / function"),
            ("(+ 1 <s>)", "Error: non-number (S1) passed to + function"),
            ("(div 7 2)", "3"),
            ("(div -7 2)", "-3"),
            ("(mod 7 -2)", "1"),
            ("(mod -7 2)", "-1"),
            ("(div 7 0)", "Error: attempt to divide ('div') by zero."),
            ("(mod 7 0)", "Error: attempt to divide ('mod') by zero."),
            (
                "(div 7.0 2)",
                "Error: non-integer (7.000000) passed to div function",
            ),
            (
                "(mod 7 2.0)",
                "Error: non-integer (2.000000) passed to mod function",
            ),
            (
                "(div abc 2)",
                "Error: non-integer (abc) passed to div function",
            ),
            ("(abs -4)", "4"),
            ("(abs -4.5)", "4.500000"),
            ("(abs 3)", "3"),
            (
                "(abs abc)",
                "Error: 'abs' function called with non-numeric argument abc",
            ),
            ("(sqrt 16)", "4.000000"),
            ("(sqrt 2)", "1.414214"),
            (
                "(sqrt abc)",
                "Error: 'sqrt' function called with non-numeric argument abc",
            ),
            ("(sin 0)", "0.000000"),
            ("(sin 1)", "0.841471"),
            ("(cos 0)", "1.000000"),
            (
                "(cos abc)",
                "Error: 'cos' function called with non-numeric argument abc",
            ),
            ("(atan2 1 1)", "0.785398"),
            ("(atan2 0 -1)", "3.141593"),
            ("(atan2 abc 1)", "Error: non-number (abc) passed to atan2"),
            ("(min 3 1 2)", "1"),
            ("(min 3 1.5 2)", "1.500000"),
            ("(max 1 2 3)", "3"),
            ("(max 1 2.5 2)", "2.500000"),
            ("(min 2.5 1)", "1.000000"),
            ("(max 2 2.0)", "2.000000"),
            ("(max 2.0 2)", "2.000000"),
            ("(min)", "0"),
            ("(max)", "0"),
            ("(max 1.5 7)", "7.000000"),
            (
                "(min abc 1)",
                "Error: non-number (abc) passed to min function",
            ),
            (
                "(max 1 abc)",
                "Error: non-number (abc) passed to max function",
            ),
        ],
    );
    // Types: int if all ints, else float; `/` always float.
    assert_eq!(k.kind("(+ 1 2)"), "int");
    assert_eq!(k.kind("(* 2 1.5)"), "float");
    assert_eq!(k.kind("(/ 6 3)"), "float");
    assert_eq!(k.kind("(min 3 1.5)"), "float");
    // glibc prints the NaN of sqrt(-1) (sign bit set on x86-64) as -nan.
    #[cfg(target_arch = "x86_64")]
    assert_eq!(k.w("(sqrt -1)"), "-nan");
}

#[test]
fn extremes_as_the_official_kernel() {
    let mut k = Kit::new();
    check(
        &mut k,
        &[
            ("(+ 1.0e30)", "1000000000000000019884624838656.000000"),
            ("(int 1.0e30)", "-9223372036854775808"),
            ("(int (* 1.0e200 1.0e200))", "-9223372036854775808"),
            ("(int (sqrt -1))", "-9223372036854775808"),
            ("(* 1.0e200 1.0e200)", "inf"),
            ("(- (* 1.0e200 1.0e200))", "-inf"),
            ("(+ 9223372036854775807 1)", "-9223372036854775808"),
            ("(* 9223372036854775807 2)", "-2"),
            ("(- -9223372036854775807 2)", "9223372036854775807"),
            ("(abs -9223372036854775807)", "9223372036854775807"),
            ("(div -9223372036854775807 -1)", "9223372036854775807"),
            (
                "(float |1e-400|)",
                "Error: bad float (1e-400) given to 'float' RHS function",
            ),
            (
                "(float |4.9e-324|)",
                "Error: bad float (|4.9e-324|) given to 'float' RHS function",
            ),
            (
                "(float |1e-310|)",
                "Error: bad float (1e-310) given to 'float' RHS function",
            ),
            ("(float |nan|)", "nan"),
            ("(float |-nan|)", "-nan"),
            ("(float |  -2.5xyz|)", "-2.500000"),
            ("(float ||)", "0.000000"),
            ("(int ||)", "0"),
            ("(int |+7|)", "7"),
            ("(int | -7 |)", "-7"),
            ("(int |9223372036854775807|)", "9223372036854775807"),
            (
                "(int |9223372036854775808|)",
                "Error: bad integer (|9223372036854775808|) given to 'int' RHS function",
            ),
            ("(int |-9223372036854775808|)", "-9223372036854775808"),
            (
                "(string 1.0e30)",
                "1000000000000000019884624838656.00000000000000000",
            ),
            ("(string 0.000001)", "0.00000100000000000"),
            ("(strlen (sqrt -1))", "4"),
            (
                "(concat (sqrt -1) 1.0e30)",
                "-nan1000000000000000019884624838656.000000",
            ),
            ("(min 1 (sqrt -1) 3)", "1.000000"),
            ("(max (sqrt -1) 1)", "-nan"),
            ("(round-off 2.5 (sqrt -1))", "-nan"),
        ],
    );
    // Where 9.6 crashes (SIGFPE), an error instead of a panic.
    assert!(k.w("(round-off 7 0)").starts_with("Error:"));
    assert!(k.w("(round-off 12 abc)").starts_with("Error:"));
    assert!(k.w("(round-off-heading 7 0)").starts_with("Error:"));
    assert_eq!(k.w("(div -9223372036854775808 -1)"), "-9223372036854775808");
    assert_eq!(k.w("(mod -9223372036854775808 -1)"), "0");
    assert_eq!(
        k.w("(round-off -9223372036854775808 -1)"),
        "-9223372036854775808"
    );
    // Huge headings: 9.6 loops for ever; a value in (-180, 180] here.
    for e in [
        "(round-off-heading 9223372036854775807 1)",
        "(round-off-heading 1.0e300 1.0)",
        "(round-off-heading -1.0e300 1.0)",
    ] {
        let v: f64 = k.w(e).parse().unwrap();
        assert!(v > -180.0 && v <= 180.0, "{e} gave {v}");
    }
    assert!(k
        .w("(compute-dice-probability 100000 6 1 eq)")
        .starts_with("Error:"));
}

#[test]
fn conversions_and_legacy_helpers_as_the_official_kernel() {
    let mut k = Kit::new();
    check(
        &mut k,
        &[
            ("(int 3)", "3"),
            ("(int -2.7)", "-2"),
            ("(int 2.7)", "2"),
            ("(int |42|)", "42"),
            ("(int |42abc|)", "42"),
            ("(int abc)", "0"),
            ("(int | 12|)", "12"),
            ("(int |-0x10|)", "0"),
            (
                "(int |99999999999999999999|)",
                "Error: bad integer (|99999999999999999999|) given to 'int' RHS function",
            ),
            (
                "(int |-99999999999999999999|)",
                "Error: bad integer (|-99999999999999999999|) given to 'int' RHS function",
            ),
            (
                "(int <s>)",
                "Error: identifier (S1) passed to 'int' RHS function.",
            ),
            ("(int 1e300)", "1"),
            ("(float 3)", "3.000000"),
            ("(float |2.5|)", "2.500000"),
            ("(float abc)", "0.000000"),
            ("(float |1e3|)", "1000.000000"),
            ("(float 2.5)", "2.500000"),
            (
                "(float |1e999|)",
                "Error: bad float (1e999) given to 'float' RHS function",
            ),
            (
                "(float <s>)",
                "Error: identifier (S1) passed to 'float' RHS function.",
            ),
            ("(float |inf|)", "inf"),
            ("(float | 0x10|)", "16.000000"),
            ("(round-off 17 5)", "15"),
            ("(round-off -17 5)", "-15"),
            ("(round-off 2.37 0.1)", "2.300000"),
            ("(round-off 12.5 1)", "12"),
            ("(round-off 12 2.5)", "12.500000"),
            ("(round-off abc 2)", "0"),
            ("(round-off-heading 190 1)", "-170"),
            ("(round-off-heading 185.3 1.0)", "-175.000000"),
            ("(round-off-heading -400 10)", "-40"),
            ("(compute-heading 0 0 10 10)", "44"),
            ("(compute-heading 0 0 -10 0)", "-90"),
            ("(compute-heading 0 0 0 0)", "90"),
            (
                "(compute-heading 0 0 abc 0)",
                "Error: non-number (abc) passed to - compute-heading",
            ),
            (
                "(compute-heading abc 0 1 0)",
                "Error: non-number (abc) passed to - compute-heading",
            ),
            ("(compute-range 0 0 3 4)", "5"),
            ("(compute-range 0 0 3.5 4.5)", "5"),
            ("(compute-dice-probability 3 6 1 eq)", "0.347222"),
            ("(compute-dice-probability 3 6 1 ge)", "0.421296"),
            ("(compute-dice-probability 3 6 1 lt)", "0.578704"),
            ("(compute-dice-probability 3 6 1 gt)", "0.074074"),
            ("(compute-dice-probability 3 6 1 le)", "0.925926"),
            ("(compute-dice-probability 3 6 1 ne)", "0.652778"),
            (
                "(compute-dice-probability 3 6 1 xx)",
                "Error: invalid string (xx) passed as 'pred' to - compute-dice-probability",
            ),
            (
                "(compute-dice-probability 3 6 1 2)",
                "Error: non-string (2) passed as 'pred' to - compute-dice-probability",
            ),
            (
                "(compute-dice-probability a 6 1 eq)",
                "Error: non-number (a) passed as 'dice' to - compute-dice-probability",
            ),
            // Not in the 9.6 binary: read as exec of an unregistered function.
            (
                "(predict-x 0 90 2 3)",
                "Error: Nobody was registered to implement rhs function predict-x",
            ),
        ],
    );
    assert_eq!(k.kind("(int 2.7)"), "int");
    assert_eq!(k.kind("(float 3)"), "float");
}

#[test]
fn strings_and_misc_as_the_official_kernel() {
    let mut k = Kit::new();
    check(
        &mut k,
        &[
            ("(concat a |b c| 3 1.5 <s>)", "ab c31.500000S1"),
            ("(concat)", ""),
            ("(concat || x)", "x"),
            ("(strlen abc)", "3"),
            ("(strlen 1.5)", "8"),
            ("(strlen <s>)", "2"),
            ("(strlen |a b|)", "3"),
            ("(strlen 12)", "2"),
            ("(string abc)", "abc"),
            ("(string 12)", "12"),
            ("(string 1.5)", "1.50000000000000000"),
            ("(string 0.1)", "0.10000000000000001"),
            ("(string 2.0)", "2.00000000000000000"),
            ("(string 1e3)", "1e3"),
            ("(string <s>)", "S1"),
            ("(string (/ 1 3))", "0.33333333333333331"),
            ("(trim |  a b  |)", "a b"),
            ("(trim |   |)", ""),
            ("(trim abc)", "abc"),
            (
                "(trim 12)",
                "Error: non-symbol (12) passed to 'trim' function.",
            ),
            (
                "(trim <s>)",
                "Error: non-symbol (S1) passed to 'trim' function.",
            ),
            ("(capitalize-symbol abc)", "Abc"),
            ("(capitalize-symbol |1bc|)", "1bc"),
            (
                "(capitalize-symbol 12)",
                "Error: non-symbol (12) passed to capitalize-symbol function.",
            ),
            (
                "(capitalize-symbol <s>)",
                "Error: non-symbol (S1) passed to capitalize-symbol function.",
            ),
            ("(capitalize-symbol ||)", ""),
            ("(make-constant-symbol)", "constant1"),
            ("(make-constant-symbol)", "constant2"),
            ("(make-constant-symbol foo)", "foo3"),
            ("(make-constant-symbol foo)", "foo4"),
            ("(make-constant-symbol a 1 2.5)", "a12.5000005"),
            ("(make-constant-symbol abc)", "abc6"),
            ("(make-constant-symbol constant)", "constant7"),
            ("(ifeq 1 1 yes no)", "yes"),
            ("(ifeq 1 1.0 yes no)", "no"),
            ("(ifeq a a yes no)", "yes"),
            ("(ifeq <s> <s> yes no)", "yes"),
            ("(ifeq a b yes no)", "no"),
            ("(dc)", "0"),
            ("(crlf)", "\n"),
            ("(exec echo a |b c| 3 1.5 <s>)", "<a|echo|ab c31.500000S1>"),
            ("(exec getlength abc)", "3"),
            (
                "(exec nothere x y)",
                "Error: Nobody was registered to implement rhs function nothere",
            ),
            ("(echo x 1)", "<a|echo|x1>"),
            ("(echo)", "<a|echo|>"),
            ("(getlength 1 |, | 2.5)", "11"),
            (
                "(exec 5 x)",
                "Error: Nobody was registered to implement rhs function 5",
            ),
            (
                "(exec)",
                "error_expected_rhs_function_to_return_value_but_it_did_NOT",
            ),
            (
                "(cmd)",
                "error_expected_rhs_function_to_return_value_but_it_did_NOT",
            ),
            (
                "(size abc)",
                "Error: non-symbol (abc) passed to size function",
            ),
            (
                "(sum abc)",
                "Error: non-symbol (abc) passed to sum function",
            ),
            (
                "(product abc)",
                "Error: non-symbol (abc) passed to product function",
            ),
            (
                "(set-count abc superstate)",
                "|ERROR: First parameter needs to be an identifier.|",
            ),
            ("(deep-copy abc)", "*symbol not id*"),
            (
                "(rand-int abc)",
                "Error: non-number (abc) passed to - rand-int",
            ),
            (
                "(rand-float abc)",
                "Error: non-number (abc) passed to - rand-float",
            ),
            (
                "(@ <s>)",
                "Error: S1 is not linked to a semantic identifier.",
            ),
        ],
    );
    // exec, concat, string, crlf, ... always make strings, even when they look numeric.
    for e in [
        "(exec getlength abc)",
        "(concat 1 2)",
        "(string 5)",
        "(crlf)",
        "(exec nothere)",
        "(trim |  x  |)",
        "(timestamp)",
    ] {
        assert_eq!(k.kind(e), "string", "{e}");
    }
    k.decision_count = 12;
    assert_eq!(k.w("(dc)"), "12");
    assert_eq!(k.kind("(dc)"), "int");
    // cmd joins its arguments with a leading space each (9.6), runs the line, and returns
    // the output as a string.
    assert_eq!(k.w("(cmd echo hello world)"), "ran[ echo hello world]\n");
    assert_eq!(k.kind("(cmd print s1)"), "string");
    // The `%e` messages start on a fresh line; the math errors do not.
    k.w("(trim 12)");
    assert!(k.fresh);
    k.w("(@ <s>)");
    assert!(k.fresh);
    k.w("(+ a)");
    assert!(!k.fresh);
}

#[test]
fn random_numbers_after_srand_7_as_the_official_kernel() {
    let mut k = Kit::new(); // Mt19937::new(7) is `srand 7`.
    check(
        &mut k,
        &[
            ("(rand-int)", "327741615"),
            ("(rand-int 10)", "4"),
            ("(rand-int 10)", "9"),
            ("(rand-int 0)", "1369975286"),
            ("(rand-int -5)", "1882953283"),
            ("(rand-int 2.9)", "0"),
            ("(rand-int 4294967296)", "0"),
            ("(rand-int 4294967297)", "0"),
            ("(rand-float)", "0.263871"),
            ("(rand-float 10)", "5.011205"),
            ("(rand-float -1)", "0.086743"),
            ("(rand-float 0.5)", "0.036026"),
            ("(rand-float 2)", "0.838744"),
        ],
    );
    let mut k = Kit::new();
    assert_eq!(k.kind("(rand-int)"), "int");
    assert_eq!(k.kind("(rand-float)"), "float");
    // (rand-int 1.0e30): the cast gives i64::MIN, not positive: the raw 32-bit output.
    let mut k2 = Kit::new();
    assert_eq!(k2.w("(rand-int 1.0e30)"), "327741615");
}

#[test]
fn write_trace_log_and_learning_flags_as_the_official_kernel() {
    let mut k = Kit::new();
    let d = k.new_var("<d>", 'd');
    for (arg, want) in [
        ("abc", "abc"),
        ("|a b|", "a b"),
        ("1.5", "1.500000"),
        // Soar has no negative zero: 9.6 writes `-0.0` as 0.000000.
        ("-0.0", "0.000000"),
        ("<s>", "S1"),
        ("||", ""),
        ("|x\\|y|", "x|y"),
    ] {
        k.out.clear();
        assert_eq!(k.w(&format!("(write {arg})")), "<none>");
        assert_eq!(k.out, want, "{arg}");
    }
    k.out.clear();
    assert_eq!(k.w("(write)"), "<none>");
    assert_eq!(k.out, "");
    k.w("(write |[| (crlf) |]|)");
    k.w("(write 1 2.5 abc |a b| <s> (crlf))");
    assert_eq!(k.out, "[\n]12.500000abca bS1\n");
    k.out.clear();
    let bad = |n: &str| {
        format!("Error: First argument of agent's (trace) rhs-function must be an integer trace level between 0 and 5.  {n} is invalid.")
    };
    assert_eq!(k.w("(trace 0 |T0|)"), "<none>");
    assert_eq!(k.w("(trace 1 |T1|)"), "<none>");
    assert_eq!(k.w("(trace 6 |T6|)"), bad("6"));
    assert!(k.fresh);
    assert_eq!(k.w("(trace abc x)"), bad("abc"));
    assert_eq!(k.w("(trace -1 x)"), bad("-1"));
    assert_eq!(k.w("(trace 5 |T5|)"), "<none>");
    assert_eq!(k.out, "T1");
    k.out.clear();
    // Observed: watch 2 prints trace 1-2, watch 3 and above trace 1-5; trace 0 never.
    k.trace_level = 3;
    for l in 0..=5 {
        k.w(&format!("(trace {l} |T{l} |)"));
    }
    assert_eq!(k.out, "T1 T2 T3 T4 T5 ");
    k.out.clear();
    let badlog = |n: &str| {
        format!("Error: First argument of agent's (log) rhs-function must be an integer channel number between 1 and 100.  {n} is invalid.")
    };
    assert_eq!(k.w("(log 1 |L1|)"), "<none>");
    assert_eq!(k.w("(log 0 x)"), badlog("0"));
    assert_eq!(k.w("(log 100 x)"), "<none>");
    assert_eq!(k.w("(log 2.5 x)"), badlog("2.500000"));
    assert_eq!(k.w("(log abc x)"), badlog("abc"));
    assert_eq!(k.out, "L1x");
    assert_eq!(k.w("(count a b 1.5)"), "<none>");
    assert_eq!(k.reg.counts.get("1.500000"), Some(&1));
    assert_eq!(
        k.w("(dont-learn abc)"),
        "Error: non-identifier (abc) passed to dont-learn function."
    );
    assert_eq!(k.dont_learn, None);
    assert_eq!(
        k.w("(dont-learn <d>)"),
        "Error: identifier passed to dont-learn is not a state: D1."
    );
    assert_eq!(k.dont_learn, Some(d)); // 9.6 records it anyway
    assert_eq!(
        k.w("(force-learn 1)"),
        "Error: non-identifier (1) passed to force-learn function."
    );
    assert_eq!(
        k.w("(force-learn <d>)"),
        "Error: identifier passed to force-learn is not a state: D1."
    );
    let s = k.var("<s>");
    assert_eq!(k.w("(force-learn <s>)"), "<none>");
    assert_eq!(k.force_learn, Some(s));
    assert_eq!(k.w("(halt)"), "<none>");
    assert!(k.halt);
    assert_eq!(k.w("(wait 1)"), "<none>");
    assert_eq!(k.w("(wait abc)"), "<none>");
}

#[test]
fn agent_writes_off_silences_write_trace_and_log() {
    let mut k = Kit::new();
    let args = [k.symbols.int(9), k.symbols.str("x")];
    for name in ["write", "trace", "log"] {
        let mut ctx = RhsContext::new(
            &mut k.symbols,
            &k.wm,
            &mut k.rng,
            &mut k.reg,
            &mut k.out,
            "a",
        );
        ctx.agent_writes = false;
        assert_eq!(call(name, &args, &mut ctx), Ok(None), "{name}");
    }
    assert_eq!(k.out, "");
}

/// The structure of the `set-*` experiment: `(<s> ^data <d>)`, `(<d> ^n 1 ^n 2 ^n 3.5 ^n abc
/// ^x 2.5 ^y 3 ^z 4 ^sub <q> ^sub <r>)`, `(<q> ^v 1 ^w 10)`, `(<r> ^v 2 ^w 20 ^w 30)`,
/// `(<f> ^a 2.5)`, `(<e> ^q <e>)`.
#[test]
fn size_sum_product_and_sets_as_the_official_kernel() {
    let mut k = Kit::new();
    let s = k.var("<s>");
    let d = k.new_var("<d>", 'd');
    let q = k.new_var("<q>", 'q');
    let r = k.new_var("<r>", 'r');
    let f = k.new_var("<f>", 'f');
    // The kernel's <e> was E2 (E1 is the epmem link).
    k.symbols.new_id('e', 1);
    let e = k.new_var("<e>", 'e');
    fn add(k: &mut Kit, id: Sym, attr: &str, v: &str) {
        let a = k.symbols.str(attr);
        let v = k.lit(v);
        k.wm.add(id, a, v, false);
    }
    add(&mut k, s, "data", "<d>");
    for (a, v) in [
        ("n", "1"),
        ("n", "2"),
        ("n", "3.5"),
        ("n", "abc"),
        ("x", "2.5"),
        ("y", "3"),
        ("z", "4"),
        ("sub", "<q>"),
        ("sub", "<r>"),
    ] {
        add(&mut k, d, a, v);
    }
    add(&mut k, q, "v", "1");
    add(&mut k, q, "w", "10");
    add(&mut k, r, "v", "2");
    add(&mut k, r, "w", "20");
    add(&mut k, r, "w", "30");
    add(&mut k, f, "a", "2.5");
    add(&mut k, e, "q", "<e>");
    // An acceptable-preference WME is in no slot.
    let op = k.symbols.str("operator");
    k.wm.add(d, op, q, true);
    check(
        &mut k,
        &[
            ("(size <d>)", "9"),
            ("(sum <f>)", "0"),
            ("(product <f>)", "0"),
            ("(size <f>)", "1"),
            ("(sum <e>)", "2"),
            ("(set-count <d> n)", "4"),
            ("(set-sum <d> n)", "6.500000"),
            ("(set-multiply <d> n)", "7.000000"),
            ("(set-min <d> n)", "1.000000"),
            ("(set-max <d> n)", "3.500000"),
            ("(set-range <d> n)", "2.500000"),
            ("(set-mean <d> n)", "2.166667"),
            ("(set-stdev <d> n)", "1.027402"),
            ("(set-count <d> nothere)", "0"),
            ("(set-sum <d> nothere)", "NaN"),
            ("(set-min <d> nothere)", "NaN"),
            ("(set-count <d> sub)", "2"),
            ("(set-sum <d> sub v)", "3.000000"),
            ("(set-sum <d> sub w)", "60.000000"),
            ("(set-count <d> sub w)", "3"),
            ("(set-mean <d> sub w)", "20.000000"),
            ("(set-count <s> data sub w)", "3"),
            ("(set-sum <s> data sub w)", "60.000000"),
            ("(set-count <d>)", "0"),
            ("(set-sum <d>)", "NaN"),
            ("(set-count <d> 1)", "0"),
            ("(set-sum <d> x)", "2.500000"),
            ("(set-multiply <d> x)", "2.500000"),
            ("(set-stdev <d> x)", "0.000000"),
            ("(set-count <d> n <d>)", "0"),
            // 9.6 crashes on these; an error string here.
            (
                "(set-count)",
                "|ERROR: First parameter needs to be an identifier.|",
            ),
        ],
    );
    assert_eq!(k.kind("(set-count <d> n)"), "int");
    assert_eq!(k.kind("(set-sum <d> n)"), "float");
    assert_eq!(k.kind("(set-sum <d> nothere)"), "string");
    // `sum` reads ints: ints add, `product` multiplies (wrapping 32-bit).
    assert_eq!(k.w("(sum <q>)"), "11");
    assert_eq!(k.w("(product <r>)"), "1200");
    // The caller's view of slots replaces the default one: 9.6 keeps the architecture
    // WMEs of a state out of its slots.
    let data = k.symbols.str("data");
    let only_data = |id: Sym| -> (Vec<WmeId>, Vec<WmeId>) {
        let v =
            k.wm.of_id(id)
                .filter(|w| k.wm.get(*w).is_some_and(|x| x.attr == data))
                .collect();
        (v, Vec::new())
    };
    let mut out = String::new();
    let mut symbols = std::mem::take(&mut k.symbols);
    let mut ctx = RhsContext::new(&mut symbols, &k.wm, &mut k.rng, &mut k.reg, &mut out, "a");
    ctx.wme_order = Some(&only_data);
    let r = call("size", &[s], &mut ctx).unwrap().unwrap();
    assert_eq!(value_text(&symbols, r), "1");
}

/// `deep-copy` of `(<d> ^a <x1> ^a <x2> ^b <x3> ^e 1) (<x1> ^c <x4>) (<x3> ^d 1)` made by
/// one firing (timetags 15-20 as in the kernel: `^a X2` 15, `^a X1` 16, `^b X3` 17,
/// `^e 1` 18, `X1 ^c X4` 19, `X3 ^d 1` 20). The kernel's copy was `D2` with `X1->X5`,
/// `X4->X6`, `X2->X7`, `X3->X8`.
#[test]
fn deep_copy_numbers_identifiers_as_the_official_kernel() {
    let mut k = Kit::new();
    let s = k.var("<s>");
    let d = k.new_var("<d>", 'd');
    let x: Vec<Sym> = (1..=4)
        .map(|i| k.new_var(&format!("<x{i}>"), 'x'))
        .collect();
    let data = k.symbols.str("data");
    k.wm.add(s, data, d, false);
    for (id, attr, v) in [
        ("<d>", "a", "<x2>"),
        ("<d>", "a", "<x1>"),
        ("<d>", "b", "<x3>"),
        ("<d>", "e", "1"),
        ("<x1>", "c", "<x4>"),
        ("<x3>", "d", "1"),
    ] {
        let id = k.var(id);
        let a = k.symbols.str(attr);
        let v = k.lit(v);
        k.wm.add(id, a, v, false);
    }
    // The self-reference of the first experiment (`D1 ^back D1` became `D3 ^back D3`).
    let back = k.symbols.str("back");
    k.wm.add(x[2], back, x[2], false);
    let root = k.eval_sym("(deep-copy <d>)").unwrap().unwrap();
    let t = |k: &Kit, s: Sym| value_text(&k.symbols, s);
    assert_eq!(t(&k, root), "D2");
    let got: Vec<String> = k
        .copies
        .iter()
        .map(|(i, a, v)| format!("({} ^{} {})", t(&k, *i), t(&k, *a), t(&k, *v)))
        .collect();
    assert_eq!(
        got,
        [
            "(X5 ^c X6)",
            "(D2 ^a X5)",
            "(D2 ^a X7)",
            "(X8 ^d 1)",
            "(X8 ^back X8)",
            "(D2 ^b X8)",
            "(D2 ^e 1)",
        ]
    );
    // Copies are new identifiers at level 0 (the caller sets the level).
    assert_eq!(k.symbols.id_data(root).map(|d| d.level), Some(0));
    // A second deep-copy replaces the list.
    let x4 = k.eval_sym("(deep-copy <x4>)").unwrap().unwrap();
    assert_eq!(t(&k, x4), "D3");
    assert!(k.copies.is_empty());
}

#[test]
fn deep_copy_of_a_long_chain_does_not_overflow_the_stack() {
    let mut k = Kit::new();
    let next = k.symbols.str("next");
    let first = k.new_var("<c>", 'c');
    let mut cur = first;
    for _ in 0..200_000 {
        let n = k.symbols.new_id('c', 1);
        k.wm.add(cur, next, n, false);
        cur = n;
    }
    k.eval_sym("(deep-copy <c>)").unwrap().unwrap();
    assert_eq!(k.copies.len(), 200_000);
}

/// `(from-st-xml |<root><a>hello</a><b type="integer">42</b><c type="double">2.1</c>
/// <d><e>x</e></d><f value="v"/><g link="L1"/><h link-id="L1">z</h>
/// <i type="integer">abc</i></root>|)`: the kernel made `R4` and, in timetag order,
/// `R4 ^a hello`, `^b 42`, `^c 2.100000`, `D1 ^e x`, `R4 ^d D1`, `^f v`, `^h z`, `^i 0`,
/// `^g z`; `(from-st-xml |notxml|)` skipped its action silently.
#[test]
fn from_st_xml_as_the_official_kernel() {
    let mut k = Kit::new();
    let xml = r#"(from-st-xml |<root><a>hello</a><b type="integer">42</b><c type="double">2.1</c><d><e>x</e></d><f value="v"/><g link="L1"/><h link-id="L1">z</h><i type="integer">abc</i></root>|)"#;
    let root = k.eval_sym(xml).unwrap().unwrap();
    let t = |k: &Kit, s: Sym| value_text(&k.symbols, s);
    assert_eq!(t(&k, root), "R1");
    let got: Vec<String> = k
        .module
        .iter()
        .map(|(i, a, v)| format!("({} ^{} {})", t(&k, *i), t(&k, *a), t(&k, *v)))
        .collect();
    assert_eq!(
        got,
        [
            "(R1 ^a hello)",
            "(R1 ^b 42)",
            "(R1 ^c 2.100000)",
            "(D1 ^e x)",
            "(R1 ^d D1)",
            "(R1 ^f v)",
            "(R1 ^h z)",
            "(R1 ^i 0)",
            "(R1 ^g z)",
        ]
    );
    // std::stof: single precision.
    let c = k.module[2].2;
    assert_eq!(k.symbols.get(c), &SymData::Float(f64::from(2.1f32)));
    assert_eq!(k.w("(from-st-xml |notxml|)"), "");
    assert_eq!(k.w("(from-st-xml |<a><b></a>|)"), "");
}

/// Lines typed to `accept`, as the kernel read them: `  42 abc` -> 42, `2.5` -> 2.5,
/// empty and blank lines skipped, `|a b| c` -> `|`, `S1` -> the string `S1`, `<x>` -> `<`,
/// `(foo)` -> `(`.
#[test]
fn accept_reads_symbols_as_the_official_kernel() {
    assert_eq!(accept_symbol("  42 abc\n"), Some(Accepted::Int(42)));
    assert_eq!(accept_symbol("2.5\n"), Some(Accepted::Float(2.5)));
    assert_eq!(accept_symbol("\n"), None);
    assert_eq!(accept_symbol("   \n"), None);
    assert_eq!(accept_symbol("|a b| c\n"), Some(Accepted::Str("|".into())));
    assert_eq!(accept_symbol("S1\n"), Some(Accepted::Str("S1".into())));
    assert_eq!(accept_symbol("<x>\n"), Some(Accepted::Str("<".into())));
    assert_eq!(accept_symbol("(foo)\n"), Some(Accepted::Str("(".into())));
    assert_eq!(accept_symbol("1e3"), Some(Accepted::Str("1e3".into())));
    assert_eq!(
        accept_symbol("99999999999999999999"),
        Some(Accepted::BadInt)
    );
}

#[test]
fn registry_registers_replaces_and_unregisters() {
    let mut r = Registry::new();
    assert!(!r.is_registered("f"));
    assert!(r
        .register("f", Box::new(|_: &str, a: &str| a.to_uppercase()))
        .is_none());
    assert_eq!(r.call("f", "agent", "abc"), Some(Ok(Ok("ABC".into()))));
    assert!(r
        .register("f", Box::new(|ag: &str, _: &str| ag.to_string()))
        .is_some());
    assert_eq!(r.call("f", "me", ""), Some(Ok(Ok("me".into()))));
    assert!(r.unregister("f"));
    assert_eq!(r.call("f", "agent", "abc"), None);
    // A panic in a function is an error, not the end of the program.
    r.register("boom", Box::new(|_: &str, _: &str| panic!("no way")));
    assert_eq!(
        r.call("boom", "a", ""),
        Some(Err("rhs function boom panicked: no way".into()))
    );
    // A registered function may keep state.
    let mut n = 0;
    r.register(
        "counter",
        Box::new(move |_: &str, _: &str| {
            n += 1;
            n.to_string()
        }),
    );
    assert_eq!(r.call("counter", "a", ""), Some(Ok(Ok("1".into()))));
    assert_eq!(r.call("counter", "a", ""), Some(Ok(Ok("2".into()))));
}

#[test]
fn timestamp_layout() {
    assert_eq!(timestamp_text(0, 0), "1970-01-01 00:00:00.000");
    assert_eq!(timestamp_text(1_795_831_287, 30), "2026-11-28 02:01:27.030");
    assert_eq!(timestamp_text(951_782_400, 999), "2000-02-29 00:00:00.999");
    let mut k = Kit::new();
    let ts = k.w("(timestamp)");
    assert_eq!(ts.len(), 23, "{ts}");
}

#[test]
fn c_conversions() {
    assert_eq!(c_strtol("  -12x"), Ok(-12));
    assert_eq!(c_strtol("x"), Ok(0));
    assert_eq!(c_strtol("-9223372036854775809"), Err(text::Erange));
    assert_eq!(c_strtod("0x1.8p1"), (3.0, false));
    assert_eq!(c_strtod(".5"), (0.5, false));
    assert_eq!(c_strtod("5."), (5.0, false));
    assert_eq!(c_strtod("1e"), (1.0, false));
    assert_eq!(c_strtod("-"), (0.0, false));
    assert_eq!(c_strtod("0e-999999999999"), (0.0, false));
    assert!(c_strtod("1e999999999999").1);
    assert_eq!(c_strtod("Infinity").0, f64::INFINITY);
    assert_eq!(c_fixed(0.125, 2), "0.12");
    assert_eq!(c_fixed(f64::NEG_INFINITY, 6), "-inf");
}

/// Every name in the parse-time table (`crate::rhs::table`) is evaluated here, except
/// the three the 9.6 binary lacks (they fall through to `exec`, as in 9.6).
#[test]
fn every_parse_time_builtin_is_implemented() {
    const NOT_IN_96: [&str; 3] = ["predict-x", "predict-y", "compute-closest-intercept"];
    for f in crate::rhs::table::BUILTINS {
        assert!(
            is_builtin(f.name) || NOT_IN_96.contains(&f.name),
            "{} is in the parse-time table but not implemented",
            f.name
        );
    }
}

/// No input makes a function panic: every built-in with 0-5 arguments of every kind.
#[test]
fn no_panics_on_odd_arguments() {
    let mut k = Kit::new();
    let s = k.var("<s>");
    let pool = [
        k.symbols.int(0),
        k.symbols.int(-1),
        k.symbols.int(i64::MIN),
        k.symbols.int(i64::MAX),
        k.symbols.float(0.0),
        k.symbols.float(f64::NAN),
        k.symbols.float(f64::INFINITY),
        k.symbols.float(-1e300),
        k.symbols.str(""),
        k.symbols.str("abc"),
        k.symbols.str("<a>x"),
        s,
    ];
    let skip = ["accept", "wait"];
    for name in BUILTIN_NAMES.iter().filter(|n| !skip.contains(n)) {
        for n in 0..=4usize {
            for start in 0..pool.len() {
                let args: Vec<Sym> = (0..n).map(|i| pool[(start + i * 5) % pool.len()]).collect();
                let _ = k.call_syms(name, &args);
            }
        }
    }
    // `wait` with a negative or non-integer argument returns at once.
    let neg = k.symbols.int(-5);
    assert_eq!(k.call_syms("wait", &[neg]), Ok(None));
}

/// `(write (deep-copy <d>) (crlf)) (<s> ^foo bar)` over `(<d> ^a 1 ^b <x>) (<x> ^c 2)`:
/// the kernel's `watch 5` showed the instantiation's preferences (head first)
/// `(D2 ^b X2 +)`, `(X2 ^c 2 +)`, `(D2 ^a 1 +)`, `(S1 ^foo bar +)`: the copy made inside
/// the stand-alone `write` leaked into the next make action, in the list order
/// `(D2 ^a 1)`, `(X2 ^c 2)`, `(D2 ^b X2)`.
#[test]
fn deep_copy_list_order_as_the_official_kernel() {
    let mut k = Kit::new();
    let d = k.new_var("<d>", 'd');
    let x = k.new_var("<x>", 'x');
    for (id, attr, v) in [(d, "a", "1"), (d, "b", "<x>"), (x, "c", "2")] {
        let a = k.symbols.str(attr);
        let v = k.lit(v);
        k.wm.add(id, a, v, false);
    }
    k.out.clear();
    assert_eq!(k.w("(write (deep-copy <d>) (crlf))"), "<none>");
    assert_eq!(k.out, "D2\n");
    let t = |k: &Kit, s: Sym| value_text(&k.symbols, s);
    let got: Vec<String> = k
        .copies
        .iter()
        .map(|(i, a, v)| format!("({} ^{} {})", t(&k, *i), t(&k, *a), t(&k, *v)))
        .collect();
    assert_eq!(got, ["(D2 ^a 1)", "(X2 ^c 2)", "(D2 ^b X2)"]);
}
