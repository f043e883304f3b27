//! The native registry: each domain file registers signatures (in the notation of
//! [`crate::ir::sig`]) together with their implementations. The semantic pass checks calls
//! against [`Registry::signatures`]; the interpreter calls [`Registry`] implementations.

mod bits;
mod clock;
mod core;
mod data_by_name;
pub(crate) mod data_search;
mod dialogs;
mod egm;
mod egm_path;
mod file_rawbytes;
mod files;
mod interrupts;
mod io;
mod io_events;
mod math;
mod modules;
mod motion;
mod motion_events;
mod motion_settings;
mod path_recovery;
mod pose;
mod rawbytes;
mod sockets;
mod string;
mod system;
mod tasks;
mod text;

pub(crate) use math::whole;
pub(crate) use text::int_to_str;

use std::collections::HashMap;
use std::sync::Arc;

use super::errnum;
use super::error::{ErrorKind, Exec, Unwind};
use super::host::Host;
use super::value::{MAX_STRING, Value};
use super::{Interp, NArg};
use crate::ir::{NativeId, NativeSig, Program};
use crate::source::Span;
use crate::time::RobotTime;

/// A native routine: reads its arguments from the context, returns the function result
/// (`Value::Absent` for instructions).
pub type NativeFn = fn(&mut Ctx<'_>) -> Exec<Value>;

/// Natives by name.
#[derive(Clone)]
pub struct Registry {
    sigs: Vec<NativeSig>,
    impls: Vec<NativeFn>,
    by_name: HashMap<String, usize>,
    /// Per native: added or replaced after [`Registry::standard`] (compiled code runs the
    /// specialised form of a few natives only while they are the standard ones).
    custom: Vec<bool>,
}

impl std::fmt::Debug for Registry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Registry")
            .field("natives", &self.sigs.len())
            .finish()
    }
}

impl Default for Registry {
    fn default() -> Self {
        Self::standard()
    }
}

impl Registry {
    /// An empty registry.
    pub fn empty() -> Self {
        Registry {
            sigs: Vec::new(),
            impls: Vec::new(),
            by_name: HashMap::new(),
            custom: Vec::new(),
        }
    }

    /// Every built-in rapidvc knows (the one place where the domains are combined).
    pub fn standard() -> Self {
        let mut r = Registry::empty();
        core::register(&mut r);
        text::register(&mut r);
        math::register(&mut r);
        string::register(&mut r);
        pose::register(&mut r);
        bits::register(&mut r);

        clock::register(&mut r);
        io::register(&mut r);
        dialogs::register(&mut r);
        interrupts::register(&mut r);
        system::register(&mut r);
        data_by_name::register(&mut r);
        io_events::register(&mut r);
        motion::register(&mut r);
        motion_settings::register(&mut r);
        path_recovery::register(&mut r);
        path_recovery::register_corr(&mut r);
        motion_events::register(&mut r);
        egm::register(&mut r);
        egm_path::register(&mut r);
        files::register(&mut r);
        modules::register(&mut r);
        rawbytes::register(&mut r);
        file_rawbytes::register(&mut r);
        data_search::register(&mut r);
        sockets::register(&mut r);
        tasks::register(&mut r);
        r.custom.iter_mut().for_each(|c| *c = false);
        r
    }

    /// Add a native. The signature text is part of rapidvc's source; a malformed one is a
    /// bug caught by the registry's unit test.
    pub fn add(&mut self, sig: &str, f: NativeFn) {
        let sig = match NativeSig::parse(sig) {
            Ok(s) => s,
            Err(e) => panic!("malformed native signature: {e}"),
        };
        let key = sig.name.to_ascii_uppercase();
        match self.by_name.get(&key) {
            Some(&i) => {
                self.sigs[i] = sig;
                self.impls[i] = f;
                self.custom[i] = true;
            }
            None => {
                self.by_name.insert(key, self.sigs.len());
                self.sigs.push(sig);
                self.impls.push(f);
                self.custom.push(true);
            }
        }
    }

    /// Replace the implementation of an existing native (the controller plugs motion in
    /// this way); false when there is no native of that name.
    pub fn replace(&mut self, name: &str, f: NativeFn) -> bool {
        match self.by_name.get(&name.to_ascii_uppercase()) {
            Some(&i) => {
                self.impls[i] = f;
                self.custom[i] = true;
                true
            }
            None => false,
        }
    }

    /// The signatures, for the semantic pass.
    pub fn signatures(&self) -> Arc<[NativeSig]> {
        self.sigs.clone().into()
    }

