//! Run-time values: `num` as `f32` (single precision, as on a controller), `dnum` as `f64`,
//! `bool`, `string` (shared, immutable text), records and arrays.
//!
//! Scalars are stored inline, so `num`/`bool` arithmetic never allocates. Records and arrays
//! are owned (deep copies on assignment, as RAPID's value semantics require). A string is
//! shared and copied on write ([`RStr`]): copying a string value shares its text, and a
//! variable that alone holds its text is written in place (`s := s + c` appends).

use std::sync::Arc;

use crate::ir::{Ty, TypeId, TypeKind, TypeTable};

/// Longest string RAPID holds.
pub const MAX_STRING: usize = 80;

/// A RAPID value.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// `num` (and every alias of it).
    Num(f32),
    /// `dnum`.
    Dnum(f64),
    /// `bool`.
    Bool(bool),
    /// `string`.
    Str(RStr),
    /// A record: components in declaration order.
    Record(Box<[Value]>),
    /// An array.
    Array(Box<Array>),
    /// An optional parameter that was not passed (or a value not yet set).
    Absent,
}

/// The text of a `string` value: shared between the values that hold the same text, and
/// written in place by the one value that holds it alone (its buffer is kept, so a variable
/// that is built up or overwritten again and again allocates once).
#[derive(Clone, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct RStr(Arc<String>);

impl RStr {
    /// The text to write, when this value alone holds it.
    #[inline]
    pub fn unique_mut(&mut self) -> Option<&mut String> {
        Arc::get_mut(&mut self.0)
    }

    /// Make the text `s` (in place when this value alone holds its text).
    #[inline]
    pub fn set(&mut self, s: &str) {
        match self.unique_mut() {
            Some(t) => {
                t.clear();
                t.push_str(s);
            }
            None => *self = RStr::from(s),
        }
    }

    /// Make the text the one ASCII character `b`: in place when this value alone holds
    /// its text, else in a text of its own (which the next write reuses).
    #[inline]
    pub fn set_ascii(&mut self, b: u8) {
        match self.unique_mut() {
            Some(t) => {
                t.clear();
                t.push(char::from(b));
            }
            None => *self = RStr::from(String::from(char::from(b))),
        }
    }

    /// The text.
    #[inline(always)]
    pub fn as_str(&self) -> &str {
        self.0.as_str()
    }
}

impl std::ops::Deref for RStr {
    type Target = str;
    #[inline(always)]
    fn deref(&self) -> &str {
        self.0.as_str()
    }
}

impl AsRef<str> for RStr {
    fn as_ref(&self) -> &str {
        self
    }
}

impl std::borrow::Borrow<str> for RStr {
    fn borrow(&self) -> &str {
        self
    }
}

impl std::fmt::Debug for RStr {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        std::fmt::Debug::fmt(self.as_str(), f)
    }
}

impl std::fmt::Display for RStr {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self)
    }
}

impl From<&str> for RStr {
    fn from(s: &str) -> RStr {
        RStr(Arc::new(s.to_owned()))
    }
}

impl From<String> for RStr {
    fn from(s: String) -> RStr {
        RStr(Arc::new(s))
    }
}

impl From<&String> for RStr {
    fn from(s: &String) -> RStr {
        RStr::from(s.as_str())
    }
}

impl From<Arc<str>> for RStr {
    fn from(s: Arc<str>) -> RStr {
        RStr::from(&*s)
    }
}

impl From<&Arc<str>> for RStr {
    fn from(s: &Arc<str>) -> RStr {
        RStr::from(&**s)
    }
}

impl PartialEq<str> for RStr {
    fn eq(&self, o: &str) -> bool {
        self.as_str() == o
    }
}

impl PartialEq<&str> for RStr {
    fn eq(&self, o: &&str) -> bool {
        self.as_str() == *o
    }
}

/// The shared text of one ASCII character `b` (`b` < 128).
fn ascii_char(b: u8) -> RStr {
    static CHARS: std::sync::LazyLock<Box<[RStr]>> = std::sync::LazyLock::new(|| {
        (0u8..128)
            .map(|b| RStr::from(char::from(b).to_string()))
            .collect()
    });
    match CHARS.get(b as usize) {
        Some(s) => s.clone(),
        None => RStr::from(char::from(b).to_string()),
    }
}

/// An array of 1–3 dimensions, stored row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct Array {
    /// Sizes; unused trailing dimensions are 1.
    pub dims: [u32; 3],
    /// Number of dimensions (1–3).
    pub rank: u8,
    /// Elements.
    pub data: Vec<Value>,
}

