MODULE modules
  ! Program modules at run time. Each test writes the modules it loads into its own
  ! directory of HOME: (a fresh one per `rapidvc test`) and removes them. Where a test
  ! follows an example of the RAPID reference manual, the comment names it.
  VAR iodev f;
  VAR loadsession ls;
  VAR num calls := 0;
  VAR num remaining{5};
  VAR num tries := 0;
  VAR errnum seen := 0;

  ! Write a module file: `MODULE name` with the lines of `body` (separated by `|`), to
  ! HOME:/dir/file.
  PROC write_mod(string dir, string file, string name, string body)
    VAR num at := 1;
    VAR num bar;
    IF NOT IsFile("HOME:/" + dir \Directory) MakeDir "HOME:/" + dir;
    Open "HOME:/" + dir \File:=file, f \Write;
    Write f, "MODULE " + name;
    WHILE at <= StrLen(body) DO
      bar := StrFind(body, at, "|");
      Write f, StrPart(body, at, bar - at);
      at := bar + 1;
    ENDWHILE
    Write f, "ENDMODULE";
    Close f;
  ENDPROC

  PROC count_call()
    calls := calls + 1;
  ENDPROC

  ! Load: "Load \Dynamic, diskhome \File:="PART_A.MOD";" then the loaded routine is called
  ! by late binding; UnLoad takes it away again (ERR_REFUNKPRC).
  PROC test_load_late_binding_unload()
    VAR errnum err := 0;
    write_mod "t_load", "PART_A.MOD", "part_a", "VAR num a_count:=40;|PROC part_a_run()|a_count:=a_count+2;|count_call;|ENDPROC";
    Assert NOT ModExist("part_a");
    Load \Dynamic, diskhome \File:="t_load/PART_A.MOD";
    Assert ModExist("part_a");
    %"part_a_run"%;
    %"part_a:part_a_run"%;
    Assert calls = 2;
    UnLoad diskhome \File:="t_load/PART_A.MOD";
    Assert NOT ModExist("part_a");
    %"part_a_run"%;
    Assert err = ERR_REFUNKPRC;
    RemoveFile "HOME:/t_load/PART_A.MOD";
    RemoveDir "HOME:/t_load";
  ERROR
    err := ERRNO;
    TRYNEXT;
  ENDPROC

  ! Loading twice is ERR_LOADED; a missing file ERR_FILNOTFND; a syntax error ERR_SYNTAX; an
  ! unknown name ERR_LINKREF.
  PROC test_load_errors()
    VAR errnum err := 0;
    write_mod "t_lerr", "ok.mod", "lerr_ok", "  PROC lerr_ok_run()|  ENDPROC";
    write_mod "t_lerr", "syntax.mod", "lerr_syntax", "  PROC broken(|  ENDPROC";
    write_mod "t_lerr", "link.mod", "lerr_link", "  PROC uses_unknown()|    no_such_routine;|  ENDPROC";
    Load "HOME:/t_lerr/ok.mod";
    Load "HOME:/t_lerr/ok.mod";
    Assert err = ERR_LOADED;
    err := 0;
    Load "HOME:/t_lerr/missing.mod";
    Assert err = ERR_FILNOTFND;
    err := 0;
    Load "HOME:/t_lerr/syntax.mod";
    Assert err = ERR_SYNTAX;
    Assert NOT ModExist("lerr_syntax");
    err := 0;
    Load "HOME:/t_lerr" \File:="link.mod";
    Assert err = ERR_LINKREF;
    Assert NOT ModExist("lerr_link");
    err := 0;
    ! Paths may not leave the mass storage.
    Load "HOME:/../outside.mod";
    Assert err = ERR_FILEACC;
    UnLoad "HOME:/t_lerr/ok.mod";
    err := 0;
    UnLoad "HOME:/t_lerr/ok.mod";
    Assert err = ERR_UNLOAD;
    RemoveFile "HOME:/t_lerr/ok.mod";
    RemoveFile "HOME:/t_lerr/syntax.mod";
    RemoveFile "HOME:/t_lerr/link.mod";
    RemoveDir "HOME:/t_lerr";
  ERROR
    err := ERRNO;
    TRYNEXT;
  ENDPROC

  ! StartLoad/WaitLoad: "StartLoad \Dynamic, diskhome \File:="PART_B.MOD", load1; …
  ! WaitLoad load1;" then the data of the loaded module initialised and reached by name.
  PROC test_startload_waitload()
    VAR errnum err := 0;
    VAR num got;
    write_mod "t_sl", "PART_B.MOD", "part_b", "VAR num b_value:=7;|PROC part_b_run()|b_value:=b_value*3;|ENDPROC";
    write_mod "t_sl", "PART_C.MOD", "part_c", "  PROC part_c_run()|    count_call;|  ENDPROC";
    StartLoad \Dynamic, diskhome \File:="t_sl/PART_B.MOD", ls;
    WaitLoad ls;
    %"part_b_run"%;
    GetDataVal "b_value", got;
    Assert got = 21;
    ! The session ended: waiting again is ERR_LOADNO_NOUSE.
    WaitLoad ls;
    Assert err = ERR_LOADNO_NOUSE;
    ! WaitLoad \UnloadPath: unload B, then link C.
    StartLoad "HOME:/t_sl/PART_C.MOD", ls;
    WaitLoad \UnloadPath:="HOME:/t_sl/PART_B.MOD", ls;
    Assert NOT ModExist("part_b");
    Assert ModExist("part_c");
    calls := 0;
    CallByVar "part_c_ru", 0;
    Assert err = ERR_REFUNKPRC;
    %"part_c_run"%;
    Assert calls = 1;
    EraseModule "part_c";
    Assert NOT ModExist("part_c");
    RemoveFile "HOME:/t_sl/PART_B.MOD";
    RemoveFile "HOME:/t_sl/PART_C.MOD";
    RemoveDir "HOME:/t_sl";
  ERROR
    err := ERRNO;
    TRYNEXT;
  ENDPROC

  ! CancelLoad ends a session without loading; a cancelled session is not in use any more.
  PROC test_cancelload()
    VAR errnum err := 0;
    write_mod "t_cl", "PART_D.MOD", "part_d", "  PROC part_d_run()|  ENDPROC";
    StartLoad "HOME:/t_cl/PART_D.MOD", ls;
    CancelLoad ls;
    Assert NOT ModExist("part_d");
    CancelLoad ls;
    Assert err = ERR_LOADNO_NOUSE;
    RemoveFile "HOME:/t_cl/PART_D.MOD";
    RemoveDir "HOME:/t_cl";
  ERROR
    err := ERRNO;
    TRYNEXT;
  ENDPROC

  ! Save writes a loaded module back; ModTime is the time of the file it was loaded from;
  ! EraseModule of an unknown module is ERR_MODULE.
  PROC test_save_modtime_erase()
    VAR errnum err := 0;
    VAR string line;
    write_mod "t_save", "part_e.mod", "part_e", "  PROC part_e_run()|  ENDPROC";
    Load "HOME:/t_save/part_e.mod";
    Assert ModTime("part_e") = FileTime("HOME:/t_save/part_e.mod" \ModifyTime);
    Save "part_e" \FilePath:="HOME:/t_save/copy.mod";
    Open "HOME:/t_save/copy.mod", f \Read;
    line := ReadStr(f);
    Close f;
    Assert line = "MODULE part_e";
    EraseModule "part_e";
    EraseModule "part_e";
    Assert err = ERR_MODULE;
    err := 0;
    line := ValToStr(ModTime("no_such_module"));
    Assert err = ERR_MODULE;
    ! The loaded copy is the same module again.
    Load "HOME:/t_save/copy.mod";
    Assert ModExist("part_e");
    UnLoad \Save, "HOME:/t_save/copy.mod";
    CheckProgRef;
    RemoveFile "HOME:/t_save/part_e.mod";
    RemoveFile "HOME:/t_save/copy.mod";
    RemoveDir "HOME:/t_save";
  ERROR
    err := ERRNO;
    TRYNEXT;
  ENDPROC

  ! Save writes a module with the current values of its persistents, as a controller does,
  ! and UnLoad \ErrIfChanged refuses (ERR_NOTSAVED, the module stays) while they differ from
  ! the values loaded or last saved.
  PROC test_save_current_pers()
    VAR errnum err := 0;
    VAR string line;
    write_mod "t_pers", "cell.mod", "cell", "PERS num cn := 1;|PERS string cs;|PROC cb()|cn := cn + 5;|cs := ""ok"";|ENDPROC";
    Load "HOME:/t_pers/cell.mod";
    UnLoad \ErrIfChanged, "HOME:/t_pers/cell.mod";
    Assert err = 0 \Msg:="nothing changed: UnLoad with ErrIfChanged unloads";
    Assert NOT ModExist("cell");
    Load "HOME:/t_pers/cell.mod";
    %"cb"%;
    UnLoad \ErrIfChanged, "HOME:/t_pers/cell.mod";
    Assert err = ERR_NOTSAVED;
    Assert ModExist("cell");
    err := 0;
    Save "cell" \FilePath:="HOME:/t_pers/cell.mod";
    Open "HOME:/t_pers/cell.mod", f \Read;
    line := ReadStr(f);
    Assert line = "MODULE cell";
    line := ReadStr(f);
    Assert line = "PERS num cn := 6;";
    line := ReadStr(f);
    Assert line = "PERS string cs := ""ok"";";
    line := ReadStr(f);
    Assert line = "PROC cb()" \Msg:="the code stays as it was";
    Close f;
    UnLoad \ErrIfChanged, "HOME:/t_pers/cell.mod";
    Assert err = 0 \Msg:="saved: UnLoad with ErrIfChanged unloads";
    Assert NOT ModExist("cell");
    ! Loaded again it starts from the saved values; UnLoad \Save writes the new ones.
    Load "HOME:/t_pers/cell.mod";
    %"cb"%;
    UnLoad \Save, "HOME:/t_pers/cell.mod";
    Open "HOME:/t_pers/cell.mod", f \Read;
    line := ReadStr(f);
    line := ReadStr(f);
    Close f;
    Assert line = "PERS num cn := 11;";
    RemoveFile "HOME:/t_pers/cell.mod";
    RemoveDir "HOME:/t_pers";
  ERROR
    err := ERRNO;
    TRYNEXT;
  ENDPROC

  ! A module cannot unload itself while its routine runs (ERR_UNLOAD); the loaded module
  ! reaches this module's data, and a runtime error in it is handled by its caller here.
  PROC test_unload_running_module()
    VAR errnum err := 0;
    write_mod "t_self", "self.mod", "self_mod", "PROC self_unload()|UnLoad ""HOME:/t_self/self.mod"";|ERROR|seen := ERRNO;|ENDPROC";
    Load "HOME:/t_self/self.mod";
    seen := 0;
    %"self_unload"%;
    Assert seen = ERR_UNLOAD;
    Assert ModExist("self_mod");
    UnLoad "HOME:/t_self/self.mod";
    RemoveFile "HOME:/t_self/self.mod";
    RemoveDir "HOME:/t_self";
  ERROR
    err := ERRNO;
    TRYNEXT;
  ENDPROC

  PROC proc1()
    calls := calls + 1;
  ENDPROC

  PROC proc2()
    calls := calls + 10;
  ENDPROC

  PROC proc3(num x)
  ENDPROC

  ! CallByVar: "reg1 := ...; CallByVar "proc", reg1;" calls proc1 or proc2 by number.
  PROC test_callbyvar()
    VAR errnum err := 0;
    calls := 0;
    CallByVar "proc", 1;
    CallByVar "proc", 2;
    Assert calls = 11;
    CallByVar "proc", 9;
    Assert err = ERR_REFUNKPRC;
    err := 0;
    CallByVar "proc", 3;
    Assert err = ERR_CALLPROC;
  ERROR
    err := ERRNO;
    TRYNEXT;
  ENDPROC

  ! RemainingRetries: the handler RETRYs while retries are left (4 by default), then gives
  ! up with TRYNEXT (the manual's example: "IF RemainingRetries() > 0 THEN RETRY; ELSE
  ! TRYNEXT;").
  PROC test_remaining_retries()
    VAR num x := 0;
    tries := 0;
    Assert RemainingRetries() = 4;
    x := 1 / 0;
    Assert tries = 5;
    Assert remaining{1} = 4 AND remaining{2} = 3 AND remaining{5} = 0;
  ERROR
    tries := tries + 1;
    remaining{tries} := RemainingRetries();
    IF RemainingRetries() > 0 THEN
      RETRY;
    ELSE
      TRYNEXT;
    ENDIF
  ENDPROC
ENDMODULE