    /// The signature of a native by name.
    pub fn get(&self, name: &str) -> Option<&NativeSig> {
        self.by_name
            .get(&name.to_ascii_uppercase())
            .map(|&i| &self.sigs[i])
    }

    /// For each native a program was checked against: is it the standard implementation?
    pub(crate) fn standard_for(&self, sigs: &[NativeSig]) -> Vec<bool> {
        sigs.iter()
            .map(|s| {
                self.by_name
                    .get(&s.name.to_ascii_uppercase())
                    .is_some_and(|&i| !self.custom[i])
            })
            .collect()
    }

    /// Implementations for the natives a program was checked against (by name; a native the
    /// registry lacks fails with a clear error when called).
    pub(crate) fn impls_for(&self, sigs: &[NativeSig]) -> Arc<[NativeFn]> {
        sigs.iter()
            .map(|s| {
                self.by_name
                    .get(&s.name.to_ascii_uppercase())
                    .map(|&i| self.impls[i])
                    .unwrap_or(missing as NativeFn)
            })
            .collect()
    }
}

/// Overwrite a value with a parsed literal of the same shape (StrToVal, persistents).
pub(crate) fn fill_literal(target: &mut Value, lit: &crate::functions::format::LitValue) -> bool {
    text::fill(target, lit)
}

fn missing(cx: &mut Ctx<'_>) -> Exec<Value> {
    Err(cx.unsupported(""))
}

/// What a native sees: its arguments, the interpreter and the host.
pub struct Ctx<'a> {
    pub(crate) it: &'a mut Interp,
    pub(crate) p: &'a Program,
    pub(crate) base: usize,
    /// The call.
    pub span: Span,
    pub(crate) nid: NativeId,
    pub(crate) args: &'a [crate::ir::Arg],
}