impl Array {
    /// Row-major offset of 1-based indices, or `None` when one is out of bounds.
    pub fn offset(&self, idx: &[i64]) -> Option<usize> {
        if idx.len() != self.rank as usize {
            return None;
        }
        let mut off: usize = 0;
        for (k, &i) in idx.iter().enumerate() {
            let n = self.dims[k] as i64;
            if i < 1 || i > n {
                return None;
            }
            off = off * n as usize + (i - 1) as usize;
        }
        Some(off)
    }

    /// Sizes actually used.
    pub fn sizes(&self) -> &[u32] {
        &self.dims[..self.rank as usize]
    }
}

impl Value {
    /// A string value (the caller has checked the length). Texts of one ASCII character
    /// share one allocation each (programs that walk a string character by character make
    /// many of them).
    pub fn str(s: &str) -> Value {
        match s.as_bytes() {
            [b] if b.is_ascii() => Value::Str(ascii_char(*b)),
            _ => Value::Str(RStr::from(s)),
        }
    }

    /// The number, for num values.
    pub fn as_num(&self) -> Option<f32> {
        match self {
            Value::Num(x) => Some(*x),
            _ => None,
        }
    }

    /// The number as f64, for num and dnum values.
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::Num(x) => Some(*x as f64),
            Value::Dnum(x) => Some(*x),
            _ => None,
        }
    }

    /// The bool, for bool values.
    pub fn as_bool(&self) -> Option<bool> {
        match self {
            Value::Bool(b) => Some(*b),
            _ => None,
        }
    }

    /// The text, for strings.
    pub fn as_str(&self) -> Option<&str> {
        match self {
            Value::Str(s) => Some(s),
            _ => None,
        }
    }

    /// Components, for records.
    pub fn fields(&self) -> Option<&[Value]> {
        match self {
            Value::Record(f) => Some(f),
            _ => None,
        }
    }

    /// True unless this is [`Value::Absent`].
    pub fn is_present(&self) -> bool {
        !matches!(self, Value::Absent)
    }

    /// Components of a record of numbers as f64 (pos, orient, …).
    pub fn num_fields<const N: usize>(&self) -> Option<[f64; N]> {
        let f = self.fields()?;
        if f.len() != N {
            return None;
        }
        let mut out = [0.0; N];
        for (o, v) in out.iter_mut().zip(f) {
            *o = v.as_f64()?;
        }
        Some(out)
    }

    /// Make this value equal to `v`, reusing its allocations where the shapes agree (a
    /// record of as many components, an array of the same sizes).
    pub fn reset_from(&mut self, v: &Value) {
        match (self, v) {
            (Value::Record(a), Value::Record(b)) if a.len() == b.len() => {
                for (x, y) in a.iter_mut().zip(b.iter()) {
                    match (x, y) {
                        (Value::Num(x), Value::Num(y)) => *x = *y,
                        (x, y) => x.reset_from(y),
                    }
                }
            }
            (Value::Array(a), Value::Array(b))
                if a.dims == b.dims && a.rank == b.rank && a.data.len() == b.data.len() =>
            {
                for (x, y) in a.data.iter_mut().zip(b.data.iter()) {
                    x.reset_from(y);
                }
            }
            (Value::Num(x), Value::Num(y)) => *x = *y,
            (me, v) => *me = v.clone(),
        }
    }

    /// A record of `num` components from f64 values (rounded to single precision).
    pub fn num_record(vals: &[f64]) -> Value {
        Value::Record(vals.iter().map(|&x| Value::Num(x as f32)).collect())
    }

    /// [`Value::reset_from`] that also reuses records where the shapes differ: a record
    /// of another length (or a value that is no record) is exchanged for one of the right
    /// length from `pool` ([`Spares`]), and the replaced record goes back into it. A value
    /// copied into a slot another routine left there, or into a slot a RETURN emptied,
    /// allocates nothing once the pool holds records of its shape.
    #[inline(always)]
    pub(crate) fn reset_pooled(&mut self, v: &Value, pool: &mut Spares) {
        // The usual case first: a record of numbers over one of as many components.
        if let (Value::Record(a), Value::Record(b)) = (&mut *self, v)
            && copy_nums(a, b)
        {
            return;
        }
        self.reset_pooled_any(v, pool)
    }

    /// [`Value::reset_pooled`] of any value.
    fn reset_pooled_any(&mut self, v: &Value, pool: &mut Spares) {
        match (&mut *self, v) {
            (Value::Num(x), Value::Num(y)) => *x = *y,
            (_, Value::Record(b)) => {
                let a = match self {
                    Value::Record(a) if a.len() == b.len() => a,
                    _ => {
                        let old = std::mem::replace(self, Value::Record(pool.take(b.len())));
                        pool.give_value(old);
                        match self {
                            Value::Record(a) => a,
                            _ => return,
                        }
                    }
                };
                for (x, y) in a.iter_mut().zip(b.iter()) {
                    match (x, y) {
                        (Value::Num(x), Value::Num(y)) => *x = *y,
                        (x, y) => x.reset_pooled(y, pool),
                    }
                }
            }
            (Value::Array(a), Value::Array(b))
                if a.dims == b.dims && a.rank == b.rank && a.data.len() == b.data.len() =>
            {
                for (x, y) in a.data.iter_mut().zip(b.data.iter()) {
                    x.reset_pooled(y, pool);
                }
            }
            (me, v) => {
                let old = std::mem::replace(me, v.clone());
                pool.give_value(old);
            }
        }
    }
}

