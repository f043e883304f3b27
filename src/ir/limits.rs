//! How much data a RAPID task may hold, counted in values: a `num`, `dnum`, `bool` or
//! `string` is one value, a record holds the values of its components (a `pos` 3, a
//! `robtarget` 17) and an array those of its elements ([`crate::ir::TypeTable::values`]).
//!
//! A controller keeps a task's program and data in a few megabytes of RAPID memory; real
//! programs hold thousands of values, a large one some hundred thousand. rapidvc keeps
//! every value in 24 bytes (plus the text of strings), so the limits below keep a task
//! under about 50 MB of data while no real program comes near them. Sizes known before
//! the program runs are checked by the semantic pass (a declaration, the module data, one
//! routine's data with the module data); the data of routines running at the same time
//! (recursion, large arrays passed by value) is checked at each call, which raises
//! [`ERR_DATA_LIMIT`](crate::ir::errnum::ERR_DATA_LIMIT) at the call.

/// The most values one declaration (module or routine data) may hold.
pub const MAX_DECL_VALUES: u64 = 1_000_000;

/// The most values a task may hold at once: all module data plus the data and value
/// parameters of every routine call in progress.
pub const MAX_TASK_VALUES: u64 = 2_000_000;

/// `n` with thousands separators (`1,000,000`), for messages about these limits.
pub fn thousands(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thousands_separators() {
        assert_eq!(thousands(0), "0");
        assert_eq!(thousands(999), "999");
        assert_eq!(thousands(1000), "1,000");
        assert_eq!(thousands(MAX_DECL_VALUES), "1,000,000");
        assert_eq!(thousands(u64::MAX), "18,446,744,073,709,551,615");
    }
}
