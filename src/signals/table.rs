//! The shared signal table: definitions, a case-insensitive name index and lock-free value cells.

use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};

use super::{IoError, SignalDef, builtin_signals};

/// A signal's index in its [`SignalTable`]; valid only for the table that returned it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SignalId(u32);

impl SignalId {
    /// The index.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// One signal's value (`f64` bits) and change counter.
#[derive(Debug)]
struct Cell {
    value: AtomicU64,
    generation: AtomicU64,
}

/// All signals of a controller. Share it as `Arc<SignalTable>`: reads and writes go through
/// atomics, so the motion/EGM thread reads analog values every cycle without a lock.
#[derive(Debug)]
pub struct SignalTable {
    defs: Vec<SignalDef>,
    index: HashMap<String, SignalId>,
    cells: Vec<Cell>,
    total: AtomicU64,
}

fn key(name: &str) -> String {
    name.to_lowercase()
}

impl SignalTable {
    /// A table of `defs`, every signal at its default. Fails on an invalid definition or a
    /// name defined twice (case-insensitive).
    pub fn new(defs: Vec<SignalDef>) -> Result<SignalTable, IoError> {
        let mut index = HashMap::with_capacity(defs.len());
        for (i, d) in defs.iter().enumerate() {
            d.validate()?;
            let id = SignalId(u32::try_from(i).map_err(|_| IoError::InvalidDefinition {
                name: d.name.clone(),
                reason: "too many signals".into(),
            })?);
            if index.insert(key(&d.name), id).is_some() {
                return Err(IoError::DuplicateSignal {
                    name: d.name.clone(),
                });
            }
        }
        let cells = defs
            .iter()
            .map(|d| Cell {
                value: AtomicU64::new((d.default + 0.0).to_bits()),
                generation: AtomicU64::new(0),
            })
            .collect();
        Ok(SignalTable {
            defs,
            index,
            cells,
            total: AtomicU64::new(0),
        })
    }

    /// A table of only the [`builtin_signals`].
    pub fn with_builtins() -> SignalTable {
        // The built-in definitions are valid and distinct (a unit test checks it); an empty
        // table is the fallback that can never fail.
        SignalTable::new(builtin_signals()).unwrap_or_else(|_| SignalTable {
            defs: Vec::new(),
            index: HashMap::new(),
            cells: Vec::new(),
            total: AtomicU64::new(0),
        })
    }

    /// Number of signals.
    pub fn len(&self) -> usize {
        self.defs.len()
    }

    /// True when no signal is defined.
    pub fn is_empty(&self) -> bool {
        self.defs.is_empty()
    }

    /// Every signal with its id, in definition order.
    pub fn iter(&self) -> impl Iterator<Item = (SignalId, &SignalDef)> {
        self.defs
            .iter()
            .enumerate()
            .map(|(i, d)| (SignalId(i as u32), d))
    }

    /// The id of the signal called `name` (case-insensitive).
    pub fn lookup(&self, name: &str) -> Option<SignalId> {
        self.index.get(&key(name)).copied()
    }

    /// Like [`SignalTable::lookup`], with an [`IoError::UnknownSignal`] for a missing name.
    pub fn lookup_or_err(&self, name: &str) -> Result<SignalId, IoError> {
        self.lookup(name).ok_or_else(|| IoError::UnknownSignal {
            name: name.to_string(),
        })
    }

    /// The definition of a signal.
    pub fn def(&self, id: SignalId) -> Option<&SignalDef> {
        self.defs.get(id.index())
    }

    /// The current logical value (one atomic load).
    pub fn value(&self, id: SignalId) -> Option<f64> {
        self.cells
            .get(id.index())
            .map(|c| f64::from_bits(c.value.load(Ordering::Acquire)))
    }

    /// The number of changes of this signal so far.
    pub fn generation(&self, id: SignalId) -> Option<u64> {
        self.cells
            .get(id.index())
            .map(|c| c.generation.load(Ordering::Acquire))
    }

    /// The number of changes of all signals so far (a cheap "did anything change?" poll).
    pub fn total_generation(&self) -> u64 {
        self.total.load(Ordering::Acquire)
    }

    /// Set a logical value after checking it against the signal's range (see the module
    /// doc for the errors). The interpreter calls this for outputs; a simulator may set
    /// inputs the same way. Returns whether the value changed.
    pub fn set(&self, id: SignalId, value: f64) -> Result<bool, IoError> {
        let (Some(def), Some(cell)) = (self.defs.get(id.index()), self.cells.get(id.index()))
        else {
            return Err(IoError::UnknownSignal {
                name: format!("#{}", id.index()),
            });
        };
        def.check_value(value)?;
        let bits = (value + 0.0).to_bits();
        let old = cell.value.swap(bits, Ordering::AcqRel);
        if old != bits {
            cell.generation.fetch_add(1, Ordering::AcqRel);
            self.total.fetch_add(1, Ordering::AcqRel);
            Ok(true)
        } else {
            Ok(false)
        }
    }

