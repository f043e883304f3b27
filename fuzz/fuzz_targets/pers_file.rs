//! Fuzz the `--pers` file reader: any text is read or refused without panicking; a text it
//! reads is rewritten byte for byte when the program declares nothing, and rewritten with new
//! values for every stored name it reads back to those values, the other lines kept.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rapidvc::interp::Value;
use rapidvc::interp::pers::{self, PersValue};

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let Ok(entries) = pers::parse(&text) else {
        return;
    };
    assert_eq!(pers::write(Some(&text), &[]), text);
    let values: Vec<PersValue> = entries
        .iter()
        .map(|e| PersValue {
            name: e.name.clone(),
            ty: "num".into(),
            dims: Vec::new(),
            task: false,
            value: Value::Num(7.0),
        })
        .collect();
    let rewritten = pers::write(Some(&text), &values);
    let again = pers::parse(&rewritten).expect("a rewritten file reads back");
    assert_eq!(again.len(), entries.len());
    for e in &again {
        assert_eq!(e.raw.split(" := ").nth(1).map(|v| v.starts_with("7;")), Some(true));
    }
});