impl<'a> Ctx<'a> {
    /// The expression written for IN argument `i` (for natives that re-evaluate it, such as
    /// `WaitUntil`).
    pub fn arg_expr(&self, i: usize) -> Option<&'a crate::ir::Expr> {
        match self.args.get(i) {
            Some(crate::ir::Arg::Value(e)) => Some(e),
            _ => None,
        }
    }

    /// Name of the native being called.
    pub fn name(&self) -> &str {
        self.p
            .natives
            .get(self.nid.0 as usize)
            .map(|s| s.name.as_str())
            .unwrap_or("?")
    }

    fn arg(&self, i: usize) -> Option<&NArg> {
        self.it.nargs.get(self.base + i)
    }

    /// Was optional argument `i` (or switch `i`) passed?
    pub fn present(&self, i: usize) -> bool {
        match self.arg(i) {
            Some(NArg::Absent) | None => false,
            Some(NArg::Ref(r)) => r.root != super::place::AbsRoot::Absent,
            Some(NArg::Val(v)) => v.is_present(),
            Some(NArg::Switch) => true,
        }
    }

    /// The value of argument `i`.
    pub fn value(&self, i: usize) -> Exec<&Value> {
        let r = match self.arg(i) {
            Some(NArg::Val(v)) if v.is_present() => Ok(v),
            Some(NArg::Ref(r)) => self.it.abs_get(r),
            _ => Err(super::place::WalkErr::NotPresent),
        };
        r.map_err(|e| self.it.walk_err(e, self.span))
    }

    /// Argument `i` as a number (num or dnum) in f64.
    pub fn f64(&self, i: usize) -> Exec<f64> {
        match self.value(i)? {
            Value::Num(x) => Ok(*x as f64),
            Value::Dnum(x) => Ok(*x),
            other => Err(self.it.type_bug(self.span, "num", other)),
        }
    }

    /// Argument `i` as a `num`.
    pub fn num(&self, i: usize) -> Exec<f32> {
        match self.value(i)? {
            Value::Num(x) => Ok(*x),
            Value::Dnum(x) => self.it.to_f32(*x, self.span),
            other => Err(self.it.type_bug(self.span, "num", other)),
        }
    }

    /// Optional numeric argument `i`.
    pub fn opt_f64(&self, i: usize) -> Exec<Option<f64>> {
        if self.present(i) {
            self.f64(i).map(Some)
        } else {
            Ok(None)
        }
    }

    /// Argument `i` as a bool.
    pub fn bool(&self, i: usize) -> Exec<bool> {
        match self.value(i)? {
            Value::Bool(b) => Ok(*b),
            other => Err(self.it.type_bug(self.span, "bool", other)),
        }
    }

    /// Argument `i` as text.
    pub fn str(&self, i: usize) -> Exec<&str> {
        match self.value(i)? {
            Value::Str(s) => Ok(s),
            other => Err(self.it.type_bug(self.span, "string", other)),
        }
    }

    /// Argument `i` as an integer (a number with an integer value), else `ERR_ARGVALERR`
    /// naming the parameter.
    pub fn int(&self, i: usize, what: &str) -> Exec<i64> {
        let x = self.f64(i)?;
        if x.fract() != 0.0 || !x.is_finite() {
            return Err(self.error(
                errnum::ERR_ARGVALERR,
                format!("{what} must be an integer, not {x}"),
            ));
        }
        Ok(x as i64)
    }

    /// Components of a record of numbers (pos, orient, …).
    pub fn nums<const N: usize>(&self, i: usize) -> Exec<[f64; N]> {
        let v = self.value(i)?;
        v.num_fields::<N>()
            .ok_or_else(|| self.it.type_bug(self.span, "record of numbers", v))
    }

    /// Write through reference argument `i` (INOUT/VAR/PERS).
    pub fn set(&mut self, i: usize, v: Value) -> Exec<()> {
        let place = match self.arg(i) {
            Some(NArg::Ref(r)) => r.clone(),
            _ => {
                return Err(self.it.fatal(
                    ErrorKind::Host,
                    self.span,
                    "internal error: writing a non-reference argument",
                ));
            }
        };
        self.it.store_abs(&place, v, self.span)
    }

    /// A string result, checked against the 80-character limit.
    pub fn string(&self, s: String) -> Exec<Value> {
        let n = s.chars().count();
        if n > MAX_STRING {
            return Err(self.error(
                errnum::ERR_STRTOOLNG,
                format!("the result would have {n} characters (at most {MAX_STRING})"),
            ));
        }
        Ok(Value::Str(s.into()))
    }

    /// A recoverable RAPID error at the call.
    pub fn error(&self, errno: i32, message: impl Into<String>) -> Unwind {
        self.it.error(errno, self.span, message)
    }

    /// "`Name` is not (yet) supported by rapidvc …" (not recoverable).
    pub fn unsupported(&self, why: &str) -> Unwind {
        let msg = if why.is_empty() {
            format!("`{}` is not supported by rapidvc", self.name())
        } else {
            format!("`{}` is not yet supported by rapidvc ({why})", self.name())
        };
        self.it.fatal(ErrorKind::Unsupported, self.span, msg)
    }

    /// A runtime-library failure as the RAPID error it names.
    pub fn rt(&self, e: crate::functions::RtError) -> Unwind {
        self.it.rt_error(e, self.span)
    }

    /// A `num` result computed in f64 (rounded to single precision, range-checked).
    pub fn num_result(&self, x: f64) -> Exec<Value> {
        crate::functions::math::num_from_f64(x)
            .map(Value::Num)
            .map_err(|e| self.rt(e))
    }

    /// The host.
    pub fn host(&mut self) -> &mut dyn Host {
        self.it.host.as_mut()
    }

    /// Map a host failure to a RAPID or fatal error at the call.
    pub fn host_err(&self, e: super::HostError) -> Unwind {
        self.it.host_error(e, self.span)
    }

    /// The current robot time.
    pub fn now(&self) -> RobotTime {
        self.it.host.now()
    }

    /// The current robot time in seconds (a RAPID `num`, e.g. for `ClkRead`).
    pub fn now_secs(&self) -> f64 {
        self.it.host.now().as_secs_f64()
    }

    /// Wait (in host time, running traps as interrupts arrive) until `cond` holds, polling it
    /// every `poll` seconds, or until `deadline`; true when `cond` held. For instructions that
    /// wait for the controller (the robot standing still, an EGM movement converging).
    pub fn wait_host(
        &mut self,
        deadline: Option<RobotTime>,
        poll: f64,
        mut cond: impl FnMut(&mut dyn Host) -> Result<bool, super::HostError>,
    ) -> Exec<bool> {
        let (p, span) = (self.p, self.span);
        let mut f = |it: &mut Interp, _: &Program| {
            cond(it.host.as_mut()).map_err(|e| it.host_error(e, span))
        };
        self.it.wait(p, span, deadline, Some(&mut f), poll)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn standard_registry_parses_and_has_no_duplicates() {
        let r = Registry::standard();
        let sigs = r.signatures();
        let mut names = std::collections::HashSet::new();
        for s in sigs.iter() {
            assert!(names.insert(s.name.to_ascii_uppercase()), "{}", s.name);
        }
        assert!(r.get("tpwrite").is_some());
        assert!(r.get("MoveJ").is_some());
    }
}