    /// Set every signal back to its default (program start); changed signals count as
    /// changes.
    pub fn reset(&self) {
        for (def, cell) in self.defs.iter().zip(&self.cells) {
            let bits = (def.default + 0.0).to_bits();
            if cell.value.swap(bits, Ordering::AcqRel) != bits {
                cell.generation.fetch_add(1, Ordering::AcqRel);
                self.total.fetch_add(1, Ordering::AcqRel);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;
    use std::sync::atomic::AtomicBool;

    use super::super::{SignalKind, merge_defs};
    use super::*;

    fn table() -> SignalTable {
        SignalTable::new(vec![
            SignalDef::digital("do_Grip", SignalKind::Do),
            SignalDef::digital("di_Part", SignalKind::Di).with_default(1.0),
            SignalDef::analog("ao_Speed", SignalKind::Ao, -10.0, 10.0),
            SignalDef::group("go_Prog", SignalKind::Go, 4),
            SignalDef::group("gi_Wide", SignalKind::Gi, 32),
            SignalDef::analog("ai_Unset", SignalKind::Ai, 0.0, 0.0),
        ])
        .unwrap()
    }

    #[test]
    fn lookup_is_case_insensitive_and_o1() {
        let t = table();
        let id = t.lookup("DO_GRIP").unwrap();
        assert_eq!(t.lookup("do_grip"), Some(id));
        assert_eq!(t.def(id).unwrap().name, "do_Grip");
        assert_eq!(t.lookup("nope"), None);
        assert_eq!(
            t.lookup_or_err("nope").unwrap_err().to_string(),
            "I/O signal `nope` is not defined (define it in EIO.cfg)"
        );
        assert_eq!(t.len(), 6);
        assert!(!t.is_empty());
        assert_eq!(t.iter().nth(2).unwrap().1.name, "ao_Speed");
    }

    #[test]
    fn defaults_and_set() {
        let t = table();
        let di = t.lookup("di_Part").unwrap();
        let dout = t.lookup("do_Grip").unwrap();
        assert_eq!(t.value(di), Some(1.0));
        assert_eq!(t.value(dout), Some(0.0));
        assert_eq!(t.set(dout, 1.0), Ok(true));
        assert_eq!(t.set(dout, 1.0), Ok(false));
        assert_eq!(t.value(dout), Some(1.0));
        assert_eq!(t.generation(dout), Some(1));
        let ao = t.lookup("ao_Speed").unwrap();
        assert_eq!(t.set(ao, -10.0), Ok(true));
        assert_eq!(t.set(ao, 2.5), Ok(true));
        assert_eq!(t.value(ao), Some(2.5));
        let go = t.lookup("go_Prog").unwrap();
        assert_eq!(t.set(go, 15.0), Ok(true));
        let gi = t.lookup("gi_Wide").unwrap();
        assert_eq!(t.set(gi, 4_294_967_295.0), Ok(true));
        assert_eq!(t.total_generation(), 5);
        t.reset();
        assert_eq!(t.value(dout), Some(0.0));
        assert_eq!(t.value(go), Some(0.0));
        assert_eq!(t.value(di), Some(1.0));
        assert_eq!(t.total_generation(), 9);
        assert_eq!(t.generation(dout), Some(2));
    }

    #[test]
    fn range_errors_leave_the_value() {
        let t = table();
        let ao = t.lookup("ao_Speed").unwrap();
        t.set(ao, 1.0).unwrap();
        let e = t.set(ao, 10.5).unwrap_err();
        assert_eq!(e.err_name(), Some("ERR_AO_LIM"));
        assert_eq!(
            e.to_string(),
            "value 10.5 is outside the logical range -10..10 of analog signal `ao_Speed`"
        );
        assert_eq!(t.value(ao), Some(1.0));
        let unset = t.lookup("ai_Unset").unwrap();
        assert_eq!(t.set(unset, 0.0), Ok(false));
        assert_eq!(
            t.set(unset, 0.1).unwrap_err().err_name(),
            Some("ERR_AO_LIM")
        );
        let go = t.lookup("go_Prog").unwrap();
        for bad in [16.0, -1.0, 1.5] {
            let e = t.set(go, bad).unwrap_err();
            assert_eq!(e.err_name(), Some("ERR_GO_LIM"), "{bad}");
        }
        assert_eq!(
            t.set(go, 16.0).unwrap_err().to_string(),
            "value 16 does not fit group signal `go_Prog`: it takes an integer 0..15 (4 bits)"
        );
        let dout = t.lookup("do_Grip").unwrap();
        let e = t.set(dout, 2.0).unwrap_err();
        assert_eq!(e.err_name(), Some("ERR_ARGVALERR"));
        assert_eq!(
            e.to_string(),
            "value 2 is not allowed for DO signal `do_Grip`: a digital signal takes 0 or 1"
        );
        assert_eq!(
            t.set(ao, f64::NAN).unwrap_err().err_name(),
            Some("ERR_ARGVALERR")
        );
        assert_eq!(t.total_generation(), 1);
        // -0 is stored as 0 (no spurious change).
        let ao_id = t.lookup("ao_Speed").unwrap();
        t.set(ao_id, 0.0).unwrap();
        assert_eq!(t.set(ao_id, -0.0), Ok(false));
    }

    #[test]
    fn invalid_tables() {
        let dup = SignalTable::new(vec![
            SignalDef::digital("a", SignalKind::Do),
            SignalDef::digital("A", SignalKind::Di),
        ]);
        assert_eq!(
            dup.unwrap_err(),
            IoError::DuplicateSignal { name: "A".into() }
        );
        let reversed = SignalTable::new(vec![SignalDef::analog("x", SignalKind::Ao, 5.0, 1.0)]);
        assert_eq!(
            reversed.unwrap_err().to_string(),
            "I/O signal `x`: MinLog 5 is greater than MaxLog 1"
        );
        let bad_default = SignalTable::new(vec![
            SignalDef::analog("y", SignalKind::Ao, 0.0, 1.0).with_default(3.0),
        ]);
        assert!(bad_default.unwrap_err().err_name().is_none());
        for bits in [0, 33] {
            let g = SignalTable::new(vec![SignalDef::group("g", SignalKind::Gi, bits)]);
            assert!(
                matches!(g, Err(IoError::InvalidDefinition { .. })),
                "{bits}"
            );
        }
        let empty = SignalTable::new(vec![SignalDef::digital("", SignalKind::Do)]);
        assert!(matches!(empty, Err(IoError::InvalidDefinition { .. })));
    }

    #[test]
    fn builtins_and_merge() {
        let t = SignalTable::with_builtins();
        assert_eq!(t.len(), 6);
        for n in [
            "ao_MoveX", "AO_MOVEY", "ao_movez", "ao_RotX", "ao_RotY", "ao_RotZ",
        ] {
            let id = t.lookup(n).unwrap();
            let d = t.def(id).unwrap();
            assert_eq!(d.kind, SignalKind::Ao);
            assert!(d.min_log <= -20.0 && d.max_log >= 1320.0);
        }
        // The manual's example values.
        let y = t.lookup("ao_MoveY").unwrap();
        assert_eq!(t.set(y, 1320.0), Ok(true));
        let merged = merge_defs(
            builtin_signals(),
            vec![
                SignalDef::analog("AO_MOVEX", SignalKind::Ao, 0.0, 5.0),
                SignalDef::digital("do1", SignalKind::Do),
            ],
        );
        assert_eq!(merged.len(), 7);
        assert_eq!(merged[0].name, "AO_MOVEX");
        assert_eq!(merged[0].max_log, 5.0);
        assert_eq!(merged[6].name, "do1");
    }

    #[test]
    fn kinds_and_scaling() {
        for k in ["di", "DO", "Ai", "ao", "GI", "go"] {
            let kind = SignalKind::parse(k).unwrap();
            assert_eq!(kind.as_str(), k.to_ascii_uppercase());
            assert_eq!(
                kind.rapid_type(),
                format!("signal{}", k.to_ascii_lowercase())
            );
        }
        assert_eq!(SignalKind::parse("DX"), None);
        assert!(SignalKind::Do.is_output() && !SignalKind::Gi.is_output());
        assert!(SignalKind::Di.is_digital() && SignalKind::Ao.is_analog());
        assert!(SignalKind::Go.is_group());
        let mut d = SignalDef::analog("a", SignalKind::Ao, 0.0, 100.0);
        d.min_phys = 4.0;
        d.max_phys = 20.0;
        assert_eq!(d.physical(50.0), 12.0);
        assert_eq!(SignalDef::digital("d", SignalKind::Do).physical(1.0), 1.0);
        assert_eq!(SignalDef::group("g", SignalKind::Go, 8).group_max(), 255);
    }

    /// One writer toggles a DO and sweeps an AO while readers poll values and generations:
    /// readers only ever see valid values and non-decreasing generations, and the final
    /// counts match the writes.
    #[test]
    fn concurrent_readers_and_writer() {
        const N: u64 = 20_000;
        let t = Arc::new(table());
        let dout = t.lookup("do_Grip").unwrap();
        let ao = t.lookup("ao_Speed").unwrap();
        let done = AtomicBool::new(false);
        std::thread::scope(|s| {
            for _ in 0..2 {
                let t = Arc::clone(&t);
                let done = &done;
                s.spawn(move || {
                    let mut last = 0;
                    let mut reads = 0u64;
                    while !done.load(Ordering::Acquire) || reads < 1000 {
                        let g = t.generation(dout).unwrap();
                        assert!(g >= last);
                        last = g;
                        let v = t.value(dout).unwrap();
                        assert!(v == 0.0 || v == 1.0);
                        let a = t.value(ao).unwrap();
                        assert!((-10.0..=10.0).contains(&a));
                        reads += 1;
                    }
                });
            }
            for i in 0..N {
                t.set(dout, (i % 2 == 0) as u8 as f64).unwrap();
                t.set(ao, (i % 21) as f64 - 10.0).unwrap();
            }
            done.store(true, Ordering::Release);
        });
        assert_eq!(t.generation(dout), Some(N));
        assert_eq!(t.value(dout), Some(0.0));
        assert_eq!(t.generation(ao), Some(N));
        assert_eq!(t.total_generation(), 2 * N);
    }
}
