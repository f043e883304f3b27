//! Modules: the head (name, attributes), the items in source order, and the end keyword.
//! The driver in `build.rs` hands them over piece by piece.

use super::expr::placeholder;
use super::{Builder, ModuleUnderConstruction};
use crate::ast::{Ident, Module, ModuleAttr, ModuleItem, PackedData};
use crate::parse::grammar::{Pair, Rule};
use crate::parse::recover::Region;
use crate::source::Spanned;

impl<'t> Builder<'t, '_> {
    /// A `module_open` pair: `MODULE name [(attributes)]`.
    pub(crate) fn module_open(&mut self, p: Pair<'_>) -> ModuleUnderConstruction<'t> {
        let mut span = self.span(&p);
        let mut name: Option<Ident> = None;
        let mut attrs = Vec::new();
        let mut inner = p.into_inner();
        let kw = inner.next();
        let opener = kw.as_ref().map_or(span, |k| self.span(k));
        let opener_text = kw.as_ref().map_or("MODULE", |k| self.text_of(k));
        for item in inner {
            match item.as_rule() {
                Rule::ident | Rule::ph_id if name.is_none() => name = Some(self.ident(&item)),
                Rule::module_attrs => {
                    for a in item.into_inner() {
                        let attr = match a.as_rule() {
                            Rule::kw_sysmodule => ModuleAttr::SysModule,
                            Rule::kw_nostepin => ModuleAttr::NoStepIn,
                            Rule::kw_readonly => ModuleAttr::ReadOnly,
                            Rule::kw_viewonly => ModuleAttr::ViewOnly,
                            _ => ModuleAttr::NoView,
                        };
                        attrs.push(Spanned::new(attr, self.span(&a)));
                    }
                }
                Rule::bad_head => {
                    let kind = crate::parse::recover::diagnose(
                        self.file,
                        self.text,
                        opener.start as usize,
                        self.end(&item),
                        Region::ModuleHead,
                    );
                    self.error(kind);
                }
                _ => {}
            }
        }
        span = opener.merge(name.as_ref().map_or(opener, |n| n.span));
        if let Some(a) = attrs.last() {
            span = span.merge(a.span);
        }
        let name = name.unwrap_or_else(|| Spanned::new(Default::default(), opener.end_point()));
        ModuleUnderConstruction {
            module: Module {
                name,
                attrs,
                items: Vec::new(),
                span,
            },
            opener,
            opener_text,
        }
    }

    /// One module item: a declaration, a routine, a placeholder, or a skipped region.
    pub(crate) fn module_item(&mut self, m: &mut ModuleUnderConstruction<'t>, item: Pair<'_>) {
        let span = self.span(&item);
        let built = match item.as_rule() {
            Rule::record_decl => self.record(item).map(|r| ModuleItem::Record(Box::new(r))),
            Rule::alias_decl => self.alias(item).map(|a| ModuleItem::Alias(Box::new(a))),
            Rule::data_decl => {
                let errors = self.errors;
                self.data_decl(item).map(|d| {
                    // (Kept as its text when it reads back as built; see `PackedData`.)
                    if self.pack
                        && self.errors == errors
                        && let Some(p) = PackedData::pack(self.file, self.text, &d)
                    {
                        ModuleItem::PackedData(p)
                    } else {
                        ModuleItem::Data(Box::new(d))
                    }
                })
            }
            Rule::routine => self.routine(item).map(|r| ModuleItem::Routine(Box::new(r))),
            Rule::item_placeholder => item.into_inner().next().map(|ph| {
                ModuleItem::Placeholder(Spanned::new(placeholder(self.text_of(&ph)), span))
            }),
            Rule::bad_item => {
                self.skipped(&item, Region::Item);
                None
            }
            _ => None,
        };
        m.module.span = m.module.span.merge(span);
        if let Some(b) = built {
            m.module.items.push(b);
        }
    }

    /// The `module_end` pair: `ENDMODULE`, or nothing (reported).
    pub(crate) fn module_end(
        &mut self,
        mut m: ModuleUnderConstruction<'_>,
        end: Pair<'_>,
    ) -> Module {
        if let Some(e) = end.into_inner().next() {
            if e.as_rule() == Rule::missing_endmodule {
                let at = self.start(&e);
                self.missing_end_at(at, m.opener, m.opener_text, "ENDMODULE");
            } else {
                m.module.span = m.module.span.merge(self.span(&e));
            }
        }
        m.module
    }
}
