//! Build script: compiles `proto/egm.proto` into prost types with protox (pure Rust), so a
//! plain `cargo build` never needs a system `protoc`.

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("cargo:rerun-if-changed=proto/egm.proto");
    let fds = protox::compile(["egm.proto"], ["proto"])?;
    // proto2 repeated doubles stay unpacked (one tag per value), as ABB's encoder and every
    // tested client write them; prost-build follows the descriptor's labels.
    prost_build::Config::new().compile_fds(fds)?;
    Ok(())
}
