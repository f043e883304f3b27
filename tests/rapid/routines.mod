MODULE routines
  PERS num pcount := 0;
  VAR num vcount := 0;
  VAR num log{10};
  VAR num nlog := 0;

  PROC note(num v)
    nlog := nlog + 1;
    log{nlog} := v;
  ENDPROC

  PROC set_in(num v)
    note v;
  ENDPROC

  PROC set_inout(INOUT num v)
    v := v + 1;
  ENDPROC

  PROC set_var(VAR num v)
    v := 42;
  ENDPROC

  PROC set_pers(PERS num v)
    v := v + 100;
  ENDPROC

  FUNC num fact(num n)
    IF n <= 1 RETURN 1;
    RETURN n * fact(n - 1);
  ENDFUNC

  FUNC num opt(num a, \num b, \switch twice)
    VAR num r;
    r := a;
    IF Present(b) r := r + b;
    IF Present(twice) r := r * 2;
    RETURN r;
  ENDFUNC

  FUNC num which(\switch On | switch Off)
    IF Present(On) RETURN 1;
    IF Present(Off) RETURN 0;
    RETURN -1;
  ENDFUNC

  FUNC num pass_on(\num b, \switch twice)
    RETURN opt(1 \b?b \twice?twice);
  ENDFUNC

  FUNC num sum(num values{*})
    VAR num s := 0;
    FOR i FROM 1 TO Dim(values, 1) DO
      s := s + values{i};
    ENDFOR
    RETURN s;
  ENDFUNC

  PROC fill(INOUT num values{*})
    FOR i FROM 1 TO Dim(values, 1) DO
      values{i} := i * i;
    ENDFOR
  ENDPROC

  FUNC num fresh()
    VAR num n := 0;
    n := n + 1;
    RETURN n;
  ENDFUNC

  PROC late_target(num v)
    vcount := v;
  ENDPROC

  PROC test_parameter_modes()
    VAR num x := 1;
    VAR pos p := [0, 0, 0];
    set_in x;
    Assert x = 1;
    set_inout x;
    Assert x = 2;
    set_var x;
    Assert x = 42;
    set_var p.y;
    Assert p.y = 42 \Msg:="a component can be passed by reference";
    pcount := 1;
    set_pers pcount;
    Assert pcount = 101;
    set_inout pcount;
    Assert pcount = 102;
  ENDPROC

  PROC test_recursion()
    Assert fact(10) = 3628800;
  ENDPROC

  PROC test_optional_and_switches()
    Assert opt(1) = 1;
    Assert opt(1 \b:=2) = 3;
    Assert opt(1, \b:=2 \twice) = 6;
    Assert which(\On) = 1;
    Assert which(\Off) = 0;
    Assert which() = -1;
  ENDPROC

  PROC test_conditional_arguments()
    Assert pass_on() = 1;
    Assert pass_on(\b:=4) = 5;
    Assert pass_on(\b:=4 \twice) = 10;
  ENDPROC

  PROC test_named_same_object()
    VAR num b := 7;
    Assert opt(1 \b) = 8 \Msg:="a lone optional argument passes the data of the same name";
  ENDPROC

  PROC test_open_arrays()
    VAR num a{4} := [1, 2, 3, 4];
    VAR num q{3};
    Assert sum(a) = 10;
    fill q;
    Assert q{3} = 9;
    Assert sum(q) = 14;
  ENDPROC

  PROC test_routine_data_is_fresh()
    Assert fresh() = 1;
    Assert fresh() = 1;
  ENDPROC

  PROC test_late_binding()
    VAR string name := "late_target";
    %name% 5;
    Assert vcount = 5;
    %"routines:late_" + "target"% 6;
    Assert vcount = 6;
  ENDPROC

  PROC late_other(num v)
    vcount := -v;
  ENDPROC

  PROC test_late_binding_names_at_one_site()
    ! One call site calling several procedures by names in any case: each name finds
    ! its own procedure every time (what the site remembers keeps them apart).
    CONST string names{4} := ["late_target", "LATE_OTHER", "Late_Target", "late_other"];
    VAR num sum := 0;
    FOR k FROM 1 TO 8 DO
      %names{(k - 1) MOD 4 + 1}% k;
      sum := sum + vcount;
    ENDFOR
    Assert sum = 1 - 2 + 3 - 4 + 5 - 6 + 7 - 8;
  ENDPROC

  PROC test_late_binding_unknown()
    %"no_such_proc"%;
    Assert FALSE;
  ERROR
    Assert ERRNO = ERR_REFUNKPRC;
  ENDPROC

  PROC test_not_present_optional()
    VAR num r;
    r := bad_opt();
  ERROR
    Assert ERRNO = ERR_NOTPRES;
  ENDPROC

  PROC use_tool(PERS tooldata t, \PERS wobjdata w)
    Assert t.robhold;
    IF Present(w) Assert NOT w.robhold;
  ENDPROC

  PROC test_predefined_data_by_reference()
    use_tool tool0;
    use_tool tool0 \w:=wobj0;
    Assert tool0.tload.mass = 0.001;
  ENDPROC

  FUNC num bad_opt(\num b)
    RETURN b;
  ENDFUNC
ENDMODULE
