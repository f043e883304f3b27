//! Modules loaded and saved at run time stay inside the controller's mass storage: a program
//! run with `--home DIR` tries to `Load`, `StartLoad`, `Save` and `UnLoad \Save` through
//! `..`, absolute host paths and symbolic links that point out of HOME. Every attempt fails
//! with `ERR_FILEACC` (a host path written after `HOME:` is a path inside HOME, not found),
//! no module from outside joins the program, and the directory outside HOME is exactly as
//! it was.

use rapidvc_testkit::rapidvc;
use rapidvc_testkit::sandbox::Attack;
use std::path::Path;

const OUTSIDE_MODULE: &str = "MODULE stolen\n  PROC stolen_run()\n  ENDPROC\nENDMODULE\n";

fn program(outside: &Path) -> String {
    let abs = outside.join("stolen.mod");
    let abs = abs.display();
    let dir = outside.display();
    let attacks: Vec<(&str, String)> = vec![
        (
            "load_dotdot",
            r#"Load "HOME:/../outside/stolen.mod";"#.into(),
        ),
        (
            "load_dotdot_file",
            r#"Load "HOME:" \File:="../outside/stolen.mod";"#.into(),
        ),
        ("load_absolute", format!(r#"Load "{abs}";"#)),
        (
            "load_root_absolute",
            format!(r#"Load "HOME:" \File:="{abs}";"#),
        ),
        ("load_link_file", r#"Load "HOME:/link.mod";"#.into()),
        ("load_link_dir", r#"Load "HOME:/out/stolen.mod";"#.into()),
        (
            "startload_link_dir",
            r#"StartLoad "HOME:/out/stolen.mod", ls;"#.into(),
        ),
        (
            "save_dotdot",
            r#"Save "mine" \FilePath:="HOME:/../outside/mine.mod";"#.into(),
        ),
        (
            "save_link_dir",
            r#"Save "mine" \FilePath:="HOME:/out/mine.mod";"#.into(),
        ),
        (
            "save_link_file",
            r#"Save "mine" \FilePath:="HOME:/link.mod";"#.into(),
        ),
        (
            "save_absolute",
            format!(r#"Save "mine" \FilePath:="{dir}/mine.mod";"#),
        ),
        (
            "unload_save_link",
            r#"UnLoad \Save, "HOME:/out/stolen.mod";"#.into(),
        ),
    ];
    let mut m = String::from("MODULE attack\n  VAR loadsession ls;\n  VAR iodev f;\n\n");
    for (label, body) in &attacks {
        m.push_str(&format!(
            "  PROC {label}()\n    {body}\n    TPWrite \"{label}: NO ERROR\";\n  ERROR\n    \
             IF ERRNO = ERR_FILEACC TPWrite \"{label}: ERR_FILEACC\";\n    \
             IF ERRNO = ERR_FILNOTFND TPWrite \"{label}: ERR_FILNOTFND\";\n    \
             IF ERRNO <> ERR_FILEACC AND ERRNO <> ERR_FILNOTFND TPWrite \"{label}: other \" \\Num:=ERRNO;\n    \
             RETURN;\n  ENDPROC\n\n"
        ));
    }
    m.push_str("  PROC main()\n");
    // A module of its own in HOME, loaded the ordinary way, to be saved by the attacks.
    m.push_str(
        "    Open \"HOME:/mine.mod\", f \\Write;\n    Write f, \"MODULE mine\";\n    \
         Write f, \"ENDMODULE\";\n    Close f;\n    Load \"HOME:/mine.mod\";\n",
    );
    for (label, _) in &attacks {
        m.push_str(&format!("    {label};\n"));
    }
    m.push_str(
        "    IF ModExist(\"stolen\") TPWrite \"stolen loaded\";\n    TPWrite \"done\";\n  \
         ENDPROC\nENDMODULE\n",
    );
    m
}

#[cfg(unix)]
#[test]
fn no_module_comes_from_or_goes_out_of_home() {
    let attack = Attack::new("modules", "stolen.mod", OUTSIDE_MODULE, "link.mod");
    let home = &attack.home;
    let before = attack.snapshot_outside();
    let (stdout, _) = attack.run(rapidvc!(), &program(&attack.outside));
    for bad in ["NO ERROR", "other", "stolen loaded"] {
        assert!(!stdout.contains(bad), "{stdout}");
    }
    // An absolute host path after `HOME:` names a file inside HOME (which does not exist).
    assert!(
        stdout.contains("load_root_absolute: ERR_FILNOTFND"),
        "{stdout}"
    );
    let refused = stdout.lines().filter(|l| l.ends_with(": ERR_FILEACC"));
    assert_eq!(refused.count(), 11, "{stdout}");
    assert_eq!(attack.snapshot_outside(), before);
    assert_eq!(
        std::fs::read_to_string(home.join("mine.mod")).unwrap(),
        "MODULE mine\nENDMODULE\n"
    );
    assert!(
        std::fs::symlink_metadata(home.join("link.mod"))
            .unwrap()
            .is_symlink()
    );
}
