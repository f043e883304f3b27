//! Fuzz the RAPID front end: any bytes, decoded as the loader does, must parse (with or
//! without diagnostics) and render without panicking, overflowing the stack or hanging.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rapidvc::diag::Diagnostics;
use rapidvc::source::{SourceMap, decode_bytes};

fuzz_target!(|data: &[u8]| {
    let text = decode_bytes(data);
    let mut map = SourceMap::new();
    let id = map.add("fuzz.mod", text.clone());
    let mut diags = Diagnostics::new();
    let file = rapidvc::parse::parse_file(id, &text, &mut diags);
    rapidvc::parse::check_structure(&file, &mut diags);
    let _ = file.dump();
    let _ = diags.render_plain(&map, 80);
    let _ = diags.to_json(&map);
});
