//! Declarations: types (RECORD, ALIAS), module data, predefined data and routine headers,
//! with duplicate, redeclaration and shared-PERS checks.

use super::error::SemaErrorKind as K;
use super::{Checker, Env};
use crate::ast::{self, ModuleItem, ParamMode, RoutineKind as AstKind, Storage};
use crate::ir::errnum;
use crate::ir::{
    Block, Field, Global, GlobalId, GlobalOrigin, ModuleId, ParamInfo, ParamSlot, Routine,
    RoutineId, RoutineKind, Ty, TypeId, TypeKind,
};
use crate::source::Span;

impl<'a> Checker<'a> {
    /// A type name → resolved type id (aliases followed).
    pub(super) fn resolve_type(&mut self, name: &ast::Ident) -> Option<TypeId> {
        match self.types.lookup(&name.node) {
            Some(id) => Some(self.types.resolve(id)),
            None => {
                self.err(
                    K::UnknownType {
                        name: name.node.to_string(),
                    },
                    name.span,
                );
                None
            }
        }
    }

    /// Register RECORD and ALIAS declarations (records get their components later).
    pub(super) fn collect_types(&mut self) {
        let mut aliases: Vec<(TypeId, &'a ast::AliasDecl)> = Vec::new();
        let mut records: Vec<(TypeId, ModuleId, &'a ast::RecordDecl)> = Vec::new();
        for mi in 0..self.module_asts.len() {
            let m = self.module_asts[mi];
            let stdlib = self.modules[mi].stdlib;
            for item in &m.items {
                let (name, span) = match item {
                    ModuleItem::Record(r) => (&r.name, r.span),
                    ModuleItem::Alias(a) => (&a.name, a.span),
                    _ => continue,
                };
                if let Some(existing) = self.types.lookup(&name.node) {
                    let builtin = !self.types.get(existing).user;
                    if builtin && stdlib && self.same_as_builtin(existing, item) {
                        continue;
                    }
                    let kind = match self.type_spans.get(&name.folded()) {
                        Some(first) => K::Duplicate {
                            name: name.node.to_string(),
                            first: *first,
                        },
                        None => K::PredefinedRedeclared {
                            name: name.node.to_string(),
                        },
                    };
                    self.err(kind, name.span);
                    continue;
                }
                self.type_spans.insert(name.folded(), span);
                match item {
                    ModuleItem::Alias(a) => {
                        let id =
                            self.types
                                .add(&a.name.node, TypeKind::Alias(TypeId::NUM), !stdlib);
                        aliases.push((id, a));
                    }
                    ModuleItem::Record(r) => {
                        let id = self.types.add(
                            &r.name.node,
                            TypeKind::Record {
                                fields: Vec::new(),
                                value: true,
                            },
                            !stdlib,
                        );
                        records.push((id, ModuleId(mi as u32), r));
                    }
                    _ => {}
                }
            }
        }
        for (id, a) in &aliases {
            if let Some(base) = self.types.lookup(&a.base.node) {
                self.types.set_kind(*id, TypeKind::Alias(base));
            } else {
                self.err(
                    K::UnknownType {
                        name: a.base.node.to_string(),
                    },
                    a.base.span,
                );
            }
        }
        // An alias chain must end in a real type.
        for (id, a) in aliases {
            if matches!(
                self.types.get(self.types.resolve(id)).kind,
                TypeKind::Alias(_)
            ) {
                self.err(
                    K::BadDecl {
                        why: format!("alias `{}` is defined in terms of itself", a.name.node),
                    },
                    a.span,
                );
                self.types.set_kind(id, TypeKind::Alias(TypeId::NUM));
            }
        }
        self.pending_records = records;
    }

    /// Fill in record components (after module data, so sizes may name constants).
    pub(super) fn fill_records(&mut self) {
        let records = std::mem::take(&mut self.pending_records);
        for &(id, m, r) in &records {
            self.cur_module = m;
            let mut fields = Vec::new();
            for f in &r.fields {
                let Some(base) = self.resolve_type(&f.ty) else {
                    continue;
                };
                let dims = self.const_dims(&f.dims);
                fields.push(Field {
                    name: f.name.node.to_string(),
                    ty: Ty {
                        base,
                        rank: f.dims.len() as u8,
                    },
                    dims,
                });
            }
            self.types.set_kind(
                id,
                TypeKind::Record {
                    fields,
                    value: true,
                },
            );
        }
        // A record may not contain itself (directly or through other records).
        for (id, _, r) in records {
            if self.record_contains(id, id, 0) {
                self.err(
                    K::BadDecl {
                        why: format!("record `{}` contains itself", r.name.node),
                    },
                    r.span,
                );
                self.types.set_kind(
                    id,
                    TypeKind::Record {
                        fields: Vec::new(),
                        value: true,
                    },
                );
            }
        }
    }

    /// Does record `outer` contain `target` somewhere inside its components?
    fn record_contains(&self, outer: TypeId, target: TypeId, depth: usize) -> bool {
        if depth > 64 {
            return true;
        }
        let Some(fields) = self.types.fields(outer) else {
            return false;
        };
        fields
            .iter()
            .any(|f| f.ty.base == target || self.record_contains(f.ty.base, target, depth + 1))
    }

    /// Does a stdlib declaration describe exactly a built-in type?
    fn same_as_builtin(&self, id: TypeId, item: &ModuleItem) -> bool {
        match (item, &self.types.get(id).kind) {
            (ModuleItem::Alias(a), TypeKind::Alias(b)) => self
                .types
                .lookup(&a.base.node)
                .is_some_and(|x| self.types.resolve(x) == self.types.resolve(*b)),
            (ModuleItem::Record(r), TypeKind::Record { fields, .. }) => {
                fields.len() == r.fields.len()
                    && fields.iter().zip(&r.fields).all(|(f, g)| {
                        f.name.eq_ignore_ascii_case(&g.name.node)
                            && self
                                .types
                                .lookup(&g.ty.node)
                                .is_some_and(|t| self.types.resolve(t) == f.ty.base)
                    })
            }
            _ => false,
        }
    }

    fn add_global(&mut self, g: Global) -> GlobalId {
        let id = GlobalId(self.globals.len() as u32);
        let list = self
            .data_syms
            .entry(ast::EcoString::from(g.name.to_ascii_uppercase()))
            .or_default();
        *list = list.iter().copied().chain([id]).collect();
        self.globals.push(g);
        self.global_decls.push(None);
        id
    }

    /// Predefined data that is not written in RAPID.
    pub(super) fn predefined_data(&mut self, env: &Env) {
        let pre = |name: &str, origin: GlobalOrigin, storage, ty| Global {
            name: name.to_string(),
            origin,
            local: false,
            task: false,
            storage,
            ty,
            dims: Vec::new(),
            init: None,
            span: Span::default(),
        };
        for e in errnum::ERRORS {
            self.add_global(pre(
                e.name,
                GlobalOrigin::ErrConst(e.num),
                Storage::Const,
                Ty::NUM,
            ));
        }
        self.add_global(pre(
            "LONG_JMP_ALL_ERR",
            GlobalOrigin::ErrConst(errnum::LONG_JMP_ALL_ERR),
            Storage::Const,
            Ty::NUM,
        ));
        self.add_global(pre(
            "pi",
            GlobalOrigin::NumConst(std::f64::consts::PI),
            Storage::Const,
            Ty::NUM,
        ));
        for (name, v) in super::predef::AIO_CONSTS {
            self.add_global(pre(
                name,
                GlobalOrigin::NumConst(*v),
                Storage::Const,
                Ty::NUM,
            ));
        }
        let mec = self.types.lookup("mecunit").unwrap_or(TypeId::NUM);
        for m in &env.mecunits {
            self.add_global(pre(
                m,
                GlobalOrigin::MecUnit(m.clone()),
                Storage::Var,
                Ty::scalar(mec),
            ));
        }
        for (name, kind) in &env.signals {
            let ty = self.types.lookup(kind.rapid_type()).unwrap_or(TypeId::NUM);
            self.add_global(pre(
                name,
                GlobalOrigin::Signal(name.clone()),
                Storage::Var,
                Ty::scalar(ty),
            ));
        }
    }

    /// Module data declarations.
    pub(super) fn collect_globals(&mut self) {
        // (Sized up front: a module of 250,000 declarations would otherwise copy the lists
        // as they double, and hold up to twice what they need.)
        let data = self
            .module_asts
            .iter()
            .flat_map(|m| &m.items)
            .filter(|item| matches!(item, ModuleItem::Data(_) | ModuleItem::PackedData(_)))
            .count();
        self.globals.reserve(data);
        self.global_decls.reserve(data);
        self.data_syms.reserve(data);
        for mi in 0..self.module_asts.len() {
            let m = self.module_asts[mi];
            let mid = ModuleId(mi as u32);
            self.cur_module = mid;
            for item in &m.items {
                if let Some(d) = self.data_decl(mid, item) {
                    self.collect_global(mid, item, &d);
                }
            }
        }
        self.fill_records();
        // Array sizes may name constants declared anywhere: compute them now. (A packed
        // declaration has none.)
        for gi in 0..self.globals.len() {
            if let Some((m, ModuleItem::Data(d))) = self.global_decls[gi] {
                self.cur_module = m;
                self.globals[gi].dims = self.const_dims(&d.dims);
            }
        }
    }

    /// The module data declaration `d`, the data item `item` of module `mid`.
    fn collect_global(&mut self, mid: ModuleId, item: &'a ModuleItem, d: &ast::DataDecl) {
        let Some(base) = self.resolve_type(&d.ty) else {
            return;
        };
        let ty = Ty {
            base,
            rank: d.dims.len().min(3) as u8,
        };
        if d.dims.len() > 3 {
            self.err(
                K::BadDecl {
                    why: "arrays have at most 3 dimensions".into(),
                },
                d.span,
            );
        }
        if !self.types.is_value(base) {
            if d.storage != Storage::Var {
                self.err(
                    K::NonValue {
                        ty: self.ty_name(ty),
                        what: "declared CONST or PERS",
                    },
                    d.ty.span,
                );
            }
            if d.init.is_some() {
                self.err(
                    K::NonValue {
                        ty: self.ty_name(ty),
                        what: "given an initial value",
                    },
                    d.span,
                );
            }
        }
        if d.storage == Storage::Const && d.init.is_none() {
            self.err(
                K::BadDecl {
                    why: format!("constant `{}` needs a value", d.name.node),
                },
                d.span,
            );
        }
        let stdlib = self.is_stdlib(mid);
        let key = d.name.folded();
        let existing: Vec<GlobalId> = self
            .data_syms
            .get(key.as_str())
            .map(|l| l.to_vec())
            .unwrap_or_default();
        for gid in existing {
            let g = &self.globals[gid.0 as usize];
            let GlobalOrigin::Module(gm) = g.origin else {
                continue; // predefined natives may be shadowed
            };
            let same_module = gm == mid;
            if !same_module && (g.local || d.local) {
                continue;
            }
            let g_stdlib = self.is_stdlib(gm);
            if g_stdlib && !stdlib && !d.local {
                self.err(
                    K::PredefinedRedeclared {
                        name: d.name.node.to_string(),
                    },
                    d.name.span,
                );
                return;
            }
            if !same_module && g.storage == Storage::Pers && d.storage == Storage::Pers {
                if g.ty != ty {
                    let first = self.ty_name(g.ty);
                    self.err(
                        K::PersMismatch {
                            name: d.name.node.to_string(),
                            first,
                            this: self.ty_name(ty),
                        },
                        d.ty.span,
                    );
                } else {
                    self.shared_decls
                        .entry(gid.0)
                        .or_default()
                        .push((mid, item));
                }
                return;
            }
            let first = g.span;
            self.err(
                K::Duplicate {
                    name: d.name.node.to_string(),
                    first,
                },
                d.name.span,
            );
            return;
        }
        let gid = self.add_global(Global {
            name: d.name.node.to_string(),
            origin: GlobalOrigin::Module(mid),
            local: d.local,
            task: d.task,
            storage: d.storage,
            ty,
            dims: Vec::new(),
            init: None,
            span: d.span,
        });
        // (One declaration, in a list of exactly one.)
        self.global_decls[gid.0 as usize] = Some((mid, item));
    }

    /// Routine headers: parameters, slots, return types.
    pub(super) fn collect_routines(&mut self) {
        // (Sized up front: a list grown by doubling holds up to twice what it needs.)
        let count = self
            .module_asts
            .iter()
            .flat_map(|m| &m.items)
            .filter(|item| matches!(item, ModuleItem::Routine(_)))
            .count();
        self.routines.reserve(count);
        self.routine_asts.reserve(count);
        for mi in 0..self.module_asts.len() {
            let m = self.module_asts[mi];
            let mid = ModuleId(mi as u32);
            self.cur_module = mid;
            for item in &m.items {
                if let ModuleItem::Routine(r) = item {
                    self.collect_routine(mid, r);
                }
            }
        }
    }

    fn collect_routine(&mut self, mid: ModuleId, r: &'a ast::Routine) {
        let key = r.name.folded();
        if let Some(list) = self.routine_syms.get(&key) {
            for &other in list {
                let o = &self.routines[other.0 as usize];
                if o.module == mid || (!o.local && !r.local) {
                    let first = o.head_span;
                    self.err(
                        K::Duplicate {
                            name: r.name.node.to_string(),
                            first,
                        },
                        r.name.span,
                    );
                    return;
                }
            }
        }
        let kind = match &r.kind {
            AstKind::Proc => RoutineKind::Proc,
            AstKind::Trap => RoutineKind::Trap,
            AstKind::Func(t) => match self.resolve_type(t) {
                Some(base) => {
                    if !self.types.is_value(base) {
                        self.err(
                            K::NonValue {
                                ty: self.types.name(base).to_string(),
                                what: "returned by a function",
                            },
                            t.span,
                        );
                    }
                    RoutineKind::Func(Ty::scalar(base))
                }
                None => RoutineKind::Func(Ty::NUM),
            },
        };
        let mut params = Vec::new();
        let (mut vslots, mut rslots) = (0u32, 0u32);
        let mut seen: Vec<String> = Vec::new();
        for (gi, group) in r.params.iter().enumerate() {
            for p in &group.alternatives {
                if p.placeholder.is_some() {
                    // The parser already warned; the routine stops the program when called.
                    self.incomplete.insert(self.routines.len());
                    continue;
                }
                let Some(base) = self.resolve_type(&p.ty) else {
                    continue;
                };
                let is_switch = base == TypeId::SWITCH;
                if is_switch && (!p.optional || p.mode != ParamMode::In) {
                    self.err(
                        K::BadDecl {
                            why: "a switch parameter must be optional (`\\switch name`) and have no mode".into(),
                        },
                        p.span,
                    );
                }
                if p.open_dims > 3 {
                    self.err(
                        K::BadDecl {
                            why: "arrays have at most 3 dimensions".into(),
                        },
                        p.span,
                    );
                }
                let pk = p.name.folded();
                if seen.contains(&pk) {
                    self.err(
                        K::Duplicate {
                            name: p.name.node.to_string(),
                            first: p.span,
                        },
                        p.name.span,
                    );
                    continue;
                }
                seen.push(pk);
                let slot = if p.mode == ParamMode::In {
                    vslots += 1;
                    ParamSlot::Value(vslots - 1)
                } else {
                    rslots += 1;
                    ParamSlot::Ref(rslots - 1)
                };
                params.push(ParamInfo {
                    name: p.name.node.to_string(),
                    ty: Ty {
                        base,
                        rank: p.open_dims.min(3),
                    },
                    mode: p.mode,
                    optional: p.optional || group.alternatives.len() > 1,
                    group: gi as u16,
                    slot,
                    span: p.span,
                });
            }
        }
        if !matches!(r.kind, AstKind::Proc | AstKind::Func(_)) && !params.is_empty() {
            self.err(
                K::BadDecl {
                    why: "a TRAP has no parameters".into(),
                },
                r.head_span,
            );
        }
        let rid = RoutineId(self.routines.len() as u32);
        self.routine_syms.entry(key).or_default().push(rid);
        // (Exactly their length: a list grown by pushing holds four at least.)
        params.shrink_to_fit();
        self.routines.push(Routine {
            name: r.name.node.to_string(),
            module: mid,
            local: r.local,
            kind,
            params,
            locals: Vec::new(),
            n_slots: vslots,
            n_refs: rslots,
            body: Block::default(),
            error: None,
            undo: None,
            span: r.span,
            head_span: r.head_span,
            simple: false,
        });
        self.routine_asts.push(r);
    }

    /// Resolve the types of every native signature once (a bad one is an internal error).
    pub(super) fn check_native_signatures(&mut self) {
        for i in 0..self.natives.len() {
            self.native_view(crate::ir::NativeId(i as u32));
        }
    }
}
