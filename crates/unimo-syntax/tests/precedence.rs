//! Operator precedence and associativity, checked against explicit trees (as
//! s-expressions) rather than snapshots, for both parsers.

use unimo_source::FileId;
use unimo_syntax::ast::{Expr, ExprKind};

fn sexpr(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Binary { op, lhs, rhs } => {
            format!("({} {} {})", op.symbol(), sexpr(lhs), sexpr(rhs))
        }
        ExprKind::Unary { op, operand } => format!("({} {})", op.symbol(), sexpr(operand)),
        ExprKind::Ref(r) => r.to_dotted(),
        ExprKind::Integer(v) => v.to_string(),
        ExprKind::Range { start, step, stop } => match step {
            Some(s) => format!("(: {} {} {})", sexpr(start), sexpr(s), sexpr(stop)),
            None => format!("(: {} {})", sexpr(start), sexpr(stop)),
        },
        ExprKind::If {
            branches,
            otherwise,
        } => {
            format!(
                "(if {} {} {})",
                sexpr(&branches[0].0),
                sexpr(&branches[0].1),
                sexpr(otherwise)
            )
        }
        other => format!("{other:?}"),
    }
}

const CASES: &[(&str, &str)] = &[
    ("-a + b", "(+ (- a) b)"),
    ("-a - b", "(- (- a) b)"),
    ("a + -b", "(+ a (- b))"),
    ("-a * b", "(- (* a b))"),
    ("-a ^ 2", "(- (^ a 2))"),
    ("+a - b", "(- (+ a) b)"),
    ("a - b - c", "(- (- a b) c)"),
    ("a / b / c", "(/ (/ a b) c)"),
    ("a + b * c", "(+ a (* b c))"),
    ("a * b ^ c", "(* a (^ b c))"),
    ("a ^ b ^ c", "(^ a (^ b c))"),
    ("a .* b .+ c", "(.+ (.* a b) c)"),
    ("not a < b", "(not (< a b))"),
    ("not a and b", "(and (not a) b)"),
    ("a or b and c", "(or a (and b c))"),
    ("a + 1 > b * 2", "(> (+ a 1) (* b 2))"),
    ("1:n - 1", "(: 1 (- n 1))"),
    ("1:2:n", "(: 1 2 n)"),
    ("if a then b else c + 1", "(if a b (+ c 1))"),
    ("a * -b * c", "(* a (- (* b c)))"),
];

fn check_file_equation(expr_text: &str, expected: &str) {
    let src = format!("model M equation x = {expr_text}; end M;");
    for (which, parsed) in [
        (
            "pest",
            Some(unimo_syntax::differential::pest_only(FileId(0), &src)),
        ),
        (
            "fast",
            unimo_syntax::differential::fast_only(FileId(0), &src),
        ),
    ] {
        let parsed = parsed.unwrap_or_else(|| panic!("{which} declined {src}"));
        let unimo_syntax::ast::ClassBody::Long { composition, .. } = &parsed.ast.classes[0].body
        else {
            panic!("not a long class")
        };
        let unimo_syntax::ast::Section::Equation(es) = &composition.sections[0] else {
            panic!("no equation section")
        };
        let unimo_syntax::ast::EquationKind::Simple { rhs, .. } = &es.equations[0].kind else {
            panic!("not a simple equation")
        };
        assert_eq!(sexpr(rhs), expected, "{which}: {expr_text}");
    }
}

#[test]
fn precedence_and_associativity_in_both_parsers() {
    for (text, expected) in CASES {
        check_file_equation(text, expected);
        let e = unimo_syntax::parse_expression(FileId(0), text).unwrap();
        assert_eq!(sexpr(&e), *expected, "parse_expression: {text}");
    }
}

#[test]
fn printer_keeps_the_tree() {
    for (text, _) in CASES {
        let e = unimo_syntax::parse_expression(FileId(0), text).unwrap();
        let printed = unimo_syntax::print::expr(&e);
        let again = unimo_syntax::parse_expression(FileId(0), &printed).unwrap();
        assert_eq!(sexpr(&again), sexpr(&e), "{text} printed as {printed}");
    }
}
