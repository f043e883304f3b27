//! Name resolution: data names (routine, module, global, stdlib, predefined) and routine
//! names as RAPID's scopes see them, places (names with components and indices) with their
//! storage class, and "did you mean" suggestions for undeclared names.

use super::error::SemaErrorKind as K;
use super::{Checker, LocalSym};
use crate::ast::{self, ExprKind as AK, ParamMode, Storage};
use crate::ir::{
    Expr, ExprKind, GlobalId, GlobalOrigin, ParamSlot, PathOp, Place, Root, RoutineId, Ty, TypeId,
};

/// What kind of data object a place is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Obj {
    /// VAR data (module or routine).
    Var,
    /// PERS data.
    Pers,
    /// CONST data.
    Const,
    /// An IN parameter.
    InParam,
    /// An INOUT/VAR/PERS parameter.
    RefParam(ParamMode),
    /// Predefined data of a READONLY system module (`tool0`, `wobj0`, `load0`): passed to
    /// PERS parameters of built-ins, never assigned.
    ReadOnlyPers,
    /// A FOR loop variable.
    ForVar,
}

/// A lowered place with what the checks need to know about it.
#[derive(Clone, Debug)]
pub(super) struct PlaceInfo {
    pub place: Place,
    pub ty: Ty,
    /// Array sizes when known before running.
    pub dims: Option<Vec<u32>>,
    pub kind: Obj,
    /// The entire object (no component or element).
    pub whole: bool,
    /// The data name (for messages).
    pub name: String,
}

/// Result of lowering something as a place.
pub(super) enum PlaceRes {
    Ok(PlaceInfo),
    /// Not a place (a literal, a call, …); nothing reported.
    NotPlace,
    /// An error was reported.
    Err,
}

pub(super) enum NameRes {
    Place(PlaceInfo),
    Errno,
    Intno,
    Switch(String),
    Unknown,
}

