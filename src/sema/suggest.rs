//! "Did you mean" for undeclared data names, with bounded work.
//!
//! A suggestion is the visible name closest to the undeclared one (case-insensitive
//! Levenshtein distance at most [`MAX_DISTANCE`]; among equally close names, the routine's
//! parameters first, then module data in declaration order). Comparing every undeclared name
//! with every known name is quadratic: a broken file with 100,000 undeclared names and as many
//! declarations took hours. So:
//!
//! * only names whose length differs by at most [`MAX_DISTANCE`] are compared (the known
//!   names are indexed by length at the first undeclared name);
//! * the answer for a name is kept per module (a misspelt name is usually misspelt often);
//! * the comparisons of one check are capped at [`MAX_COMPARISONS`]; past that, undeclared
//!   names are still reported, without a suggestion.
//!
//! Real programs never come near the cap, so their messages are exactly what comparing every
//! name gives.

use std::collections::HashMap;

use crate::ir::{Global, GlobalOrigin, ModuleId};

/// The largest edit distance a suggestion may have.
const MAX_DISTANCE: usize = 2;

/// Name comparisons one check may spend on suggestions (about a second of work).
pub(super) const MAX_COMPARISONS: u64 = 4_000_000;

/// The index of known names and what was spent so far.
#[derive(Default)]
pub(super) struct Suggester {
    /// Indices of globals by the length (in chars) of their name.
    by_len: Vec<Vec<u32>>,
    /// How many globals `by_len` holds (it is rebuilt when globals were added since).
    indexed: usize,
    /// The closest global found for an upper-cased name in a module: (distance, index).
    cache: HashMap<(ModuleId, String), Option<(usize, u32)>>,
    /// Comparisons made so far.
    spent: u64,
    /// Rows of the distance table (kept between calls).
    rows: (Vec<usize>, Vec<usize>),
}

impl Suggester {
    /// The name to suggest for the upper-cased `key`, written in module `module`, among the
    /// routine's `params` (names as declared) and the visible `globals`; `None` when nothing
    /// is close enough, or the work for suggestions is spent.
    pub(super) fn suggest(
        &mut self,
        key: &str,
        module: ModuleId,
        params: &[&str],
        globals: &[Global],
    ) -> Option<String> {
        let len = key.chars().count();
        let mut best: Option<(usize, &str)> = None;
        for &p in params {
            if let Some(Some(d)) = self.distance(key, len, p)
                && best.is_none_or(|(bd, _)| d < bd)
            {
                best = Some((d, p));
            }
        }
        let global = self.closest_global(key, len, module, globals);
        if let Some((d, gi)) = global
            && best.is_none_or(|(bd, _)| d < bd)
        {
            best = globals.get(gi as usize).map(|g| (d, g.name.as_str()));
        }
        best.map(|(_, n)| n.to_string())
    }

    /// The closest visible global (distance, index), the first in declaration order among
    /// equally close ones.
    fn closest_global(
        &mut self,
        key: &str,
        len: usize,
        module: ModuleId,
        globals: &[Global],
    ) -> Option<(usize, u32)> {
        if let Some(found) = self.cache.get(&(module, key.to_string())) {
            return *found;
        }
        if self.indexed != globals.len() {
            self.index(globals);
        }
        let mut best: Option<(usize, u32)> = None;
        let lens = len.saturating_sub(MAX_DISTANCE)..=len + MAX_DISTANCE;
        for l in lens {
            let Some(bucket) = self.by_len.get(l) else {
                continue;
            };
            for k in 0..bucket.len() {
                let gi = self.by_len[l][k];
                let Some(g) = globals.get(gi as usize) else {
                    continue;
                };
                let visible = match g.origin {
                    GlobalOrigin::Module(gm) => !g.local || gm == module,
                    _ => true,
                };
                if !visible {
                    continue;
                }
                let Some(d) = self.distance(key, len, &g.name)? else {
                    continue;
                };
                if best.is_none_or(|b| (d, gi) < b) {
                    best = Some((d, gi));
                }
            }
        }
        // (Not reached when the work ran out: `?` above returns without a cached answer.)
        self.cache.insert((module, key.to_string()), best);
        best
    }

