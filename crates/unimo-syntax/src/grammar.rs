//! The pest parser generated from `modelica.pest`.

#[derive(pest_derive::Parser)]
#[grammar = "modelica.pest"]
pub struct ModelicaParser;

/// A human name for a grammar rule, as used in "expected ..." messages.
pub fn describe(rule: Rule) -> Option<&'static str> {
    Some(match rule {
        Rule::ident | Rule::name | Rule::type_specifier => "identifier",
        Rule::semi => "`;`",
        Rule::kw_end => "`end`",
        Rule::expression | Rule::simple_expression | Rule::operand_expr | Rule::primary => {
            "expression"
        }
        Rule::equation | Rule::simple_or_call_equation => "equation",
        Rule::statement | Rule::assign_or_call => "statement",
        Rule::element | Rule::element_body | Rule::component_clause => "declaration",
        Rule::class_definition
        | Rule::class_prefixes
        | Rule::class_kind
        | Rule::expandable_kw
        | Rule::purity_kw
        | Rule::operator_kw => "class definition",
        Rule::external_clause | Rule::kw_external => "`external`",
        Rule::string | Rule::description => "string",
        Rule::unsigned_integer | Rule::unsigned_real => "number",
        Rule::component_reference | Rule::ref_part => "component reference",
        Rule::array_subscripts => "`[`",
        Rule::class_modification => "`(`",
        Rule::function_call_args => "`(`",
        Rule::modification | Rule::binding => "`=`",
        Rule::comment | Rule::annotation_clause => "annotation",
        Rule::kw_then => "`then`",
        Rule::kw_loop => "`loop`",
        Rule::kw_else => "`else`",
        Rule::kw_if => "`if`",
        Rule::kw_for => "`for`",
        Rule::kw_when => "`when`",
        Rule::kw_while => "`while`",
        Rule::kw_in => "`in`",
        Rule::kw_equation => "`equation`",
        Rule::kw_algorithm => "`algorithm`",
        Rule::kw_enumeration => "`enumeration`",
        Rule::eq_op => "`=`",
        Rule::or_op
        | Rule::and_op
        | Rule::lt_op
        | Rule::le_op
        | Rule::gt_op
        | Rule::ge_op
        | Rule::eq_eq_op
        | Rule::ne_op
        | Rule::add_op
        | Rule::sub_op
        | Rule::mul_op
        | Rule::div_op
        | Rule::pow_op
        | Rule::ew_add
        | Rule::ew_sub
        | Rule::ew_mul
        | Rule::ew_div
        | Rule::ew_pow => "operator",
        Rule::EOI => "end of file",
        Rule::comma => "`,`",
        _ => return None,
    })
}
