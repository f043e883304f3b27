//! The mass storage sandbox attacked from RAPID: a program run with `--home DIR` tries to
//! read, write, copy, rename and remove through `..`, absolute host paths and symbolic links
//! that point out of HOME. Every attempt must fail with the RAPID error ABB raises
//! (`ERR_FILEOPEN` from `Open`, `ERR_FILEACC` otherwise), and the directory outside HOME must
//! be exactly as it was: no file read (its access is not checked, its content is not shown),
//! none written, created, renamed or removed.

use rapidvc_testkit::rapidvc;
use rapidvc_testkit::sandbox::Attack;
use std::path::{Path, PathBuf};

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rapidvc-sandbox-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

const SECRET: &str = "secret: never to be read by RAPID";

/// The attacks: each line prints its label and the error it got (or `NO ERROR`).
fn program(outside: &Path) -> String {
    let abs = outside.join("secret.txt");
    let abs = abs.display();
    let attacks: Vec<(String, String)> = vec![
        ("read_dotdot".into(), r#"Open "HOME:/../outside/secret.txt", f \Read; s := ReadStr(f);"#.into()),
        ("read_dotdot_file".into(), r#"Open "HOME:" \File:="../outside/secret.txt", f \Read; s := ReadStr(f);"#.into()),
        ("read_absolute".into(), format!(r#"Open "{abs}", f \Read; s := ReadStr(f);"#)),
        ("read_root_absolute".into(), format!(r#"Open "HOME:" \File:="{abs}", f \Read; s := ReadStr(f);"#)),
        ("read_link_file".into(), r#"Open "HOME:/link.txt", f \Read; s := ReadStr(f);"#.into()),
        ("read_link_dir".into(), r#"Open "HOME:/out/secret.txt", f \Read; s := ReadStr(f);"#.into()),
        ("write_dotdot".into(), r#"Open "HOME:/../outside/new.txt", f \Write; Write f, "x"; Close f;"#.into()),
        ("write_link_dir".into(), r#"Open "$HOME/out/new.txt", f \Write; Write f, "x"; Close f;"#.into()),
        ("append_link_file".into(), r#"Open "HOME:/link.txt", f \Append; Write f, "x"; Close f;"#.into()),
        ("bin_link_file".into(), r#"Open "HOME:/link.txt", f \Bin; WriteStrBin f, "x"; Close f;"#.into()),
        ("backslash_dotdot".into(), r#"Open "HOME:\\..\\outside\\new.txt", f \Write; Close f;"#.into()),
        ("copy_out".into(), r#"CopyFile "HOME:/inside.txt", "HOME:/../outside/copy.txt";"#.into()),
        ("copy_in".into(), r#"CopyFile "HOME:/link.txt", "HOME:/stolen.txt";"#.into()),
        ("copy_via_dir".into(), r#"CopyFile "HOME:/out/secret.txt", "HOME:/stolen.txt";"#.into()),
        ("rename_out".into(), r#"RenameFile "HOME:/inside.txt", "HOME:/out/moved.txt";"#.into()),
        ("rename_in".into(), r#"RenameFile "HOME:/out/secret.txt", "HOME:/moved.txt";"#.into()),
        ("remove_via_dir".into(), r#"RemoveFile "HOME:/out/secret.txt";"#.into()),
        ("remove_dotdot".into(), r#"RemoveFile "$HOME/../outside/secret.txt";"#.into()),
        ("remove_link".into(), r#"RemoveFile "HOME:/link.txt";"#.into()),
        ("mkdir_out".into(), r#"MakeDir "HOME:/out/newdir";"#.into()),
        ("rmdir_out".into(), r#"RemoveDir "HOME:/../outside";"#.into()),
        ("list_out".into(), r#"OpenDir d, "HOME:/out"; WHILE ReadDir(d, s) DO TPWrite "listed " + s; ENDWHILE CloseDir d;"#.into()),
        ("list_parent".into(), r#"OpenDir d, "HOME:/.."; CloseDir d;"#.into()),
        ("size_out".into(), r#"n := FileSize("HOME:/out/secret.txt");"#.into()),
        ("time_out".into(), r#"n := FileTime("HOME:/../outside/secret.txt");"#.into()),
        ("isfile_out".into(), r#"IF IsFile("HOME:/out/secret.txt") TPWrite "exists";"#.into()),
        ("fssize_out".into(), format!(r#"n := FSSize("{abs}");"#)),
        ("unknown_root".into(), r#"Open "SYSTEM:/x", f \Write;"#.into()),
    ];
    let mut m = String::from(
        "MODULE attack\n  VAR iodev f;\n  VAR dir d;\n  VAR string s;\n  VAR num n;\n\n",
    );
    for (label, body) in &attacks {
        m.push_str(&format!(
            "  PROC {label}()\n    {body}\n    TPWrite \"{label}: NO ERROR\";\n  ERROR\n    \
             IF ERRNO = ERR_FILEOPEN TPWrite \"{label}: ERR_FILEOPEN\";\n    \
             IF ERRNO = ERR_FILEACC TPWrite \"{label}: ERR_FILEACC\";\n    \
             IF ERRNO <> ERR_FILEOPEN AND ERRNO <> ERR_FILEACC TPWrite \"{label}: other \" \\Num:=ERRNO;\n    \
             RETURN;\n  ENDPROC\n\n"
        ));
    }
    m.push_str("  PROC main()\n");
    m.push_str(
        "    Open \"HOME:/inside.txt\", f \\Write;\n    Write f, \"inside\";\n    Close f;\n",
    );
    for (label, _) in &attacks {
        m.push_str(&format!("    {label};\n"));
    }
    m.push_str("    TPWrite \"done\";\n  ENDPROC\nENDMODULE\n");
    m
}

#[cfg(unix)]
#[test]
fn no_path_leaves_home() {
    let attack = Attack::new("attack", "secret.txt", SECRET, "link.txt");
    let (home, outside) = (&attack.home, &attack.outside);
    let before = attack.snapshot_outside();
    let (stdout, stderr) = attack.run(rapidvc!(), &program(outside));
    assert!(!stdout.contains("NO ERROR"), "{stdout}");
    assert!(!stdout.contains("other"), "{stdout}");
    assert!(!stdout.contains("listed"), "{stdout}");
    assert!(!stdout.contains("exists"), "{stdout}");
    assert!(!stdout.contains("secret:"), "{stdout}");
    assert!(!stderr.contains("secret:"), "{stderr}");
    // Open refuses with ERR_FILEOPEN, everything else with ERR_FILEACC.
    for line in stdout.lines().filter(|l| l.contains(": ERR_")) {
        let label = line.split(':').next().unwrap_or("");
        let opens = [
            "read_",
            "write_",
            "append_",
            "bin_",
            "backslash",
            "unknown_root",
        ];
        let want = if opens.iter().any(|p| label.starts_with(p)) {
            "ERR_FILEOPEN"
        } else {
            "ERR_FILEACC"
        };
        assert!(line.ends_with(want), "{line}: expected {want}");
    }
    assert_eq!(stdout.lines().filter(|l| l.contains(": ERR_")).count(), 28);

    // Nothing outside HOME changed, the links are still there, nothing was stolen.
    assert_eq!(attack.snapshot_outside(), before);
    assert_eq!(
        std::fs::read_to_string(outside.join("secret.txt")).unwrap(),
        SECRET
    );
    assert!(
        std::fs::symlink_metadata(home.join("link.txt"))
            .unwrap()
            .is_symlink()
    );
    assert!(!home.join("stolen.txt").exists());
    assert!(!home.join("moved.txt").exists());
    assert_eq!(
        std::fs::read_to_string(home.join("inside.txt")).unwrap(),
        "inside\n"
    );
    // Only what the program wrote is in HOME (no temporary files left behind).
    let mut names: Vec<String> = std::fs::read_dir(home)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["inside.txt", "link.txt", "out"]);
}

#[test]
fn home_must_be_an_existing_directory() {
    let root = tmp("badhome");
    let prog = root.join("p.mod");
    std::fs::write(&prog, "MODULE p\n  PROC main()\n  ENDPROC\nENDMODULE\n").unwrap();
    for bad in [root.join("missing"), prog.clone()] {
        let out = rapidvc!()
            .arg("run")
            .arg("--home")
            .arg(&bad)
            .arg(&prog)
            .output()
            .expect("run rapidvc");
        assert_eq!(out.status.code(), Some(2));
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains("--home"), "{stderr}");
    }
    let _ = std::fs::remove_dir_all(&root);
}

/// Without `--home`, a run that uses the file system gets a fresh directory and says where;
/// one that does not makes none.
#[test]
fn default_home_is_fresh_and_printed() {
    let root = tmp("fresh");
    let prog = root.join("p.mod");
    std::fs::write(
        &prog,
        "MODULE p\n  VAR iodev f;\n  PROC main()\n    Open diskhome \\File:=\"a.txt\", f \\Write;\n    Write f, \"hi\";\n    Close f;\n  ENDPROC\nENDMODULE\n",
    )
    .unwrap();
    let out = rapidvc!()
        .arg("run")
        .arg(&prog)
        .current_dir(&root)
        .output()
        .expect("run rapidvc");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let line = stderr
        .lines()
        .find(|l| l.contains("mass storage: HOME: is "))
        .unwrap_or_else(|| panic!("no mass storage line in {stderr}"));
    let home = line
        .split("HOME: is ")
        .nth(1)
        .and_then(|r| r.split(", TEMP:").next())
        .expect("home path");
    let home = PathBuf::from(home);
    assert!(home.starts_with(std::env::temp_dir()), "{}", home.display());
    assert_eq!(std::fs::read_to_string(home.join("a.txt")).unwrap(), "hi\n");
    assert!(
        !root.join("a.txt").exists(),
        "nothing written into the working directory"
    );
    if let Some(base) = home.parent() {
        let _ = std::fs::remove_dir_all(base);
    }
    let _ = std::fs::remove_dir_all(&root);
}
