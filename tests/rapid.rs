//! RAPID self-tests: `rapidvc test tests/rapid` must pass every `PROC test_*`.

use rapidvc_testkit::rapidvc;

#[test]
fn rapid_self_tests_pass() {
    let out = rapidvc!()
        .args(["test", "tests/rapid"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("run rapidvc test");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "rapidvc test failed:\n{stdout}\n{stderr}"
    );
    let last = stdout.lines().last().unwrap_or("");
    assert!(last.ends_with(" passed, 0 failed"), "{last}");
    let passed: usize = last
        .split(' ')
        .next()
        .and_then(|n| n.parse().ok())
        .unwrap_or(0);
    assert!(passed >= 60, "only {passed} RAPID tests ran");
}

#[test]
fn failing_tests_are_reported_with_location() {
    let dir = std::env::temp_dir().join(format!("rapidvc-selftest-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("failing.mod");
    std::fs::write(
        &file,
        "MODULE failing\n  PROC test_one()\n    Assert 1 = 2 \\Msg:=\"one is not two\";\n  ENDPROC\n  PROC test_two()\n  ENDPROC\nENDMODULE\n",
    )
    .unwrap();
    let out = rapidvc!()
        .arg("test")
        .arg(&file)
        .output()
        .expect("run rapidvc test");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(stdout.contains("test_one ... FAILED"), "{stdout}");
    assert!(
        stdout.contains("failing.mod:3:5: assertion failed: one is not two"),
        "{stdout}"
    );
    assert!(stdout.contains("test_two ... ok"), "{stdout}");
    assert!(stdout.ends_with("1 passed, 1 failed\n"), "{stdout}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The modules loaded at run time and the data search run the same on the tree-walking
/// engine (the whole suite runs on both in `interp_agree`; these change the program while
/// it runs, so they are run here on the reference engine too).
#[test]
fn module_tests_pass_on_the_tree_walker() {
    let out = rapidvc!()
        .args([
            "test",
            "tests/rapid/modules.mod",
            "tests/rapid/data_search.mod",
            "tests/rapid/file_rawbytes.mod",
        ])
        .env("RAPIDVC_ENGINE", "tree-walk")
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("run rapidvc test");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}");
    assert!(stdout.ends_with("15 passed, 0 failed\n"), "{stdout}");
}
