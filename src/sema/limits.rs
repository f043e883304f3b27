//! Data sizes known before the program runs, against [`crate::ir::limits`]: one
//! declaration, all module data of the task, and each routine's data on top of the module
//! data. What only the run knows (recursion, arrays passed by value) the interpreter checks
//! at each call.

use super::Checker;
use super::error::SemaErrorKind as K;
use crate::ast;
use crate::ir::limits::{MAX_DECL_VALUES, MAX_TASK_VALUES};
use crate::ir::{GlobalOrigin, LocalDecl, Ty};
use crate::source::Span;

impl Checker<'_> {
    /// How many values data of `ty` with sizes `dims` holds; reported at `span` when one
    /// declaration may not hold that many.
    fn declared_values(&mut self, name: &str, ty: Ty, dims: &[u32], span: Span) -> u64 {
        let values = self.types.values(ty, dims);
        if values > MAX_DECL_VALUES {
            self.err(
                K::DeclTooLarge {
                    name: name.to_string(),
                    values,
                },
                span,
            );
        }
        values
    }

    /// Every module data declaration within the per-declaration limit, and all of them
    /// together within the task's; the sum is kept for [`Checker::check_routine_data`].
    /// Predefined data (error numbers, signals, mechanical units) is not RAPID memory.
    pub(super) fn check_module_data(&mut self) {
        let mut total: u64 = 0;
        let mut reported = false;
        for gi in 0..self.globals.len() {
            let g = &self.globals[gi];
            if !matches!(g.origin, GlobalOrigin::Module(_)) {
                continue;
            }
            let (name, ty, dims) = (g.name.clone(), g.ty, g.dims.clone());
            let span = match self.global_decls[gi] {
                Some((_, ast::ModuleItem::Data(d))) => d.span,
                Some((m, ast::ModuleItem::PackedData(d))) => {
                    d.span(self.modules[m.0 as usize].source)
                }
                _ => g.span,
            };
            let values = self.declared_values(&name, ty, &dims, span);
            if values > MAX_DECL_VALUES {
                // Reported on its own; counting it would only repeat that.
                continue;
            }
            total = total.saturating_add(values);
            if total > MAX_TASK_VALUES && !reported {
                self.err(
                    K::TaskDataTooLarge {
                        name,
                        routine: None,
                        values: total,
                    },
                    span,
                );
                reported = true;
            }
        }
        self.module_values = total;
    }

    /// A routine's data declarations within the per-declaration limit, and with the module
    /// data within the task's.
    pub(super) fn check_routine_data(&mut self, routine: &str, locals: &[LocalDecl]) {
        let mut total = self.module_values;
        for l in locals {
            let values = self.declared_values(&l.name, l.ty, &l.dims, l.span);
            if values > MAX_DECL_VALUES {
                continue;
            }
            total = total.saturating_add(values);
            if total > MAX_TASK_VALUES {
                self.err(
                    K::TaskDataTooLarge {
                        name: l.name.clone(),
                        routine: Some(routine.to_string()),
                        values: total,
                    },
                    l.span,
                );
                return;
            }
        }
    }
}
