//! The type table: atomic types, records (built-in and user), aliases and non-value types.

use std::collections::HashMap;

/// Index of a type in the [`TypeTable`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct TypeId(pub u32);

impl TypeId {
    /// `num` (single precision).
    pub const NUM: TypeId = TypeId(0);
    /// `dnum` (double precision).
    pub const DNUM: TypeId = TypeId(1);
    /// `bool`.
    pub const BOOL: TypeId = TypeId(2);
    /// `string` (at most 80 characters).
    pub const STRING: TypeId = TypeId(3);
    /// The pseudo type of `switch` parameters.
    pub const SWITCH: TypeId = TypeId(4);
}

/// A data type: a base type and an array rank (0 for a scalar, 1–3 for arrays).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Ty {
    /// Element type (never an alias: aliases are resolved when a `Ty` is built).
    pub base: TypeId,
    /// Number of array dimensions.
    pub rank: u8,
}

impl Ty {
    /// A scalar of type `base`.
    pub const fn scalar(base: TypeId) -> Ty {
        Ty { base, rank: 0 }
    }
    /// `num`.
    pub const NUM: Ty = Ty::scalar(TypeId::NUM);
    /// `dnum`.
    pub const DNUM: Ty = Ty::scalar(TypeId::DNUM);
    /// `bool`.
    pub const BOOL: Ty = Ty::scalar(TypeId::BOOL);
    /// `string`.
    pub const STRING: Ty = Ty::scalar(TypeId::STRING);

    /// True for arrays.
    pub fn is_array(self) -> bool {
        self.rank > 0
    }

    /// The element type of an array.
    pub fn elem(self) -> Ty {
        Ty::scalar(self.base)
    }
}

/// One record component.
#[derive(Clone, Debug, PartialEq)]
pub struct Field {
    /// Component name as declared.
    pub name: String,
    /// Component type.
    pub ty: Ty,
    /// Array sizes when the component is an array (empty for scalars).
    pub dims: Vec<u32>,
}

/// What a type is.
#[derive(Clone, Debug, PartialEq)]
pub enum TypeKind {
    /// `num`
    Num,
    /// `dnum`
    Dnum,
    /// `bool`
    Bool,
    /// `string`
    String,
    /// `switch` (parameters only).
    Switch,
    /// A record with named components.
    Record {
        /// Components in order.
        fields: Vec<Field>,
        /// False for non-value and semi-value types (`clock`, `egmident`, signals …):
        /// they cannot be written as aggregates, assigned, compared or declared `CONST`.
        value: bool,
    },
    /// `ALIAS base name`: behaves as its base type.
    Alias(TypeId),
}

/// A named type.
#[derive(Clone, Debug, PartialEq)]
pub struct TypeDef {
    /// Name as declared.
    pub name: String,
    /// What it is.
    pub kind: TypeKind,
    /// Declared by the program (true) or built in / stdlib (false).
    pub user: bool,
}

/// All types known to a program.
#[derive(Clone, Debug)]
pub struct TypeTable {
    defs: Vec<TypeDef>,
    by_name: HashMap<String, TypeId>,
}

impl Default for TypeTable {
    fn default() -> Self {
        Self::new()
    }
}

impl TypeTable {
    /// A table holding only the atomic types and `switch` (ids fixed by the `TypeId` consts).
    pub fn new() -> Self {
        let mut t = TypeTable {
            defs: Vec::new(),
            by_name: HashMap::new(),
        };
        t.add("num", TypeKind::Num, false);
        t.add("dnum", TypeKind::Dnum, false);
        t.add("bool", TypeKind::Bool, false);
        t.add("string", TypeKind::String, false);
        t.add("switch", TypeKind::Switch, false);
        t
    }

    /// Add a type; the caller checks for duplicates with [`TypeTable::lookup`] first.
    pub fn add(&mut self, name: &str, kind: TypeKind, user: bool) -> TypeId {
        let id = TypeId(self.defs.len() as u32);
        self.defs.push(TypeDef {
            name: name.to_string(),
            kind,
            user,
        });
        self.by_name.insert(name.to_ascii_uppercase(), id);
        id
    }

