//! A generator of large, valid RAPID programs mixing every construct the parser handles, for
//! the throughput benchmark and the large-file tests. Deterministic: same size, same text.

/// A valid RAPID file of at least `min_bytes` bytes (several modules are not needed: one
/// module with many routines and declarations). It passes the semantic check too when the
/// digital output `doGripper` is configured (see `benches/check_memory.rs`).
pub fn program(min_bytes: usize) -> String {
    let mut s = String::with_capacity(min_bytes + 4096);
    s.push_str("%%%\r\n  VERSION:1\r\n  LANGUAGE:ENGLISH\r\n%%%\r\n");
    s.push_str("! Generated benchmark program: every construct, CRLF line ends.\r\n");
    s.push_str("MODULE BenchMod(SYSMODULE, NOSTEPIN)\r\n");
    s.push_str("  RECORD benchrec\r\n    num count; ! a counter\r\n    pos where;\r\n    string label;\r\n  ENDRECORD\r\n");
    s.push_str("  ALIAS num benchnum;\r\n");
    s.push_str("  LOCAL CONST num table{2,3} := [[1,2,3],[4,5,6]];\r\n");
    s.push_str("  TASK PERS tooldata tBench:=[TRUE,[[12.3313,-0.108707,416.142],[0.903899,-0.00320735,0.427666,0.00765917]],[2.6,[-111.1,24.6,386.6],[1,0,0,0],0,0,0.072]];\r\n");
    s.push_str("  VAR intnum irBench;\r\n  VAR benchrec rec;\r\n  VAR num cycle := 0;\r\n");
    s.push_str("  VAR num counter := 0;\r\n  TRAP trapBench\r\n    RETURN;\r\n  ENDTRAP\r\n");
    s.push_str(
        "  CONST jointtarget jHome:=[[0,0,0,0,30,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];\r\n",
    );
    let mut i = 0usize;
    while s.len() < min_bytes {
        // Real programs are mostly target declarations and motion calls; every few blocks
        // also holds a routine with every other construct.
        typical(&mut s, i);
        if i.is_multiple_of(3) {
            block(&mut s, i);
        }
        i += 1;
    }
    s.push_str("ENDMODULE\r\n");
    s
}

/// Targets and a motion routine, the way taught programs look.
fn typical(s: &mut String, i: usize) {
    for k in 0..8 {
        s.push_str(&format!(
            "  PERS robtarget t{i}_{k}:=[[{}.{},-{}.{},{}.{}],[0.0356{k},-0.7062{k},0.7061,-0.0364],[-1,0,-1,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];\r\n",
            500 + (i * 7 + k) % 900, k, (i * 13) % 400, k + 1, 200 + k * 25, i % 10
        ));
    }
    s.push_str(&format!(
        "  PROC path{i}()\r\n    MoveAbsJ jHome\\NoEOffs, v1000, z50, tBench;\r\n"
    ));
    for k in 0..8 {
        let (instr, zone) = if k % 3 == 0 {
            ("MoveJ", "z50")
        } else {
            ("MoveL", "z10")
        };
        s.push_str(&format!(
            "    {instr} t{i}_{k}, v500, {zone}, tBench\\WObj:=wobj0;\r\n"
        ));
        if k == 3 {
            s.push_str("    SetDO doGripper, 1;\r\n    WaitTime 0.25;\r\n");
        }
    }
    s.push_str(&format!(
        "    MoveL Offs(t{i}_7, 0, 0, 50), v200, fine, tBench\\WObj:=wobj0;\r\n    TPWrite \"Cycle \"\\Num:=cycle;\r\n  ENDPROC\r\n"
    ));
}

/// One routine (and data) with every construct.
fn block(s: &mut String, i: usize) {
    let x = (i * 37) % 1000;
    let y = (i * 53) % 600;
    // Data: robtargets with aggregates and exponent literals, as controllers write them.
    for k in 0..4 {
        s.push_str(&format!(
            "  CONST robtarget p{i}_{k}:=[[{}.5,{}.25,{}],[0.000494947,0.662278,-0.749217,-0.00783173],[0,0,-1,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];\r\n",
            x + k,
            y,
            300 + k * 10
        ));
    }
    s.push_str(&format!("  LOCAL VAR num counter{i} := {};\r\n  PERS string name{i} := \"item \"\"{i}\"\" \\41\";\r\n", i % 7));
    // A procedure with every parameter form and most statements.
    s.push_str(&format!(
        "  PROC work{i}(num n, \\switch Fast | switch Slow, INOUT num vals{{*}}, \\num speed \\string msg)\r\n"
    ));
    s.push_str("    VAR num j := 0;\r\n    VAR pos delta;\r\n");
    s.push_str(&format!(
        "    MoveJ p{i}_0, v1000, z50, tBench\\WObj:=wobj0;\r\n"
    ));
    s.push_str(&format!(
        "    MoveL Offs(p{i}_1, 0, 0, -10), v100, fine, tBench;\r\n"
    ));
    s.push_str(&format!(
        "    MoveL p{i}_2, v200, z10, tBench \\WObj:=wobj0; ! approach\r\n"
    ));
    s.push_str("    delta := [n * 2 + 1, -n / 3, (n - 1) DIV 2];\r\n");
    s.push_str("    rec.where.x := rec.where.x + delta.x * -1;\r\n");
    s.push_str("    vals{1} := vals{Dim(vals, 1)} MOD 4;\r\n");
    s.push_str(
        "    IF NOT n > 0 AND Present(Slow) THEN\r\n      TPWrite \"fast \" + msg \\Num:=n;\r\n",
    );
    s.push_str("    ELSEIF n = -1 OR n >= 100 THEN\r\n      j := j + 1;\r\n    ELSE\r\n      WaitTime (0.5);\r\n    ENDIF\r\n");
    s.push_str("    IF j <> 0 j := 0;\r\n");
    s.push_str("    WHILE j < n DO\r\n      j := j + 1;\r\n    ENDWHILE\r\n");
    s.push_str(
        "    FOR k FROM 1 TO 10 STEP 2 DO\r\n      counter := counter + k * .5;\r\n    ENDFOR\r\n",
    );
    s.push_str("    TEST j\r\n    CASE 1, 2, 3:\r\n      Stop;\r\n    CASE 4:\r\n      GOTO done;\r\n    DEFAULT:\r\n      j := -1;\r\n    ENDTEST\r\n");
    s.push_str("    done:\r\n");
    s.push_str("    %\"work\" + NumToStr(n, 0)% n;\r\n");
    s.push_str(&format!("    work{i} n, \\Fast?Fast, vals;\r\n"));
    s.push_str("    CONNECT irBench WITH trapBench;\r\n");
    s.push_str("  ERROR (ERR_DIVZERO, 41)\r\n    IF ERRNO = ERR_DIVZERO THEN\r\n      TRYNEXT;\r\n    ENDIF\r\n    RETRY;\r\n");
    s.push_str("  ENDPROC\r\n");
    s.push_str(&format!(
        "  LOCAL FUNC num calc{i}(num a, \\num b)\r\n    IF Present(b) RETURN a * b + 1.5E-3;\r\n    RETURN Abs(a) + Sqrt(a * a + 9E+09) - 0xFF;\r\n  ENDFUNC\r\n"
    ));
    if i.is_multiple_of(10) {
        s.push_str(&format!(
            "  TRAP trap{i}\r\n    EXIT;\r\n  ERROR\r\n    RAISE;\r\n  ENDTRAP\r\n"
        ));
    }
}
