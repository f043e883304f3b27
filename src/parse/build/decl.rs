//! Declarations: data (VAR/PERS/CONST with LOCAL, TASK and array dimensions), RECORD and
//! ALIAS type definitions.

use super::Builder;
use crate::ast::{AliasDecl, DataDecl, Ident, RecordDecl, RecordField, Storage};
use crate::parse::error::ParseErrorKind;
use crate::parse::grammar::{Pair, Rule};
use crate::parse::recover::Region;

impl Builder<'_, '_> {
    /// A `data_decl` pair (module or routine level; the caller checks what is allowed).
    pub(crate) fn data_decl(&mut self, p: Pair<'_>) -> Option<DataDecl> {
        let span = self.span(&p);
        let mut local = false;
        let mut task = false;
        let mut storage = Storage::Var;
        // The type, then the name.
        let mut ty: Option<Ident> = None;
        let mut name: Option<Ident> = None;
        let mut dims = Vec::new();
        let mut init = None;
        for item in p.into_inner() {
            match item.as_rule() {
                Rule::kw_local => local = true,
                Rule::kw_task => task = true,
                Rule::kw_var => storage = Storage::Var,
                Rule::kw_pers => storage = Storage::Pers,
                Rule::kw_const => storage = Storage::Const,
                Rule::ident | Rule::ph_id if ty.is_none() => ty = Some(self.ident(&item)),
                Rule::ident | Rule::ph_id if name.is_none() => name = Some(self.ident(&item)),
                Rule::dims => dims = self.dims(item)?,
                Rule::expr | Rule::simple_operand => init = Some(self.expr(item)?),
                _ => {}
            }
        }
        // `TASK VAR` and `TASK CONST` (seen in controller backups) say what VAR and CONST
        // data are anyway: one object per task. They are accepted at module level; in a
        // routine the caller reports `TASK`.
        Some(DataDecl {
            local,
            task,
            storage,
            ty: ty?,
            name: name?,
            dims,
            init,
            span,
        })
    }

    /// A `dims` pair: 1 to 3 dimension expressions.
    pub(crate) fn dims(&mut self, p: Pair<'_>) -> Option<Vec<crate::ast::Expr>> {
        let span = self.span(&p);
        let dims = self.exprs(p.into_inner())?;
        if dims.len() > 3 {
            self.error(ParseErrorKind::TooManyDimensions {
                span,
                count: dims.len(),
            });
        }
        Some(dims)
    }

    /// A `record_decl` pair.
    pub(crate) fn record(&mut self, p: Pair<'_>) -> Option<RecordDecl> {
        let span = self.span(&p);
        let mut local = false;
        let mut opener = None;
        let mut name = None;
        let mut fields = Vec::new();
        for item in p.into_inner() {
            match item.as_rule() {
                Rule::kw_local => local = true,
                Rule::kw_record => opener = Some(item),
                Rule::ident | Rule::ph_id => name = Some(self.ident(&item)),
                Rule::record_field => {
                    let fspan = self.span(&item);
                    let mut names = Vec::new();
                    let mut dims = Vec::new();
                    for f in item.into_inner() {
                        match f.as_rule() {
                            Rule::dims => {
                                if let Some(d) = self.dims(f) {
                                    dims = d;
                                }
                            }
                            _ => names.push(self.ident(&f)),
                        }
                    }
                    let mut names = names.into_iter();
                    if let (Some(ty), Some(name)) = (names.next(), names.next()) {
                        fields.push(RecordField {
                            ty,
                            name,
                            dims,
                            span: fspan,
                        });
                    }
                }
                Rule::bad_field => self.skipped(&item, Region::Field),
                Rule::record_end => {
                    if let (Some(m), Some(o)) = (item.into_inner().next(), opener.as_ref())
                        && m.as_rule() == Rule::missing_end
                    {
                        self.missing_end(&m, o, "ENDRECORD");
                    }
                }
                _ => {}
            }
        }
        Some(RecordDecl {
            local,
            name: name?,
            fields,
            span,
        })
    }

    /// An `alias_decl` pair.
    pub(crate) fn alias(&mut self, p: Pair<'_>) -> Option<AliasDecl> {
        let span = self.span(&p);
        let mut local = false;
        let mut names = Vec::new();
        for item in p.into_inner() {
            match item.as_rule() {
                Rule::kw_local => local = true,
                Rule::ident | Rule::ph_id => names.push(self.ident(&item)),
                _ => {}
            }
        }
        let mut names = names.into_iter();
        Some(AliasDecl {
            local,
            base: names.next()?,
            name: names.next()?,
            span,
        })
    }
}