/// Copy the components of `b` into `a` when both are records of as many `num`s (`false`,
/// with `a` partly written, for any other shape: the caller then writes every component).
#[inline]
fn copy_nums(a: &mut [Value], b: &[Value]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    for (x, y) in a.iter_mut().zip(b) {
        match (x, y) {
            (Value::Num(x), Value::Num(y)) => *x = *y,
            _ => return false,
        }
    }
    true
}

/// Records kept for reuse: replaced records go in, and a record of a wanted length comes
/// out without allocating while one of that length is there. Their components are left as
/// they were: whoever takes one overwrites every component.
#[derive(Default, Debug)]
pub(crate) struct Spares(Vec<Box<[Value]>>);

impl Spares {
    /// Most records kept.
    const MAX: usize = 16;

    /// A record of `n` components (a kept one, else a new one of zeros).
    #[inline]
    pub(crate) fn take(&mut self, n: usize) -> Box<[Value]> {
        match self.0.iter().rposition(|r| r.len() == n) {
            Some(k) => self.0.swap_remove(k),
            None => vec![Value::Num(0.0); n].into_boxed_slice(),
        }
    }

    /// Keep a record (dropped when the pool is full).
    #[inline]
    pub(crate) fn give(&mut self, r: Box<[Value]>) {
        if self.0.len() < Self::MAX {
            self.0.push(r);
        }
    }

    /// Keep `v` if it is a record (anything else is dropped). A scalar, the usual case, is
    /// let go without running any drop code.
    #[inline(always)]
    pub(crate) fn give_value(&mut self, v: Value) {
        match v {
            v @ (Value::Num(_) | Value::Dnum(_) | Value::Bool(_) | Value::Absent) => {
                std::mem::forget(v)
            }
            v => self.give_value_slow(v),
        }
    }

    #[inline(never)]
    fn give_value_slow(&mut self, v: Value) {
        if let Value::Record(r) = v {
            self.give(r);
        }
    }
}

/// The integer a `num` holds, if it holds one that fits `i32` (the hot path of array indices
/// and `DIV`/`MOD`): a truncating conversion and back. NaN converts to 0 and values outside
/// `i32` saturate to its ends, which are excluded (±2³¹ are not in range, and the slow path
/// takes them).
#[inline(always)]
pub fn f32_int(x: f32) -> Option<i32> {
    let i = x as i32;
    if i as f32 == x && i != i32::MIN && i != i32::MAX {
        Some(i)
    } else {
        None
    }
}

/// Structural equality as RAPID's `=`: numbers by value (num and dnum compare as numbers),
/// records and arrays component-wise.
pub fn values_equal(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Num(x), Value::Num(y)) => x == y,
        (Value::Dnum(x), Value::Dnum(y)) => x == y,
        (Value::Num(x), Value::Dnum(y)) | (Value::Dnum(y), Value::Num(x)) => (*x as f64) == *y,
        (Value::Bool(x), Value::Bool(y)) => x == y,
        (Value::Str(x), Value::Str(y)) => x == y,
        (Value::Record(x), Value::Record(y)) => {
            x.len() == y.len() && x.iter().zip(y.iter()).all(|(p, q)| values_equal(p, q))
        }
        (Value::Array(x), Value::Array(y)) => {
            x.dims == y.dims
                && x.data.len() == y.data.len()
                && x.data.iter().zip(&y.data).all(|(p, q)| values_equal(p, q))
        }
        (Value::Absent, Value::Absent) => true,
        _ => false,
    }
}