    fn index(&mut self, globals: &[Global]) {
        self.by_len.clear();
        // (Answers found among fewer globals may no longer be the closest.)
        self.cache.clear();
        for (i, g) in globals.iter().enumerate() {
            let l = g.name.chars().count();
            if self.by_len.len() <= l {
                self.by_len.resize_with(l + 1, Vec::new);
            }
            self.by_len[l].push(i as u32);
        }
        self.indexed = globals.len();
    }

    /// `Some(Some(d))`: `name` is `d` ≤ [`MAX_DISTANCE`] edits from `key` (`len` chars,
    /// upper case); `Some(None)`: farther; `None`: the work for suggestions is spent.
    fn distance(&mut self, key: &str, len: usize, name: &str) -> Option<Option<usize>> {
        if self.spent >= MAX_COMPARISONS {
            return None;
        }
        self.spent += 1;
        if name.chars().count().abs_diff(len) > MAX_DISTANCE {
            return Some(None);
        }
        let d = edit_distance(key, name, &mut self.rows);
        Some((d <= MAX_DISTANCE).then_some(d))
    }
}

/// Levenshtein distance between `a` and `b`, letters compared without case (ASCII); `rows`
/// are scratch rows reused between calls.
fn edit_distance(a: &str, b: &str, rows: &mut (Vec<usize>, Vec<usize>)) -> usize {
    let (prev, cur) = rows;
    prev.clear();
    prev.extend(0..=b.chars().count());
    for (i, ca) in a.chars().enumerate() {
        cur.clear();
        cur.push(i + 1);
        for (j, cb) in b.chars().enumerate() {
            let same = ca.eq_ignore_ascii_case(&cb);
            let v = (prev[j] + usize::from(!same))
                .min(prev[j + 1] + 1)
                .min(cur[j] + 1);
            cur.push(v);
        }
        std::mem::swap(prev, cur);
    }
    prev.last().copied().unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::Ty;
    use crate::source::Span;

    fn global(name: &str, module: u32, local: bool) -> Global {
        Global {
            name: name.into(),
            origin: GlobalOrigin::Module(ModuleId(module)),
            local,
            task: false,
            storage: crate::ast::Storage::Var,
            ty: Ty::NUM,
            dims: Vec::new(),
            init: None,
            span: Span::default(),
        }
    }

    #[test]
    fn distances() {
        let mut rows = Default::default();
        assert_eq!(edit_distance("COUNTER", "counter", &mut rows), 0);
        assert_eq!(edit_distance("COUNTR", "counter", &mut rows), 1);
        assert_eq!(edit_distance("CUONTER", "counter", &mut rows), 2);
        assert_eq!(edit_distance("", "abc", &mut rows), 3);
        assert_eq!(edit_distance("ABC", "", &mut rows), 3);
    }

    #[test]
    fn closest_first_declared_params_before_data_and_local_data_only_in_its_module() {
        let globals = [
            global("speedB", 0, false),
            global("speedA", 0, false),
            global("speed", 1, true),
        ];
        let mut s = Suggester::default();
        // Two names one edit away: the first declared.
        assert_eq!(
            s.suggest("SPEEDC", ModuleId(0), &[], &globals).as_deref(),
            Some("speedB")
        );
        // `speed` is LOCAL to module 1: exact there, invisible from module 0.
        assert_eq!(
            s.suggest("SPEE", ModuleId(1), &[], &globals).as_deref(),
            Some("speed")
        );
        assert_eq!(
            s.suggest("SPEE", ModuleId(0), &[], &globals).as_deref(),
            Some("speedB")
        );
        // A parameter as close as data wins.
        assert_eq!(
            s.suggest("SPEEDC", ModuleId(0), &["speedX"], &globals)
                .as_deref(),
            Some("speedX")
        );
        assert_eq!(s.suggest("ELSEWHERE", ModuleId(0), &[], &globals), None);
    }

    #[test]
    fn no_suggestion_once_the_work_is_spent() {
        let globals: Vec<Global> = (0..1000)
            .map(|i| global(&format!("v{i}"), 0, false))
            .collect();
        let mut s = Suggester::default();
        assert_eq!(
            s.suggest("V1X", ModuleId(0), &[], &globals).as_deref(),
            Some("v1")
        );
        s.spent = MAX_COMPARISONS;
        // Cached: still answered.
        assert_eq!(
            s.suggest("V1X", ModuleId(0), &[], &globals).as_deref(),
            Some("v1")
        );
        assert_eq!(s.suggest("V2X", ModuleId(0), &[], &globals), None);
    }
}