impl Checker<'_> {
    /// The visible global of this name: LOCAL of the current module, then global user data,
    /// then stdlib data, then predefined data.
    pub(super) fn lookup_global(&self, key: &str) -> Option<GlobalId> {
        let list = self.data_syms.get(key)?;
        let m = self.cur_module;
        list.iter()
            .filter_map(|&id| {
                let g = &self.globals[id.0 as usize];
                let rank = match g.origin {
                    GlobalOrigin::Module(gm) => {
                        if g.local {
                            if gm == m { 0 } else { return None }
                        } else if self.is_stdlib(gm) {
                            2
                        } else {
                            1
                        }
                    }
                    _ => 3,
                };
                Some((rank, id))
            })
            .min_by_key(|(r, _)| *r)
            .map(|(_, id)| id)
    }

    /// The visible user routine of this name (LOCAL of this module first).
    pub(super) fn lookup_routine(&self, key: &str) -> Option<RoutineId> {
        let list = self.routine_syms.get(key)?;
        let m = self.cur_module;
        list.iter()
            .copied()
            .filter(|&r| {
                let rr = &self.routines[r.0 as usize];
                !rr.local || rr.module == m
            })
            .min_by_key(|&r| !self.routines[r.0 as usize].local)
    }

    pub(super) fn resolve_name(&mut self, id: &ast::Ident) -> NameRes {
        let key = id.folded();
        if let Some(rcx) = &self.rcx {
            if let Some((_, slot)) = rcx.for_vars.iter().rev().find(|(n, _)| *n == key) {
                return NameRes::Place(PlaceInfo {
                    place: Place {
                        root: Root::Local(*slot),
                        path: Box::new([]),
                        span: id.span,
                    },
                    ty: Ty::NUM,
                    dims: None,
                    kind: Obj::ForVar,
                    whole: true,
                    name: id.node.to_string(),
                });
            }
            match rcx.scope.get(&key) {
                Some(LocalSym::Param(i)) => {
                    let p = &self.routines[rcx.rid.0 as usize].params[*i];
                    if p.ty.base == TypeId::SWITCH {
                        return NameRes::Switch(p.name.clone());
                    }
                    let (root, kind) = match p.slot {
                        ParamSlot::Value(s) => (Root::Local(s), Obj::InParam),
                        ParamSlot::Ref(k) => (Root::Ref(k), Obj::RefParam(p.mode)),
                    };
                    return NameRes::Place(PlaceInfo {
                        place: Place {
                            root,
                            path: Box::new([]),
                            span: id.span,
                        },
                        ty: p.ty,
                        dims: None,
                        kind,
                        whole: true,
                        name: p.name.clone(),
                    });
                }
                Some(LocalSym::Data {
                    slot,
                    ty,
                    dims,
                    constant,
                    ..
                }) => {
                    return NameRes::Place(PlaceInfo {
                        place: Place {
                            root: Root::Local(*slot),
                            path: Box::new([]),
                            span: id.span,
                        },
                        ty: *ty,
                        dims: (!dims.is_empty()).then(|| dims.clone()),
                        kind: if *constant { Obj::Const } else { Obj::Var },
                        whole: true,
                        name: id.node.to_string(),
                    });
                }
                None => {}
            }
        }
        if key == "ERRNO" {
            return NameRes::Errno;
        }
        if key == "INTNO" {
            return NameRes::Intno;
        }
        let Some(gid) = self.lookup_global(&key) else {
            return NameRes::Unknown;
        };
        let g = &self.globals[gid.0 as usize];
        // (Only a global initialiser's dependencies are wanted: outside one, the list would
        // only grow with every name of every routine.)
        if self.rcx.is_none() && matches!(g.origin, GlobalOrigin::Module(_)) {
            self.deps.push(gid);
        }
        let readonly = matches!(g.origin, GlobalOrigin::Module(m) if self.is_stdlib(m));
        let kind = match g.storage {
            Storage::Pers if readonly => Obj::ReadOnlyPers,
            Storage::Var => Obj::Var,
            Storage::Pers => Obj::Pers,
            Storage::Const => Obj::Const,
        };
        NameRes::Place(PlaceInfo {
            place: Place {
                root: Root::Global(gid.0),
                path: Box::new([]),
                span: id.span,
            },
            ty: g.ty,
            dims: (!g.dims.is_empty()).then(|| g.dims.clone()),
            kind,
            whole: true,
            name: g.name.clone(),
        })
    }

    /// Report `id` as undeclared, with the closest visible name as a suggestion
    /// (`suggest.rs`).
    pub(super) fn undeclared(&mut self, id: &ast::Ident) {
        let key = id.folded();
        let params: Vec<&str> = match &self.rcx {
            Some(rcx) => self.routines[rcx.rid.0 as usize]
                .params
                .iter()
                .map(|p| p.name.as_str())
                .collect(),
            None => Vec::new(),
        };
        let suggestion = self
            .suggester
            .suggest(&key, self.cur_module, &params, &self.globals);
        self.err(
            K::Undeclared {
                name: id.node.to_string(),
                suggestion,
            },
            id.span,
        );
    }

    /// Lower an expression as a place (for assignment and reference arguments).
    pub(super) fn place(&mut self, e: &ast::Expr) -> PlaceRes {
        match &e.kind {
            AK::Name(id) => match self.resolve_name(id) {
                NameRes::Place(p) => PlaceRes::Ok(p),
                NameRes::Errno | NameRes::Intno => PlaceRes::NotPlace,
                NameRes::Switch(n) => {
                    self.err(K::SwitchAsValue { name: n }, e.span);
                    PlaceRes::Err
                }
                NameRes::Unknown => {
                    self.undeclared(id);
                    PlaceRes::Err
                }
            },
            AK::Component { base, field } => {
                let mut info = match self.place(base) {
                    PlaceRes::Ok(i) => i,
                    other => return other,
                };
                let Some((idx, fty, fdims)) = self.field_of(info.ty, field) else {
                    return PlaceRes::Err;
                };
                let mut path = info.place.path.into_vec();
                path.push(PathOp::Field(idx));
                info.place.path = path.into_boxed_slice();
                info.place.span = e.span;
                info.ty = fty;
                info.dims = (!fdims.is_empty()).then_some(fdims);
                info.whole = false;
                PlaceRes::Ok(info)
            }
            AK::Index { base, indices } => {
                let mut info = match self.place(base) {
                    PlaceRes::Ok(i) => i,
                    other => return other,
                };
                if info.ty.rank as usize != indices.len() {
                    self.err(
                        K::NotArray {
                            ty: self.ty_name(info.ty),
                            given: indices.len(),
                        },
                        e.span,
                    );
                    return PlaceRes::Err;
                }
                let mut idx = Vec::with_capacity(indices.len());
                for i in indices {
                    match self.rvalue_as(i, Ty::NUM, "an array index") {
                        Some(x) => idx.push(x),
                        None => return PlaceRes::Err,
                    }
                }
                let mut path = info.place.path.into_vec();
                path.push(PathOp::Index(idx.into_boxed_slice()));
                info.place.path = path.into_boxed_slice();
                info.place.span = e.span;
                info.ty = info.ty.elem();
                info.dims = None;
                info.whole = false;
                PlaceRes::Ok(info)
            }
            _ => PlaceRes::NotPlace,
        }
    }

    /// Component `field` of a record type: (index, type, sizes).
    pub(super) fn field_of(&mut self, ty: Ty, field: &ast::Ident) -> Option<(u16, Ty, Vec<u32>)> {
        let found = if ty.rank == 0 {
            self.types.fields(ty.base).and_then(|fs| {
                fs.iter()
                    .position(|f| f.name.eq_ignore_ascii_case(&field.node))
                    .map(|i| (i as u16, fs[i].ty, fs[i].dims.clone()))
            })
        } else {
            None
        };
        if found.is_none() {
            self.err(
                K::UnknownComponent {
                    ty: self.ty_name(ty),
                    field: field.node.to_string(),
                },
                field.span,
            );
        }
        found
    }

    /// The value of a place as an expression.
    pub(super) fn load_place(&mut self, info: PlaceInfo) -> (Expr, Ty) {
        let span = info.place.span;
        let kind = if info.place.path.is_empty() {
            match info.place.root {
                Root::Local(s) => ExprKind::Local(s),
                Root::Global(g) => ExprKind::Global(g),
                Root::Ref(_) => ExprKind::Load(Box::new(info.place)),
            }
        } else {
            ExprKind::Load(Box::new(info.place))
        };
        (Expr { kind, span }, info.ty)
    }

    /// Does a data name resolve (without recording a dependency)?
    pub(super) fn name_exists(&self, id: &ast::Ident) -> bool {
        let key = id.folded();
        if let Some(rcx) = &self.rcx
            && (rcx.scope.contains_key(&key) || rcx.for_vars.iter().any(|(n, _)| *n == key))
        {
            return true;
        }
        key == "ERRNO" || key == "INTNO" || self.lookup_global(&key).is_some()
    }

    /// The slot of an optional parameter of the current routine named `id`.
    pub(super) fn optional_param_slot(&mut self, id: &ast::Ident) -> Option<ParamSlot> {
        let key = id.folded();
        let found = self.rcx.as_ref().and_then(|rcx| match rcx.scope.get(&key) {
            Some(LocalSym::Param(i)) => {
                let p = &self.routines[rcx.rid.0 as usize].params[*i];
                p.optional.then_some(p.slot)
            }
            _ => None,
        });
        if found.is_none() {
            self.err(
                K::NotOptional {
                    name: id.node.to_string(),
                },
                id.span,
            );
        }
        found
    }
}
