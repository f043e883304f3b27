//! Build script: compiles `proto/egm.proto` into prost types with protox (pure Rust), so a
//! plain `cargo build` never needs a system `protoc`.

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("cargo:rerun-if-changed=proto/egm.proto");
    let fds = protox::compile(["egm.proto"], ["proto"])?;
    let mut config = prost_build::Config::new();
    // Repeated doubles go on the wire unpacked, one tag per value, as ABB's own encoder and
    // every tested client do (proto2's default; prost follows the descriptor).
    config.compile_fds(fds)?;
    Ok(())
}
