//! The clock of a program with sockets: its peers are real processes, so `rapidvc run` runs
//! it in real time, as it does for an external EGM sensor (a note on stderr says so).

use crate::ir::{GlobalOrigin, Program, Ty, TypeId, TypeKind, TypeTable};

/// Whether one of the program's own modules declares socket data (`socketdev` data,
/// parameters, or records holding one): then it talks to real processes.
pub fn uses_sockets(prog: &Program) -> bool {
    let Some(socketdev) = prog.types.lookup("socketdev") else {
        return false;
    };
    let holds = |ty: &Ty| holds(&prog.types, ty.base, socketdev, 0);
    let own = |m: usize| prog.modules.get(m).is_some_and(|m| !m.stdlib);
    let global = prog.globals.iter().any(|g| match g.origin {
        GlobalOrigin::Module(m) => own(m.0 as usize) && holds(&g.ty),
        _ => false,
    });
    global
        || prog
            .routines
            .iter()
            .filter(|r| own(r.module.0 as usize))
            .any(|r| r.locals.iter().any(|l| holds(&l.ty)) || r.params.iter().any(|p| holds(&p.ty)))
}

/// Whether type `id` is `target` or a record with a component that holds it.
fn holds(types: &TypeTable, id: TypeId, target: TypeId, depth: u32) -> bool {
    let id = types.resolve(id);
    if id == target {
        return true;
    }
    // Records nest only a few levels; the bound guards against a malformed table.
    if depth > 32 {
        return false;
    }
    match &types.get(id).kind {
        TypeKind::Record { fields, .. } => fields
            .iter()
            .any(|f| holds(types, f.ty.base, target, depth + 1)),
        _ => false,
    }
}

/// The note when sockets switch the clock to real time (`None`: the clock was real anyway).
pub fn note(realtime_anyway: bool, lockstep: bool) -> Option<&'static str> {
    if realtime_anyway {
        None
    } else if lockstep {
        Some(
            "note: the program uses sockets, but --lockstep keeps virtual time: the robot's \
             clock stands still while a socket instruction waits",
        )
    } else {
        Some(
            "note: the program uses sockets, which talk to real processes: the clock runs in \
             real time",
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(text: &str) -> std::sync::Arc<Program> {
        let loaded =
            crate::program::load_texts([("t.mod", text)], crate::config::Config::default());
        loaded.program.expect("the program checks")
    }

    #[test]
    fn socket_data_anywhere_in_the_program_counts() {
        let plain = check("MODULE t\n  PROC main()\n    TPWrite \"x\";\n  ENDPROC\nENDMODULE\n");
        assert!(!uses_sockets(&plain));
        let global = check("MODULE t\n  VAR socketdev s;\n  PROC main()\n  ENDPROC\nENDMODULE\n");
        assert!(uses_sockets(&global));
        let local = check("MODULE t\n  PROC main()\n    VAR socketdev s;\n  ENDPROC\nENDMODULE\n");
        assert!(uses_sockets(&local));
        let record = check(
            "MODULE t\n  RECORD link\n    num n;\n    socketdev s;\n  ENDRECORD\n  VAR link l;\n  PROC main()\n  ENDPROC\nENDMODULE\n",
        );
        assert!(uses_sockets(&record));
        assert!(note(true, false).is_none());
        assert!(note(false, true).unwrap().contains("--lockstep"));
        assert!(note(false, false).unwrap().contains("real time"));
    }
}