    /// Replace the kind of an existing type (used to fill in records declared later).
    pub fn set_kind(&mut self, id: TypeId, kind: TypeKind) {
        if let Some(d) = self.defs.get_mut(id.0 as usize) {
            d.kind = kind;
        }
    }

    /// Find a type by (case-insensitive) name.
    pub fn lookup(&self, name: &str) -> Option<TypeId> {
        self.by_name.get(&name.to_ascii_uppercase()).copied()
    }

    /// The definition of a type.
    pub fn get(&self, id: TypeId) -> &TypeDef {
        &self.defs[id.0 as usize]
    }

    /// Name of a type as declared.
    pub fn name(&self, id: TypeId) -> &str {
        &self.get(id).name
    }

    /// Follow aliases to the underlying type.
    pub fn resolve(&self, mut id: TypeId) -> TypeId {
        for _ in 0..32 {
            match self.get(id).kind {
                TypeKind::Alias(b) => id = b,
                _ => return id,
            }
        }
        id
    }

    /// Record components, if `id` is a record.
    pub fn fields(&self, id: TypeId) -> Option<&[Field]> {
        match &self.get(self.resolve(id)).kind {
            TypeKind::Record { fields, .. } => Some(fields),
            _ => None,
        }
    }

    /// True for value types (atomic, value records, arrays of them).
    pub fn is_value(&self, id: TypeId) -> bool {
        match &self.get(self.resolve(id)).kind {
            TypeKind::Record { value, .. } => *value,
            TypeKind::Switch => false,
            _ => true,
        }
    }

    /// Human-readable spelling of a data type, e.g. `num{*}`.
    pub fn display(&self, ty: Ty) -> String {
        let mut s = self.name(ty.base).to_string();
        if ty.rank > 0 {
            s.push('{');
            for i in 0..ty.rank {
                if i > 0 {
                    s.push(',');
                }
                s.push('*');
            }
            s.push('}');
        }
        s
    }

    /// How many values data of type `ty` holds ([`crate::ir::limits`]): one for each
    /// `num`, `dnum`, `bool` and `string`, a record's components added up (at least one per
    /// record), times the array sizes `dims` for an array. Saturates instead of overflowing.
    pub fn values(&self, ty: Ty, dims: &[u32]) -> u64 {
        let one = self.values_of(ty.base, 0);
        if ty.rank == 0 {
            return one;
        }
        dims.iter()
            .fold(one, |acc, &n| acc.saturating_mul(u64::from(n)))
    }

    fn values_of(&self, id: TypeId, depth: u32) -> u64 {
        // Records cannot contain themselves (the semantic pass reports and empties such a
        // record), so the depth is the nesting of distinct records; the guard only keeps
        // an unchecked table from recursing without end.
        if depth > 64 {
            return u64::MAX;
        }
        match &self.get(self.resolve(id)).kind {
            TypeKind::Record { fields, .. } => fields
                .iter()
                .map(|f| {
                    let one = self.values_of(f.ty.base, depth + 1);
                    if f.ty.rank == 0 {
                        one
                    } else {
                        f.dims
                            .iter()
                            .fold(one, |acc, &n| acc.saturating_mul(u64::from(n)))
                    }
                })
                .fold(0u64, u64::saturating_add)
                .max(1),
            _ => 1,
        }
    }

    /// Number of types.
    pub fn len(&self) -> usize {
        self.defs.len()
    }

    /// Always false: the atomic types are always present.
    pub fn is_empty(&self) -> bool {
        self.defs.is_empty()
    }

    /// Iterate over (id, definition).
    pub fn iter(&self) -> impl Iterator<Item = (TypeId, &TypeDef)> {
        self.defs
            .iter()
            .enumerate()
            .map(|(i, d)| (TypeId(i as u32), d))
    }
}
