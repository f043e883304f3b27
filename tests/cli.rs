//! The command line as a user sees it: exit codes, human and JSON output of `rapidvc check`
//! (trycmd cases in `tests/cli/*.toml`).

#[test]
fn cli() {
    trycmd::TestCases::new().case("tests/cli/*.toml");
}
