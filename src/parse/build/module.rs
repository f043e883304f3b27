//! Modules: name, attributes, the items in source order, and the end keyword.

use super::Builder;
use super::expr::placeholder;
use crate::ast::{Ident, Module, ModuleAttr, ModuleItem};
use crate::parse::grammar::{Pair, Rule};
use crate::parse::recover::Region;
use crate::source::Spanned;

impl Builder<'_, '_> {
    /// A `module` pair.
    pub(crate) fn module(&mut self, p: Pair<'_>) -> Option<Module> {
        let span = self.span(&p);
        let mut inner = p.into_inner();
        let kw = inner.next()?;
        let mut name: Option<Ident> = None;
        let mut attrs = Vec::new();
        let mut items = Vec::new();
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
                    let start = kw.as_span().start();
                    let kind = crate::parse::recover::diagnose(
                        self.file,
                        self.text,
                        start,
                        item.as_span().end(),
                        Region::ModuleHead,
                    );
                    self.error(kind);
                }
                Rule::record_decl => {
                    if let Some(r) = self.record(item) {
                        items.push(ModuleItem::Record(r));
                    }
                }
                Rule::alias_decl => {
                    if let Some(a) = self.alias(item) {
                        items.push(ModuleItem::Alias(a));
                    }
                }
                Rule::data_decl => {
                    if let Some(d) = self.data_decl(item) {
                        items.push(ModuleItem::Data(d));
                    }
                }
                Rule::routine => {
                    if let Some(r) = self.routine(item) {
                        items.push(ModuleItem::Routine(r));
                    }
                }
                Rule::item_placeholder => {
                    let span = self.span(&item);
                    let ph = item.into_inner().next()?;
                    items.push(ModuleItem::Placeholder(Spanned::new(
                        placeholder(ph.as_str()),
                        span,
                    )));
                }
                Rule::bad_item => self.skipped(&item, Region::Item),
                Rule::module_end => {
                    if let Some(m) = item.into_inner().next()
                        && m.as_rule() == Rule::missing_endmodule
                    {
                        self.missing_end(&m, &kw, "ENDMODULE");
                    }
                }
                _ => {}
            }
        }
        let name = name.unwrap_or_else(|| Spanned::new(String::new(), self.span(&kw).end_point()));
        Some(Module {
            name,
            attrs,
            items,
            span,
        })
    }
}
