//! Human names for grammar rules, used in "expected …" messages: the words a RAPID
//! programmer knows ("`;`", "`ENDIF`", "an expression"), never internal rule names.

use super::grammar::diag::Rule;

/// How an expected rule is shown, ordered by how useful it is to list first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Expected {
    /// A keyword that closes a construct (`ENDIF`, `ENDPROC`).
    Closer(&'static str),
    /// Any other keyword (`THEN`, `DO`).
    Keyword(&'static str),
    /// Punctuation (`;`, `)`).
    Token(&'static str),
    /// A syntactic category (an expression, a statement).
    Thing(&'static str),
    /// Any binary operator.
    Operator,
}

impl Expected {
    /// The text shown in messages.
    pub(crate) fn text(self) -> &'static str {
        match self {
            Expected::Closer(s)
            | Expected::Keyword(s)
            | Expected::Token(s)
            | Expected::Thing(s) => s,
            Expected::Operator => "an operator",
        }
    }
}

/// The human name of a rule of the diagnostic parser; `None` for rules that are never worth
/// naming (recovery rules, placeholders).
pub(crate) fn expected(rule: Rule) -> Option<Expected> {
    use Expected::*;
    Some(match rule {
        Rule::semi => Token("`;`"),
        Rule::comma => Token("`,`"),
        Rule::colon => Token("`:`"),
        Rule::assign => Token("`:=`"),
        Rule::lparen | Rule::call_args | Rule::paren | Rule::params | Rule::module_attrs => {
            Token("`(`")
        }
        Rule::rparen => Token("`)`"),
        Rule::lbracket => Token("`[`"),
        Rule::rbracket => Token("`]`"),
        Rule::lbrace | Rule::dims | Rule::index | Rule::open_dims => Token("`{`"),
        Rule::rbrace => Token("`}`"),
        Rule::dot | Rule::component => Token("`.`"),
        Rule::backslash => Thing("an optional argument (`\\Name`)"),
        Rule::optional_mark => Token("`\\`"),
        Rule::question | Rule::cond_arg => Token("`?`"),
        Rule::percent | Rule::late_call => Token("`%`"),
        Rule::bar => Token("`|`"),
        Rule::star | Rule::open_dim => Token("`*`"),

        Rule::infix_op
        | Rule::kw_div
        | Rule::kw_mod
        | Rule::kw_and
        | Rule::kw_or
        | Rule::kw_xor => Operator,

        Rule::kw_endif => Closer("`ENDIF`"),
        Rule::kw_endwhile => Closer("`ENDWHILE`"),
        Rule::kw_endfor => Closer("`ENDFOR`"),
        Rule::kw_endtest => Closer("`ENDTEST`"),
        Rule::kw_endproc => Closer("`ENDPROC`"),
        Rule::kw_endfunc => Closer("`ENDFUNC`"),
        Rule::kw_endtrap => Closer("`ENDTRAP`"),
        Rule::kw_endrecord | Rule::record_end => Closer("`ENDRECORD`"),
        Rule::kw_endmodule | Rule::module_end => Closer("`ENDMODULE`"),

        Rule::kw_alias => Keyword("`ALIAS`"),
        Rule::kw_backward | Rule::backward_section => Keyword("`BACKWARD`"),
        Rule::kw_case | Rule::case_clause => Keyword("`CASE`"),
        Rule::kw_connect => Keyword("`CONNECT`"),
        Rule::kw_const => Keyword("`CONST`"),
        Rule::kw_default | Rule::default_clause => Keyword("`DEFAULT`"),
        Rule::kw_do => Keyword("`DO`"),
        Rule::kw_else | Rule::else_clause => Keyword("`ELSE`"),
        Rule::kw_elseif | Rule::elseif_clause => Keyword("`ELSEIF`"),
        Rule::kw_error | Rule::error_section => Keyword("`ERROR`"),
        Rule::kw_exit => Keyword("`EXIT`"),
        Rule::kw_false => Keyword("`FALSE`"),
        Rule::kw_for => Keyword("`FOR`"),
        Rule::kw_from => Keyword("`FROM`"),
        Rule::kw_func | Rule::func_head => Keyword("`FUNC`"),
        Rule::kw_goto => Keyword("`GOTO`"),
        Rule::kw_if => Keyword("`IF`"),
        Rule::kw_inout => Keyword("`INOUT`"),
        Rule::kw_local => Keyword("`LOCAL`"),
        Rule::kw_module | Rule::module_open => Keyword("`MODULE`"),
        Rule::kw_nostepin => Keyword("`NOSTEPIN`"),
        Rule::kw_not => Keyword("`NOT`"),
        Rule::kw_noview => Keyword("`NOVIEW`"),
        Rule::kw_pers => Keyword("`PERS`"),
        Rule::kw_proc | Rule::proc_head => Keyword("`PROC`"),
        Rule::kw_raise => Keyword("`RAISE`"),
        Rule::kw_readonly => Keyword("`READONLY`"),
        Rule::kw_record => Keyword("`RECORD`"),
        Rule::kw_retry => Keyword("`RETRY`"),
        Rule::kw_return => Keyword("`RETURN`"),
        Rule::kw_step => Keyword("`STEP`"),
        Rule::kw_sysmodule => Keyword("`SYSMODULE`"),
        Rule::kw_task => Keyword("`TASK`"),
        Rule::kw_test => Keyword("`TEST`"),
        Rule::kw_then => Keyword("`THEN`"),
        Rule::kw_to => Keyword("`TO`"),
        Rule::kw_trap | Rule::trap_head => Keyword("`TRAP`"),
        Rule::kw_true => Keyword("`TRUE`"),
        Rule::kw_trynext => Keyword("`TRYNEXT`"),
        Rule::kw_undo | Rule::undo_section => Keyword("`UNDO`"),
        Rule::kw_var => Keyword("`VAR`"),
        Rule::kw_viewonly => Keyword("`VIEWONLY`"),
        Rule::kw_while => Keyword("`WHILE`"),
        Rule::kw_with => Keyword("`WITH`"),

        Rule::ident | Rule::ph_id => Thing("a name"),
        Rule::number => Thing("a number"),
        Rule::string => Thing("a string"),
        Rule::expr | Rule::aggregate | Rule::named_arg => Thing("an expression"),
        Rule::opt_arg => Thing("an optional argument (`\\Name`)"),
        Rule::statement
        | Rule::call_stmt
        | Rule::assign_stmt
        | Rule::label_stmt
        | Rule::goto_stmt
        | Rule::return_stmt
        | Rule::raise_stmt
        | Rule::retry_stmt
        | Rule::trynext_stmt
        | Rule::exit_stmt
        | Rule::connect_stmt
        | Rule::if_stmt
        | Rule::while_stmt
        | Rule::for_stmt
        | Rule::test_stmt => Thing("a statement"),
        Rule::data_decl => Thing("a data declaration"),
        Rule::record_decl | Rule::alias_decl => Thing("a type definition"),
        Rule::routine => Thing("a routine (PROC, FUNC or TRAP)"),
        Rule::record_field => Thing("a record component (`type name;`)"),
        Rule::param_group | Rule::param => Thing("a parameter"),
        Rule::EOI => Thing("the end of the file"),
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_words_not_rules() {
        assert_eq!(expected(Rule::semi).map(Expected::text), Some("`;`"));
        assert_eq!(
            expected(Rule::kw_endif).map(Expected::text),
            Some("`ENDIF`")
        );
        assert_eq!(expected(Rule::infix_op), Some(Expected::Operator));
        assert_eq!(expected(Rule::bad_stmt), None);
    }
}