/// The value a declaration without initialiser gets: `0`, `FALSE`, `""`, records of
/// defaults, arrays of defaults.
pub fn default_value(types: &TypeTable, ty: Ty, dims: &[u32]) -> Value {
    if ty.rank > 0 && !dims.is_empty() {
        let mut d = [1u32; 3];
        for (k, &n) in dims.iter().take(3).enumerate() {
            d[k] = n;
        }
        let count: usize = dims.iter().map(|&n| n as usize).product();
        let elem = default_value(types, ty.elem(), &[]);
        return Value::Array(Box::new(Array {
            dims: d,
            rank: dims.len().min(3) as u8,
            data: vec![elem; count],
        }));
    }
    default_scalar(types, ty.base)
}

fn default_scalar(types: &TypeTable, id: TypeId) -> Value {
    let id = types.resolve(id);
    match &types.get(id).kind {
        TypeKind::Num => Value::Num(0.0),
        TypeKind::Dnum => Value::Dnum(0.0),
        TypeKind::Bool => Value::Bool(false),
        TypeKind::String => Value::Str(RStr::default()),
        TypeKind::Switch => Value::Absent,
        TypeKind::Record { fields, .. } => Value::Record(
            fields
                .iter()
                .map(|f| default_value(types, f.ty, &f.dims))
                .collect(),
        ),
        TypeKind::Alias(b) => default_scalar(types, *b),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integer_nums_are_recognised() {
        for x in [
            0.0f32,
            -0.0,
            1.0,
            -1.0,
            2.0,
            100.0,
            8_388_608.0,
            16_777_216.0,
            -1.0e9,
            2_147_483_520.0,
            -2_147_483_520.0,
        ] {
            assert_eq!(f32_int(x), Some(x as i32), "{x}");
        }
        // i32::MIN and beyond are left to the slow path.
        for x in [
            0.5f32,
            -0.25,
            1.5,
            1e-30,
            8_388_607.5,
            3.0e9,
            -2_147_483_648.0,
            2_147_483_648.0,
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ] {
            assert_eq!(f32_int(x), None, "{x}");
        }
    }

    #[test]
    fn value_is_small() {
        assert!(std::mem::size_of::<Value>() <= 24);
    }

    #[test]
    fn array_offsets_are_row_major_and_checked() {
        let a = Array {
            dims: [2, 3, 1],
            rank: 2,
            data: vec![Value::Num(0.0); 6],
        };
        assert_eq!(a.offset(&[1, 1]), Some(0));
        assert_eq!(a.offset(&[2, 3]), Some(5));
        assert_eq!(a.offset(&[3, 1]), None);
        assert_eq!(a.offset(&[0, 1]), None);
        assert_eq!(a.offset(&[1]), None);
    }

    #[test]
    fn reset_from_makes_equal_values() {
        let template = Value::Record(Box::new([
            Value::Num(0.0),
            Value::str(""),
            Value::Record(Box::new([Value::Bool(false)])),
        ]));
        let mut same = Value::Record(Box::new([
            Value::Num(3.0),
            Value::str("x"),
            Value::Record(Box::new([Value::Bool(true)])),
        ]));
        same.reset_from(&template);
        assert_eq!(same, template);
        let mut other = Value::Num(1.0);
        other.reset_from(&template);
        assert_eq!(other, template);
        let mut shorter = Value::Record(Box::new([Value::Num(1.0)]));
        shorter.reset_from(&template);
        assert_eq!(shorter, template);
    }

    #[test]
    fn a_shared_text_is_copied_before_it_is_written() {
        let mut a = RStr::from("ab");
        a.set("abc");
        assert_eq!(a, "abc");
        let b = a.clone();
        a.set("x");
        assert_eq!(b, "abc", "the copy keeps its text");
        assert_eq!(a, "x");
        assert!(a.unique_mut().is_some(), "a new text is held alone");
        let mut c = b.clone();
        assert!(
            c.unique_mut().is_none(),
            "a shared text is not written in place"
        );
    }

    #[test]
    fn equality_is_structural() {
        let p = Value::num_record(&[1.0, 2.0, 3.0]);
        assert!(values_equal(&p, &Value::num_record(&[1.0, 2.0, 3.0])));
        assert!(!values_equal(&p, &Value::num_record(&[1.0, 2.0, 4.0])));
        assert!(values_equal(&Value::Num(9e9), &Value::Num(9e9_f64 as f32)));
    }
}
