//! Build script: compiles `proto/egm.proto` into prost types with protox (pure Rust), so a
//! plain `cargo build` never needs a system `protoc`.

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("cargo:rerun-if-changed=proto/egm.proto");
    // Tests that drive third-party software run only where it is installed: `cargo test`
    // on a fresh machine reports them as ignored (with the reason), and CI (`.ci/run`), which
    // installs the software and exports the variable first, runs them with the same command.
    println!("cargo::rustc-check-cfg=cfg(rapidvc_python)");
    println!("cargo:rerun-if-env-changed=RAPIDVC_PYTHON");
    if std::env::var_os("RAPIDVC_PYTHON").is_some_and(|v| !v.is_empty()) {
        println!("cargo:rustc-cfg=rapidvc_python");
    }
    // The same for the browser tests of the view pages (tests/view_browser.rs): Chromium.
    println!("cargo::rustc-check-cfg=cfg(rapidvc_chromium)");
    println!("cargo:rerun-if-env-changed=RAPIDVC_CHROMIUM");
    if std::env::var_os("RAPIDVC_CHROMIUM").is_some_and(|v| !v.is_empty()) {
        println!("cargo:rustc-cfg=rapidvc_chromium");
    }
    let fds = protox::compile(["egm.proto"], ["proto"])?;
    // proto2 repeated doubles stay unpacked (one tag per value), as ABB's encoder and every
    // tested client write them; prost-build follows the descriptor's labels.
    prost_build::Config::new().compile_fds(fds)?;
    Ok(())
}
